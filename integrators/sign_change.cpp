#include "sign_change.hpp"

#include <cmath>
#include <stdexcept>

namespace contact {

SignChange narrow_sign_change(const std::function<double(double)>& g, SignChange b, double tol, double guess,
                              int max_evals, double guess_slope,
                              const std::function<double(const SignChange&, double)>& refine) {
  if (!(b.g_lo != 0 && b.g_lo * b.g_hi <= 0) || !(b.lo < b.hi))
    throw std::invalid_argument("narrow_sign_change: [lo, hi] does not bracket a sign change");
  const double old_sign = b.g_lo > 0 ? 1.0 : -1.0;
  const auto secant = [](double x0, double g0, double x1, double g1) {
    return x1 - g1 * (x1 - x0) / (g1 - g0);
  };
  // The first trial: the guess if it lies inside, else the secant (regula falsi) of the ends.
  double x = guess > b.lo && guess < b.hi ? guess : secant(b.lo, b.g_lo, b.hi, b.g_hi);
  double x_prev = NAN, g_prev = NAN;
  double step_last = b.hi - b.lo, step_before = step_last;  // Brent's test: steps must shrink
  while (b.hi - b.lo > tol && b.evals < max_evals) {
    if (!(x > b.lo && x < b.hi)) x = 0.5 * (b.lo + b.hi);
    x = std::fmin(std::fmax(x, b.lo + 0.5 * tol), b.hi - 0.5 * tol);
    const double gx = g(x);
    ++b.evals;
    const bool at_lo = gx * old_sign > 0;  // x becomes the bracket's lower or upper end
    (at_lo ? b.lo : b.hi) = x;
    (at_lo ? b.g_lo : b.g_hi) = gx;
    // The secant through x and the latest other point (at first, the far end of the bracket).
    double next;
    if (b.evals == 1 && x == guess && std::isfinite(guess_slope) && guess_slope != 0) {
      next = x - gx / guess_slope;
    } else if (std::isfinite(x_prev) && gx != g_prev) {
      next = secant(x_prev, g_prev, x, gx);
    } else {
      const double xe = at_lo ? b.hi : b.lo, ge = at_lo ? b.g_hi : b.g_lo;
      next = gx != ge ? secant(xe, ge, x, gx) : NAN;
    }
    // (Not where the secant already lands within tol/2: the closing step needs no model.)
    if (refine && b.hi - b.lo > tol && !(std::abs(next - x) < 0.5 * tol)) {
      const double better = refine(b, x);
      if (std::isfinite(better)) next = better;
    }
    double step = next - x;
    // (The ends themselves are fine: a secant through an exact zero returns that zero, and the
    // tol/2 step below then closes the bracket from its side.)
    if (!(next >= b.lo && next <= b.hi) || std::abs(step) >= 0.5 * std::abs(step_before)) {
      next = 0.5 * (b.lo + b.hi);  // outside, or not converging: bisect
      step = next - x;
    } else if (std::abs(step) < 0.5 * tol) {
      // Within tol/2 of the root by the secant's estimate: step tol/2 into the bracket, so
      // that the next point crosses the root and closes the bracket.
      step = at_lo ? 0.5 * tol : -0.5 * tol;
      next = x + step;
    }
    step_before = step_last;
    step_last = step;
    x_prev = x;
    g_prev = gx;
    x = next;
  }
  return b;
}

}  // namespace contact
