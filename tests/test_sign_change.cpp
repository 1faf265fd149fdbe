// The root narrowing behind SteppingIntegrator (integrators/sign_change.hpp): it must return a
// valid bracket no wider than the tolerance around the first sign change, converge superlinearly
// on smooth functions (the point of replacing Brent's method), and stay bounded on functions where
// secant steps are useless.
#include "sign_change.hpp"
#include "unit_roundoff.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

using contact::narrow_sign_change;
using contact::SignChange;

namespace {

SignChange bracket(const std::function<double(double)>& g, double lo, double hi) {
  return {lo, g(lo), hi, g(hi)};
}

// The bracket holds the sign change: old sign strictly at lo, new sign or zero at hi.
void expect_valid(const SignChange& b, const std::function<double(double)>& g, double old_sign) {
  EXPECT_GT(g(b.lo) * old_sign, 0);
  EXPECT_LE(g(b.hi) * old_sign, 0);
  EXPECT_LT(b.lo, b.hi);
}

}  // namespace

TEST(SignChange, SmoothRootToTolerance) {
  const auto g = [](double t) { return std::cos(t) - t; };  // root 0.7390851332151607
  const double tol = 100 * kEps;
  const auto b = narrow_sign_change(g, bracket(g, 0, 1), tol);
  expect_valid(b, g, 1);
  EXPECT_LE(b.hi - b.lo, tol);
  EXPECT_NEAR(b.hi, 0.7390851332151607, tol);
  // Bisection needs log2(1 / tol) = 46 evaluations; secant steps (order 1.6) about a fifth.
  EXPECT_LE(b.evals, 10);
}

TEST(SignChange, AGoodGuessSavesTheCoarseSteps) {
  const auto g = [](double t) { return std::cos(t) - t; };
  const double tol = 100 * kEps, root = 0.7390851332151607;
  const auto cold = narrow_sign_change(g, bracket(g, 0, 1), tol);
  const auto warm = narrow_sign_change(g, bracket(g, 0, 1), tol, root + 1e-6);
  expect_valid(warm, g, 1);
  EXPECT_LE(warm.hi - warm.lo, tol);
  EXPECT_NEAR(warm.hi, root, tol);
  // From 1e-6 the secant needs ~3 steps to reach 1e-14 (errors 1e-6, ~1e-7, ~1e-11, < 1e-14)
  // and one tol/2 step to close the bracket.
  EXPECT_LE(warm.evals, 5);
  EXPECT_LT(warm.evals, cold.evals);
}

TEST(SignChange, ASlopeAtTheGuessMakesTheFirstStepNewtons) {
  // With g' at the guess known to 1 %, the first step is Newton's (error 1e-6 -> 1e-8) instead of
  // a secant through the far end of the bracket; the secant on the two latest points then
  // reaches 1e-14 in one step: one evaluation fewer than from the guess alone.
  const auto g = [](double t) { return std::cos(t) - t; };
  const double tol = 100 * kEps, root = 0.7390851332151607, guess = root + 1e-6;
  const double slope = -(std::sin(guess) + 1) * 1.01;
  const auto warm = narrow_sign_change(g, bracket(g, 0, 1), tol, guess);
  const auto newton = narrow_sign_change(g, bracket(g, 0, 1), tol, guess, 200, slope);
  expect_valid(newton, g, 1);
  EXPECT_LE(newton.hi - newton.lo, tol);
  EXPECT_NEAR(newton.hi, root, tol);
  EXPECT_LT(newton.evals, warm.evals);
}

TEST(SignChange, ConvexFunctionDoesNotStallOnOneSide) {
  // Regula falsi keeps one end fixed on a convex function and converges linearly; the secant
  // on the latest points with Brent's step test must not.
  const auto g = [](double t) { return std::exp(t) - 2; };
  const double tol = 100 * kEps * 10;
  const auto b = narrow_sign_change(g, bracket(g, 0, 10), tol);
  expect_valid(b, g, -1);
  EXPECT_LE(b.hi - b.lo, tol);
  EXPECT_NEAR(b.hi, std::log(2.0), tol);
  EXPECT_LE(b.evals, 25);  // bisection: log2(10 / tol) = 46
}

TEST(SignChange, DiscontinuityIsBracketedInBisectionCount) {
  // A jump: secant steps carry no information, so the safeguard must bisect. Brent's test
  // allows at most one failed secant per halving: <= 2 log2(width / tol) + 2 evaluations.
  const double r = 1.0 / 3.0;
  const auto g = [r](double t) { return t < r ? -1.0 : 2.0; };
  const double tol = 1e-12;
  const auto b = narrow_sign_change(g, bracket(g, 0, 1), tol);
  expect_valid(b, g, -1);
  EXPECT_LE(b.hi - b.lo, tol);
  EXPECT_LE(b.lo, r);
  EXPECT_GE(b.hi, r);
  EXPECT_LE(b.evals, 2 * static_cast<int>(std::ceil(std::log2(1 / tol))) + 2);
}

TEST(SignChange, ExactZeroIsTheUpperEnd) {
  // g reaches zero at 0.5 exactly (the regula falsi point): zero counts as the new sign, so 0.5
  // is the upper end and the lower end closes in from below.
  const auto g = [](double t) { return t - 0.5; };
  const double tol = 1e-13;
  const auto b = narrow_sign_change(g, bracket(g, 0, 1), tol);
  EXPECT_EQ(b.hi, 0.5);
  EXPECT_LT(b.lo, 0.5);
  EXPECT_LE(b.hi - b.lo, tol);
}

TEST(SignChange, WorkIsBounded) {
  const auto g = [](double t) { return t < 0.3 ? -1.0 : 1.0; };
  const auto b = narrow_sign_change(g, bracket(g, 0, 1), 1e-15, std::numeric_limits<double>::quiet_NaN(), 3);
  EXPECT_EQ(b.evals, 3);
  expect_valid(b, g, -1);
  EXPECT_GT(b.hi - b.lo, 1e-15);
}

TEST(SignChange, RejectsAnIntervalWithoutASignChange) {
  const auto g = [](double t) { return t * t + 1; };
  EXPECT_THROW(narrow_sign_change(g, bracket(g, -1, 1), 1e-12), std::invalid_argument);
  EXPECT_THROW(narrow_sign_change(g, {1, -1, 0, 1}, 1e-12), std::invalid_argument);  // lo > hi
}

TEST(SignChange, ARefinedModelTakesTheSecantsPlace) {
  // A model that knows the root to 1e-17 after the first evaluation (SteppingIntegrator's quintic
  // through the first re-step): the next trial lands within tol/2 and one more closes the bracket,
  // three evaluations in all; from a guess 1e-6 off the secant alone needs more.
  const auto g = [](double t) { return std::cos(t) - t; };
  const double tol = 100 * kEps, root = 0.7390851332151607, guess = root + 1e-6;
  int asked = 0;
  const auto model = [&](const SignChange& b, double x) {
    ++asked;
    EXPECT_TRUE(b.lo <= x && x <= b.hi);
    return root;
  };
  const auto plain = narrow_sign_change(g, bracket(g, 0, 1), tol, guess);
  const auto refined = narrow_sign_change(g, bracket(g, 0, 1), tol, guess, 200,
                                          std::numeric_limits<double>::quiet_NaN(), model);
  expect_valid(refined, g, 1);
  EXPECT_LE(refined.hi - refined.lo, tol);
  EXPECT_NEAR(refined.hi, root, tol);
  EXPECT_LE(refined.evals, 3);
  EXPECT_LT(refined.evals, plain.evals);
  // Asked after the first evaluation only: after the second the secant already lands within tol/2.
  EXPECT_EQ(asked, 1);
}

TEST(SignChange, AWrongModelCannotBreakTheBracket) {
  // A model that points outside the bracket, or nowhere, is ignored (bisection or the secant).
  const auto g = [](double t) { return std::cos(t) - t; };
  const double tol = 100 * kEps;
  for (const double answer : {-5.0, 7.0, std::numeric_limits<double>::quiet_NaN()}) {
    const auto b = narrow_sign_change(g, bracket(g, 0, 1), tol, std::numeric_limits<double>::quiet_NaN(), 200,
                                      std::numeric_limits<double>::quiet_NaN(),
                                      [&](const SignChange&, double) { return answer; });
    expect_valid(b, g, 1);
    EXPECT_LE(b.hi - b.lo, tol) << answer;
    EXPECT_LE(b.evals, 60) << answer;  // bisection's 46 plus its safeguard's slack
  }
}

// A root function that sits exactly at its old sign's value over a stretch before its root: a gap
// computed from positions far larger than it (|x_a - x_b| - 2r at 200 m) rounds to exactly zero,
// plus the touch offset of 1e-150, for ~3e-14 s around the root. The secant on two equal values
// landed on the plateau's start and then crept on by tol/2 an evaluation, 2300 of them for the
// plateau, and the narrowing gave up at 200 returning the bracket's far end: the event-driven
// wedge took its impacts at the step's end, 45 us late and 3.9e-5 m deep. A nudge that does not
// cross is doubled: a plateau of 1e-9 is crossed in log2(1e-9 / tol) = 16 nudges, and the root
// found to tol in no more evaluations than bisection's 46 (20 here).
TEST(SignChange, APlateauAtTheOldSignIsCrossedNotCrept) {
  const double root = 0.6, plateau = 1e-9, tol = 100 * kEps;
  const auto g = [&](double t) {
    return t < root - plateau ? (root - plateau - t) : t < root ? 1e-150 : root - t;
  };
  const auto b = narrow_sign_change(g, bracket(g, 0, 1), tol);
  expect_valid(b, g, 1);
  EXPECT_LE(b.hi - b.lo, tol);
  EXPECT_NEAR(b.hi, root, tol);
  EXPECT_LE(b.evals, 46);
}
