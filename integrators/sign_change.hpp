#pragma once
// Narrowing a sign change of a scalar function g on [lo, hi] to a bracket of width tol: the root
// location used by SteppingIntegrator. Secant steps on the two latest points (superlinear near a
// simple root), kept inside the bracket and at least tol/2 from its ends, so that once a point
// lands within tol/2 of the root the next one straddles it (doubling that step while g stays
// exactly at its value, a plateau at the old sign); bisection whenever two evaluations did not
// halve the bracket. An optional first guess (e.g. from an interpolant that costs nothing to
// evaluate) saves the first, coarse steps, and an estimate of g' there (from the same interpolant)
// turns the first step into a Newton step instead of a secant through a far end of the bracket.
// An optional `refine`, called after each evaluation with the bracket and the point just evaluated,
// may return a better estimate of the root than the secant's (NaN: none), e.g. from a model that
// the evaluation has just made more accurate; it takes the secant's place as the next trial.
#include <functional>
#include <limits>

namespace contact {

struct SignChange {
  double lo, g_lo;  // g has its old sign at lo (strictly: g_lo != 0)
  double hi, g_hi;  // g is zero or has the new sign at hi
  int evals = 0;    // evaluations of g spent narrowing
};

// Narrows `b` until hi - lo <= tol or max_evals evaluations are spent (then the bracket is wider
// but still valid). Requires g_lo != 0 and g_hi zero or of the other sign.
SignChange narrow_sign_change(const std::function<double(double)>& g, SignChange b, double tol,
                              double guess = std::numeric_limits<double>::quiet_NaN(), int max_evals = 200,
                              double guess_slope = std::numeric_limits<double>::quiet_NaN(),
                              const std::function<double(const SignChange&, double)>& refine = {});

}  // namespace contact
