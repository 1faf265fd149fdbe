// Roots located by the stepping methods (GSL's one-step methods, the fixed-step schemes), whose
// dense output is a re-step from the step's start: every trial of a root's narrowing costs a step.
// Several root functions crossing zero within one step (a column of balls ringing together) must
// each be found where it is found alone, and the step's trials must serve them all: each function
// narrowed once, not every function again after each root.
#include "contact_ode/integrators/integrator.hpp"
#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/models/scene_registry.hpp"
#include "method_param_name.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

using namespace contact;

namespace {

// y = (cos t, sin t): a rotation, whose root functions g_i = sin t - sin(theta_i) rise through zero
// at exactly t = theta_i (all in (0, pi/2), where sin rises).
OdeSystem rotation_with_roots(const std::vector<double>& thetas) {
  OdeSystem sys;
  sys.size = 2;
  sys.rhs = [](double, ConstVectorRef y, VectorRef yd) { yd << -y[1], y[0]; };
  sys.root_count = thetas.size();
  sys.roots = [thetas](double, ConstVectorRef y, VectorRef g) {
    for (std::size_t i = 0; i < thetas.size(); ++i)
      g[static_cast<Eigen::Index>(i)] = y[1] - std::sin(thetas[i]);
  };
  return sys;
}

struct RootRun {
  std::vector<double> times;  // the roots, in the order found
  long rhs_evals;
};

RootRun run_to(const IntegratorOptions& o, const std::vector<double>& thetas, double t_end) {
  auto integrator = make_integrator(o, rotation_with_roots(thetas), 0.0, Vector{{1.0, 0.0}});
  RootRun run{{}, 0};
  for (int bound = 0; bound <= static_cast<int>(thetas.size()); ++bound) {  // one return per root, then t_end
    const auto out = integrator->advance(t_end);
    if (!out.root) break;
    run.times.push_back(out.t);
  }
  run.rhs_evals = integrator->stats().rhs_evals;
  return run;
}

class SteppingRoots : public ::testing::TestWithParam<std::string> {};

// Six roots 0.01 apart (RK4 steps 0.1 from 1.0, and the roots are at 1.02 ... 1.07; GSL's steps
// are longer). The step sequence does not depend on the root functions, so a run's right-hand sides
// beyond a run without roots are its narrowings'. Each root alone costs its own narrowing; together
// they may cost no more than the sum of those (measured: the sum less the step's two end slopes,
// which the roots of one step share). Before the step's trials were kept, the six cost 3.2 to 3.4
// times that sum: every root function was narrowed over the whole step, and those left were
// narrowed again after each root (6 + 5 + ... + 1 narrowings for 6 roots).
TEST_P(SteppingRoots, SeveralRootsInOneStepAreEachNarrowedOnce) {
  IntegratorOptions o;
  o.method = GetParam();
  o.rtol = 1e-6;
  o.atol = 1e-9;
  const bool fixed = GetParam().find("gsl-") != 0;
  if (fixed) o.dt = 0.1;
  std::vector<double> thetas;
  for (int i = 0; i < 6; ++i) thetas.push_back(1.02 + 0.01 * i);
  const double t_end = 1.5;
  const long base = run_to(o, {}, t_end).rhs_evals;
  const RootRun all = run_to(o, thetas, t_end);
  ASSERT_EQ(all.times.size(), thetas.size());
  long alone_sum = 0;
  for (std::size_t i = 0; i < thetas.size(); ++i) {
    const RootRun alone = run_to(o, {thetas[i]}, t_end);
    ASSERT_EQ(alone.times.size(), 1u);
    alone_sum += alone.rhs_evals - base;
    // The same root as alone, to the root tolerance (100 ulps of t, ~2.5e-14 here) at each end.
    EXPECT_NEAR(all.times[i], alone.times[0], 1e-13) << o.method << " root " << i;
    // And theta_i to the method's accuracy: RK4's global error at dt = 0.1 is about t dt^4 / 120
    // = 8.5e-7 at t = 1 (measured 9.7e-7); GSL's at rtol 1e-6 is below it (2.2e-7 for RKF45,
    // 1.7e-10 for RK8PD).
    EXPECT_NEAR(all.times[i], thetas[i], 2e-6) << o.method << " root " << i;
  }
  EXPECT_LE(all.rhs_evals - base, alone_sum) << o.method;
}

// A column of four balls on damped springs (resting_cost's, k = 1e6 N/m) rings down and rests, its
// gap rates crossing zero at the tolerance's level thousands of times a second, where a re-step's
// value of a root function is mostly its own rounding. Each root costs RK8PD at most five re-steps
// (a Newton step from the cubic's root, the quintic's, two secant steps, superlinear from the
// quintic's ~1e-3 H down to the 1e-5 H where the bracket's cubic takes over, and the step that
// closes the bracket), each 12 right-hand sides past the shared first stage, and five single
// ones (the step's two end slopes, the quintic's midpoint and the bracket cubic's two slopes): 65.
// Measured 26. Before the cubic finished, the re-steps bisected their rounding down to 100 ulps of
// t: 97 (and about 390 before the step's trials were kept).
TEST(RingingColumnRoots, EachCostsAFewReStepsThoughItsFunctionIsAtItsRounding) {
  const auto column = make_scene("ball-stack", {{"n", 4}, {"m", 0.1}, {"k", 1e6}}, "kelvin-voigt");
  Method penalty{.name = "penalty"};
  penalty.integrator.method = "gsl-rk8pd";
  penalty.integrator.rtol = 1e-6;
  penalty.integrator.atol = 1e-8;
  const RunResult r = solve(*column, penalty, {.t_end = 1.0, .sample_dt = 1.0});
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_GT(r.stats.events, 1000);                                    // the ringing's roots, thousands
  const long stepping = 13 * (r.stats.steps + r.stats.failed_steps);  // RK8PD: 13 stages a step
  EXPECT_LE(static_cast<double>(r.stats.rhs_evals - stepping) / static_cast<double>(r.stats.events), 65.0);
}

INSTANTIATE_TEST_SUITE_P(ReStepping, SteppingRoots, ::testing::Values("gsl-rk8pd", "gsl-rkf45", "rk4"),
                         MethodParamName());

}  // namespace
