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
  // The nudge across the secant's root: tol/2, doubled each time the last one landed on the same
  // side again with g unchanged, on a plateau at its old sign: a gap computed from positions of
  // 200 m is exactly zero (the touch offset, 1e-150, at the old sign) for 3e-14 s before its root,
  // and nudges of tol/2 crept across it, 2300 for the event-driven wedge's tol: the narrowing gave
  // up at 200 returning the step's end, and the impact was taken 45 us late, 3.9e-5 m deep.
  // Doubling crosses a plateau of width w in log2(w / tol) evaluations. Where g moved, the secant
  // was merely a little off and the next tol/2 closes the bracket, as before (bisecting there
  // doubled the right-hand sides of GSL's RK8PD runs, whose every trial is a re-step; doubling
  // there too added up to 3 %).
  double nudge = 0.0;  // the last step's nudge, signed; 0: the last step was no nudge
  bool nudged_from_lo = false;
  while (b.hi - b.lo > tol && b.evals < max_evals) {
    if (!(x > b.lo && x < b.hi)) x = 0.5 * (b.lo + b.hi);
    x = std::fmin(std::fmax(x, b.lo + 0.5 * tol), b.hi - 0.5 * tol);
    const double gx = g(x);
    ++b.evals;
    const bool at_lo = gx * old_sign > 0;  // x becomes the bracket's lower or upper end
    const bool on_plateau = nudge != 0.0 && at_lo == nudged_from_lo && gx == g_prev;
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
    const double last_nudge = nudge;
    nudge = 0.0;
    if (!(next >= b.lo && next <= b.hi) || std::abs(step) >= 0.5 * std::abs(step_before)) {
      next = 0.5 * (b.lo + b.hi);  // outside, or not converging: bisect
      step = next - x;
    } else if (std::abs(step) < 0.5 * tol) {
      // Within tol/2 of the root by the secant's estimate: step tol/2 into the bracket, so
      // that the next point crosses the root and closes the bracket.
      step = on_plateau ? 2 * last_nudge : at_lo ? 0.5 * tol : -0.5 * tol;
      next = x + step;
      nudge = step;
      nudged_from_lo = at_lo;
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
