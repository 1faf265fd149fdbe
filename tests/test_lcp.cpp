// The exact LCP solver behind Moreau–Jean (integrators/lcp.hpp): every answer is checked by the
// LCP's own conditions (p >= 0, w = W p + b >= 0, p_i w_i = 0) to rounding, not against a stored
// solution; and Moreau–Jean on a long touching cradle, where Gauss–Seidel alone needed ~3 n^2
// sweeps, against the closed form of Newton's law on all contacts at once.
#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/models/ball_chain.hpp"
#include "contact_ode/models/scene_registry.hpp"
#include "lcp.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

using namespace contact;

namespace {

// Complementarity to `tol` (velocity units) for p and w, and to tol times the impulse for p w.
void expect_complementary(const Eigen::MatrixXd& W, const Eigen::VectorXd& b, const LcpSolution& s,
                          double tol) {
  ASSERT_TRUE(s.solved);
  const Eigen::VectorXd w = W * s.p + b;
  for (Eigen::Index i = 0; i < b.size(); ++i) {
    EXPECT_GE(s.p(i), 0.0) << i;
    EXPECT_GE(w(i), -tol) << i;
    EXPECT_LE(std::abs(s.p(i) * w(i)), tol * (1 + std::abs(s.p(i)))) << i;
  }
}

// A row of n touching unit masses pushed by gap rates b: W is the 1-D Laplacian (2 on the
// diagonal, -1 beside it), whose condition number ~ n^2 is what slows Gauss–Seidel down.
Eigen::MatrixXd row_of_contacts(Eigen::Index n) {
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    W(i, i) = 2;
    if (i > 0) W(i, i - 1) = W(i - 1, i) = -1;
  }
  return W;
}

}  // namespace

// Half the contacts approach (b < 0), half separate: from the guess "every impulse positive" the
// block pivots find the set in a few dozen solves (21), far fewer than the n = 200 single flips
// Murty's rule alone could need.
TEST(Lcp, ARowOfApproachingAndSeparatingContactsIsSolvedFromAWrongGuess) {
  const Eigen::Index n = 200;
  const Eigen::MatrixXd W = row_of_contacts(n);
  Eigen::VectorXd b(n);
  for (Eigen::Index i = 0; i < n; ++i) b(i) = std::sin(0.1 * static_cast<double>(i));
  const LcpSolution s = solve_lcp(W.sparseView(), b, std::vector<bool>(n, true), 1e-12, 100);
  expect_complementary(W, b, s, 1e-12);
  EXPECT_LE(s.solves, n / 4);
  // Both kinds of contact are in the answer: a pushing impulse and an open one.
  EXPECT_GT(s.p.maxCoeff(), 0.1);
  EXPECT_EQ(s.p.minCoeff(), 0.0);
}

// A column of n unit balls on the floor, falling together, h g = 1e-3 m/s short at the floor (b_0)
// and at rest against each other (b = 0): W is the row's Laplacian with the floor's 1 at W_00, and
// the answer p_k = (n - k) 1e-3 holds the whole column. The first block solve is it, to rounding:
// its w comes out of about eps cond(W) |b| (cond ~ 4 n^2 / pi^2, 1.6e6 at n = 2000), and
// Moreau–Jean asks for 1e-12 of the rates, 1e-15. Judged against that alone, a solved index went
// out and back for ever (here: 20 solves of 20 without an answer; a falling column of 1500 balls
// under Moreau–Jean pivoted 850 times a step); w is now judged to its own rounding (1e-10 of |b|),
// and Moreau–Jean's sweeps take it on from there. p to cond eps of its largest, four times over.
TEST(Lcp, ASolvedBlockIsNotFlippedOutForItsRounding) {
  const Eigen::Index n = 2000;
  Eigen::MatrixXd W = row_of_contacts(n);
  W(0, 0) = 1;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
  b(0) = -1e-3;
  const LcpSolution s =
      solve_lcp(W.sparseView(), b, std::vector<bool>(static_cast<std::size_t>(n), true), 1e-15, 20);
  ASSERT_TRUE(s.solved) << s.solves << " solves";
  EXPECT_EQ(s.solves, 1);
  const double cond = 4.0 * static_cast<double>(n * n) / (std::numbers::pi * std::numbers::pi),
               largest = 1e-3 * static_cast<double>(n);
  for (Eigen::Index k = 0; k < n; ++k)
    EXPECT_NEAR(s.p(k), 1e-3 * static_cast<double>(n - k),
                4 * cond * std::numeric_limits<double>::epsilon() * largest)
        << k;
}

// Contacts that all share bodies (a dense W: B B^T + I/10, B's entries spread in [-1, 1]): the
// sparse factorisation fills in completely and must still give the LCP's answer, from a wrong
// guess, with both kinds of contact in it.
TEST(Lcp, AFullyCoupledProblemIsSolvedToo) {
  const Eigen::Index n = 40;
  Eigen::MatrixXd B(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) B(i, j) = std::sin(static_cast<double>(7 * i + 3 * j + 1));
  const Eigen::MatrixXd W = B * B.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
  Eigen::VectorXd b(n);
  for (Eigen::Index i = 0; i < n; ++i) b(i) = 10 * std::cos(static_cast<double>(5 * i));
  const LcpSolution s = solve_lcp(W.sparseView(), b, std::vector<bool>(n, true), 1e-12, 4 * n + 16);
  // To the solver's own floor for w, 1e-10 of the largest |b| (lcp.hpp): 1e-9.
  expect_complementary(W, b, s, 1e-9);
  EXPECT_GT(s.p.maxCoeff(), 0.0);
  EXPECT_EQ(s.p.minCoeff(), 0.0);
}

// Two contacts on the same normal between the same bodies (a redundant pair): W is singular, the
// impulses are not unique, but their sum is, and the rates come out exactly zero.
TEST(Lcp, ARedundantPairGetsItsSumRight) {
  Eigen::MatrixXd W(2, 2);
  W << 1, 1, 1, 1;
  const Eigen::Vector2d b(-1, -1);
  const LcpSolution s = solve_lcp(W.sparseView(), b, {true, true}, 1e-12, 20);
  expect_complementary(W, b, s, 1e-12);
  EXPECT_NEAR(s.p.sum(), 1.0, 1e-12);
}

// No impulse can stop an approach that no impulse acts on (W = 0, b < 0): no solution, and the
// solver says so within its bound instead of pivoting for ever.
TEST(Lcp, AnUnsolvableProblemEndsUnsolvedWithinTheBound) {
  const Eigen::MatrixXd W = Eigen::MatrixXd::Zero(3, 3);
  const Eigen::Vector3d b(-1, 0.5, -2);
  const LcpSolution s = solve_lcp(W.sparseView(), b, {false, false, false}, 1e-12, 25);
  EXPECT_FALSE(s.solved);
  EXPECT_LE(s.solves, 25);
}

// A striker into n touching balls under Moreau–Jean: Newton's law with e = 1 on every contact at
// once (one LCP) sends the n - 1 resting balls off together at v_rest - v_striker = 1 with momentum
// 1: v_rest = 2/n, the striker at 2/n - 1 (newton_cradle's five-ball test). Gauss–Seidel needs
// ~3 n^2 sweeps for the impact's LCP: 100 balls failed with 'did not converge in 10000
// Gauss-Seidel sweeps' (newton_cradle --balls 100 ended there), 300 would need 270000.
TEST(MoreauJean, ALongTouchingCradleTakesNewtonsLawOnEveryContactAtOnce) {
  for (const std::size_t n : {100u, 300u}) {
    const BallChain chain({.n = n, .m = 0.1, .v0 = 1.0, .approach = 0.01, .law = Hooke{1e6}});
    const RunResult r = solve(chain, {.name = "moreau-jean", .dt = 1e-4}, {.t_end = 0.02, .sample_dt = 0.02});
    ASSERT_TRUE(r.ok()) << n << ": " << r.message;
    const Vector& y = r.samples.back().y;
    const double rest = 2.0 / static_cast<double>(n);
    EXPECT_NEAR(y[1], rest - 1, 1e-9) << n;
    for (std::size_t b = 1; b < n; ++b) EXPECT_NEAR(y[static_cast<Eigen::Index>(2 * b + 1)], rest, 1e-9) << n;
  }
}

// A column of n balls released touching on the floor: Moreau–Jean's first step has every contact
// closed, and gravity's g h short at the floor only (the balls fall together, at gap rates of
// exactly zero between them). Newton's law holds the whole column: every velocity 0. From
// Gauss–Seidel's pushes alone as the guess, block pivoting found one more contact short per solve
// (150 dense solves for 300 balls, 850 for 1000: 7 s for one step); with the closing and still
// contacts in the guess, the first solve is the answer. Solves and W's formations are counted as
// the step's linear setups and Jacobians; a few solves per formation are allowed.
TEST(MoreauJean, AFallingColumnsLcpIsSolvedInAFewBlockSolves) {
  const auto column = make_scene("ball-stack", {{"n", 300}}, "kelvin-voigt");
  const RunResult r = solve(*column, {.name = "moreau-jean", .dt = 1e-4}, {.t_end = 1e-3, .sample_dt = 1e-3});
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_GE(r.stats.jac_evals, 1);  // the exact solve ran (Gauss–Seidel alone needs ~3 n^2 sweeps)
  EXPECT_LE(r.stats.linear_setups, 3 * r.stats.jac_evals);
  const Vector& y = r.samples.back().y;
  for (Eigen::Index b = 0; b < 300; ++b) EXPECT_NEAR(y[2 * b + 1], 0.0, 1e-10) << "ball " << b;
}

// Beyond the 3000 closed contacts solved exactly (forming W asks n^2 gap rates: 1e10 for a 1e5-ball
// column) a falling column's first step is Gauss–Seidel's alone, which needs ~3 n^2 sweeps: the
// run ends at t = 0 as a convergence failure that names the bound, within 10^4 sweeps.
TEST(MoreauJean, ATooLargeImpactLcpEndsAFailureThatNamesTheExactSolvesBound) {
  const auto column = make_scene("ball-stack", {{"n", 3001}}, "kelvin-voigt");
  const RunResult r = solve(*column, {.name = "moreau-jean", .dt = 1e-4}, {.t_end = 1e-3, .sample_dt = 1e-3});
  EXPECT_EQ(r.status, Status::ConvergenceFailure);
  EXPECT_EQ(r.t_reached, 0.0);
  EXPECT_NE(r.message.find("its 3001 closed contacts are more than the 3000 solved exactly"),
            std::string::npos)
      << r.message;
  EXPECT_EQ(r.stats.jac_evals, 0);
}
