// Runs that used to hang, overflow, grow without bound or succeed with a wrong answer: each now
// ends in bounded work, and a run that cannot give a right answer says so with a typed status.
#include "contact_ode/analysis/references.hpp"
#include "contact_ode/integrators/event_driven.hpp"
#include "contact_ode/integrators/game_step.hpp"
#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/integrators/penalty.hpp"
#include "contact_ode/models/ball_chain.hpp"
#include "contact_ode/models/ball_drop.hpp"
#include "contact_ode/models/scene_registry.hpp"
#include "integrator_driver.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

using namespace contact;

namespace {

RunResult chain_run(std::size_t n) {
  BallChainParams p;
  p.n = n;
  p.approach = 0.0;  // the striker touches ball 1: every gap starts exactly at zero
  p.law = Hooke{1e6};
  PenaltyOptions o{};
  SolveOptions o_span{.t_end = 2e-3, .sample_dt = 2e-3};
  o.integrator.rtol = 1e-6;
  o.integrator.atol = 1e-10;
  o.integrator.linear_solver = LinearSolverKind::Band;
  o.integrator.max_steps = 1000000;
  return run_penalty(BallChain(p), o, o_span);
}

}  // namespace

// The chain benchmark's case: CVODE used to return the same root time forever at N = 200 and
// 1000 (root functions of ~1e-160 made its sign test underflow), and contacts were opened by
// overlaps of 1e-26 ... 1e-150 m.
TEST(RunBounds, TouchingChainRunsAtEveryLengthAndOpensContactsOnlyOnRealOverlaps) {
  IntegratorOptions io;
  io.atol = 1e-10;
  const double threshold = contact_threshold(io);
  std::size_t contacts_200 = 0;
  for (std::size_t n : {10u, 200u, 1000u, 10000u}) {
    const RunResult r = chain_run(n);
    ASSERT_TRUE(r.ok()) << "N = " << n << ": " << to_string(r.status) << " " << r.message;
    ASSERT_FALSE(r.contacts.empty());
    for (const auto& c : r.contacts)
      EXPECT_GE(c.max_penetration, threshold)
          << "N = " << n << ", contact " << c.contact << " at t = " << c.t_begin;
    // In 2 ms the wave compresses only the first ~15 contacts above the threshold; a longer
    // chain adds balls nobody reaches, so it must report exactly the same contacts.
    if (n == 200) {
      contacts_200 = r.contacts.size();
    } else if (n > 200) {
      EXPECT_EQ(r.contacts.size(), contacts_200) << "N = " << n;
    }
    // Each contact switches on and off at most a few times: restarts are bounded by the log.
    EXPECT_LE(r.stats.restarts, 2 * static_cast<long>(r.contacts.size()) + 2) << "N = " << n;
  }
}

// t_end / dt = 1e20 used to overflow the step count to 0 and report success.
TEST(RunBounds, GameStepCountBeyondTheRunLimitFailsTyped) {
  const BallDrop model({});
  const RunResult r = run_game(model, GameOptions{.dt = 1e-16}, {.t_end = 1e4});
  EXPECT_EQ(r.status, Status::WorkLimit) << to_string(r.status);
  EXPECT_EQ(r.stats.steps, 0);
  EXPECT_NE(r.message.find("steps"), std::string::npos) << r.message;
}

// A fixed step beyond its scheme's stability bound 'succeeded' with the exploded state: the
// default chain (k = 1e6 N/m, 0.1 kg balls, omega_max = 2 sqrt(k/m) = 6325/s) at dt = 1 ms
// (omega dt = 6.3, semi-implicit Euler's bound is 2) ended at 1e43 m/s under the spring game loops
// and the penalty ODE under Euler alike. It now ends diverged where a speed passes 1e10 times the
// initial state's largest entry (1 m/s), naming the entry (the energy line, below, drawn off: it
// comes first). At dt = 0.1 ms (omega dt = 0.63) every one runs, and so does explicit Euler's
// energy growth on the ball that energy_drift measures (a speed gain of ~50: far below the line).
TEST(RunBounds, AFixedStepBeyondItsStabilityBoundEndsDivergedNotWithTheExplodedState) {
  const BallChain chain{BallChainParams{}};
  const SolveOptions span{.t_end = 0.05,
                          .sample_dt = 1e-3,
                          .limits = {.max_energy_gain = std::numeric_limits<double>::infinity()}};
  Method euler_ode{.name = "penalty", .dt = 0.0};
  euler_ode.integrator.method = "euler";
  for (Method m :
       {Method{.name = "game-symplectic-spring"}, Method{.name = "game-euler-spring"}, euler_ode}) {
    if (m.name == "penalty") m.integrator.dt = 1e-3;
    RunResult r = solve(chain, m, span);
    const std::string what = m.name + (m.name == "penalty" ? " euler" : "");
    EXPECT_EQ(r.status, Status::Diverged) << what << ": " << to_string(r.status) << " " << r.message;
    EXPECT_LT(r.t_reached, span.t_end) << what;
    EXPECT_NE(r.message.find("_mps = "), std::string::npos) << r.message;
    EXPECT_NE(r.message.find("stability bound"), std::string::npos) << r.message;
    ASSERT_FALSE(r.samples.empty());
    EXPECT_GT(r.samples.back().y.cwiseAbs().maxCoeff(), 1e10) << what;  // the last sample shows it

    if (m.name == "penalty")
      m.integrator.dt = 1e-4;
    else
      m.dt = 1e-4;
    r = solve(chain, m, span);
    EXPECT_TRUE(r.ok()) << what << " at 0.1 ms: " << r.message;
  }
  // energy_drift's ball: Hooke k = 1e5 N/m, e = 1, 100 bounces of the rigid ball (2 t0 each).
  const BallDrop ball({1.0, 9.81, 1.0, 0.0, 1.0, Hooke{1e5}});
  const double t_ball = 200 * std::sqrt(2 / 9.81);
  const RunResult grows =
      solve(ball, {.name = "game-euler-spring", .dt = 1e-3}, {.t_end = t_ball, .sample_dt = t_ball / 200});
  ASSERT_TRUE(grows.ok()) << grows.message;
  EXPECT_GT(grows.samples.back().energy, 1000 * grows.energy0);  // it does gain energy: ~2650 E0
}

// An unstable run whose state stays below the line above 'succeeded': on a column at dt = 1 ms the
// fastest spring mode is past semi-implicit Euler's bound (omega dt = 2 sqrt(k/m) dt ~ 2 with two
// springs a ball; 0.1 kg, k = 1e5 N/m), and the study's 16-ball column under game-symplectic-spring
// ended at 2 s 'successful' with its top ball 6.6e9 m up (below 1e10) and 3.7e18 times its energy;
// explicit Euler's 4-ball column 2e5 m up with 2e10 times its energy. The ledger's energy E + D can
// only fall in a passive scene, and now a gain of 1e6 |E0| (1e3 in the speeds) ends the run as
// diverged, at the first sample past it. The same column at 0.1 ms runs, to rounding.
TEST(RunBounds, AnEnergyGainOfAMillionFoldEndsDivergedEvenWhereTheStateStaysBelowItsLine) {
  const SolveOptions span{.t_end = 2.0, .sample_dt = 0.01};
  for (const auto& [name, n] :
       {std::pair{"game-symplectic-spring", 16.0}, std::pair{"game-euler-spring", 4.0}}) {
    const auto column = make_scene("ball-stack", {{"n", n}, {"m", 0.1}, {"k", 1e5}}, "kelvin-voigt");
    const RunResult r = solve(*column, {.name = name, .dt = 1e-3}, span);
    EXPECT_EQ(r.status, Status::Diverged) << name << ": " << to_string(r.status) << " " << r.message;
    EXPECT_NE(r.message.find("energy"), std::string::npos) << r.message;
    EXPECT_NE(r.message.find("unstable at these settings"), std::string::npos) << r.message;
    ASSERT_FALSE(r.samples.empty());
    const auto& last = r.samples.back();  // shows the gain, and that the state line was not reached
    EXPECT_GT(last.energy + last.dissipated - r.energy0, 1e6 * std::abs(r.energy0)) << name;
    EXPECT_LT(last.y.cwiseAbs().maxCoeff(), 1e10) << name;
    const RunResult stable = solve(*column, {.name = name, .dt = 1e-4}, span);
    EXPECT_TRUE(stable.ok()) << name << " at 0.1 ms: " << stable.message;
  }
}

// The state's line is no proof of instability: a weight far beyond what the spring holds sinks
// through it with the energy conserved. A 1 kg ball under g = 1e20 m/s^2 on k = 1e5 N/m sags
// m g / k = 1e15 m and swings at sqrt(k / m) = 316 /s about that, its speed 1e17 m/s, past 1e10 times
// its 1 m start; CVODE follows it to its tolerance. The run still ends diverged (the line is the
// run's bound), but the message said the method was unstable; it names the motion too now, and the
// energy ledger's reading, which stays inside its own line.
TEST(RunBounds, AStateBeyondItsLineWithTheEnergyConservedNamesTheMotionNotOnlyTheMethod) {
  const double g = 1e20, k = 1e5, sag = g / k;
  const BallDrop ball({.g = g, .law = Hooke{k}});
  const RunResult r = solve(ball, {.name = "penalty"}, {.t_end = 0.05, .sample_dt = 0.005});
  EXPECT_EQ(r.status, Status::Diverged) << to_string(r.status) << " " << r.message;
  EXPECT_NE(r.message.find("is more than 1e+10 times the initial state"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("either the motion itself leaves that scale"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("unstable at these settings"), std::string::npos) << r.message;
  ASSERT_FALSE(r.samples.empty());
  const auto& last = r.samples.back();
  EXPECT_GT(last.y[0], -2.0 * sag * (1 + 1e-6));  // the spring's swing about its sag, no further
  EXPECT_LT(last.y.cwiseAbs().maxCoeff(), 1e10 * sag);
  EXPECT_LT(last.energy + last.dissipated - r.energy0, 1e6 * r.energy0);  // the ledger holds
}

// Past 1e154 a state's squares leave the doubles: under g = 1e300 m/s^2 the game spring's ball passes
// 1e296 m/s within 0.02 s, and the message read "the energy (with what the run booked as lost) -nan J
// from its initial 1e+300 J" (inf - inf). It says the energy left the doubles' range now.
TEST(RunBounds, AnEnergyPastTheDoublesIsNamedSoNotNan) {
  const BallDrop ball({.g = 1e300, .law = Hooke{1e5}});
  const RunResult r = solve(ball, {.name = "game-symplectic-spring", .dt = 1e-3}, {.t_end = 0.05});
  EXPECT_EQ(r.status, Status::Diverged) << to_string(r.status) << " " << r.message;
  EXPECT_NE(
      r.message.find("the energy (with what the run booked as lost) past the doubles' range (its initial "
                     "1e+300 J): either the motion itself leaves that scale"),
      std::string::npos)
      << r.message;
  EXPECT_EQ(r.message.find("nan"), std::string::npos) << r.message;
}

// CVODE and ARKODE (re)start with the step sqrt(hlb hub), which underflows to 0 at extreme scales;
// they then stepped by 0 and returned the next output time with the state of the start, as a
// success. A 0.17 kg ball at 2 m/s into a 1e217 N/m Kelvin–Voigt contact (tuned to e = 0.9; 4e-109
// s long) with the tolerance scaled to it: after the contact's switch the dashpot's power against
// the absolute tolerance made hub 1e-227 and hlb 3e-122, and every SUNDIALS integrator 'succeeded'
// with the ball held at the floor at -2 m/s, the contact never ended. Restarted with hlb as the
// first step, each runs the contact to its restitution, or fails typed; none succeeds wrongly.
TEST(RunBounds, AFirstStepThatUnderflowsIsRetriedNotASuccessWithoutASingleStep) {
  const double m = 0.17, V = 2.0, e = 0.9, k = 1e217;
  const double duration = std::numbers::pi * std::sqrt(m / k), depth = 2 * V * std::sqrt(m / k);
  const BallDrop ball({m, 0.0, 1e-3 * depth, -V, e, kelvin_voigt_for_restitution(k, m, e, false)});
  PenaltyOptions o;
  o.integrator.rtol = 1e-8;
  o.integrator.atol = 1e-11 * depth;
  for (const char* integrator : {"cvode-bdf", "cvode-adams", "arkode-erk", "arkode-dirk", "arkode-imex"}) {
    o.integrator.method = integrator;
    const RunResult r = run_penalty(ball, o, {.t_end = 3 * duration, .sample_dt = 3 * duration});
    if (!r.ok()) {  // a typed failure (ARKODE's implicit stages at these scales), never a wrong success
      EXPECT_TRUE(r.status == Status::ErrorTestFailure || r.status == Status::ConvergenceFailure ||
                  r.status == Status::NoProgress)
          << integrator << ": " << to_string(r.status) << " " << r.message;
      EXPECT_LT(r.t_reached, 3 * duration) << integrator;
      continue;
    }
    ASSERT_EQ(r.contacts.size(), 1u) << integrator;
    ASSERT_TRUE(r.contacts[0].closed()) << integrator << ": the contact never ended";
    EXPECT_NEAR(r.contacts[0].restitution(), e, 1e-6) << integrator;  // undamped by gravity: exactly e
    EXPECT_NEAR(r.samples.back().y[1], e * V, 1e-6) << integrator;
  }
  o.integrator.method = "cvode-bdf";  // the default must run it
  EXPECT_TRUE(run_penalty(ball, o, {.t_end = 3 * duration, .sample_dt = 3 * duration}).ok());
}

// A span below a billionth of the step was no step at all: every fixed-step method (game loops,
// time stepping, the engines) 'succeeded' at t = 0 with no sample at t_end. One step, shortened
// to the span, covers it; a span within 1e-9 dt of whole steps still takes that many.
TEST(RunBounds, AFixedStepRunShorterThanItsStepTakesOneShortStep) {
  const auto ball = make_scene("ball-drop");
  for (const char* method : {"game-euler", "sequential-impulses", "xpbd", "moreau-jean"})
    for (const double t_end : {1e-300, 1e-13}) {
      const RunResult r = solve(*ball, {.name = method, .dt = 1e-3}, {.t_end = t_end, .sample_dt = t_end});
      ASSERT_TRUE(r.ok()) << method << ": " << r.message;
      EXPECT_EQ(r.t_reached, t_end) << method;
      EXPECT_EQ(r.stats.steps, 1) << method;
      ASSERT_EQ(r.samples.size(), 2u) << method;
      EXPECT_EQ(r.samples.back().t, t_end) << method;
    }
  EXPECT_EQ(steps_to_cover(1.0 + 1e-13, 1e-3), 1000.0);  // 1e-10 of a step past 1000: rounding, not a step
}

// A ball resting on the floor is detected and resolved every frame; it used to add a contact
// record per frame (1e7 records for 1e4 s). Projection + impulse stop the bounces once the
// incoming speed falls below what one step of gravity gives, g dt: e^n V < g dt after
// n = log(g dt / V) / log(e) = 27 bounces for e = 0.8, V = 4.43 m/s, dt = 1 ms (fewer are seen:
// at low speed each impact is measured a step late). Then the ball rests: one record, to the end.
TEST(RunBounds, RestingGameContactIsOneRecord) {
  const BallDrop model({.e = 0.8});
  const double V = std::sqrt(2 * 9.81), dt = 1e-3;
  const auto bounces = static_cast<std::size_t>(std::ceil(std::log(9.81 * dt / V) / std::log(0.8)));
  const RunResult r = run_game(model, GameOptions{.dt = dt}, {.t_end = 100.0, .sample_dt = 1.0});
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_LE(r.contacts.size(), bounces + 1);
  EXPECT_EQ(r.contacts.back().t_end, 100.0) << "the resting contact lasts to the end";
  EXPECT_LE(r.apexes.size(), r.contacts.size()) << "a resting ball has no apexes";
  EXPECT_LT(r.contacts.back().t_begin, 10.0);
}

TEST(RunBounds, RecordsBeyondTheRunLimitFailTyped) {
  const BallDrop model({.e = 1.0});
  GameOptions o{.dt = 1e-3};
  SolveOptions o_span{.t_end = 100.0, .sample_dt = 1.0};
  o_span.limits.max_records = 10;  // the elastic ball bounces every 0.9 s: 110 contacts and apexes
  const RunResult r = run_game(model, o, o_span);
  EXPECT_EQ(r.status, Status::WorkLimit);
  EXPECT_GT(r.t_reached, 0.0);
  EXPECT_LT(r.t_reached, 100.0);
}

TEST(RunBounds, SamplesBeyondTheRunLimitFailTypedWithoutAllocatingTheGrid) {
  const BallDrop model({});
  PenaltyOptions o{};
  SolveOptions o_span{.t_end = 1e4, .sample_dt = 1e-12};  // 1e16 samples
  const RunResult r = run_penalty(model, o, o_span);
  EXPECT_EQ(r.status, Status::WorkLimit);
  EXPECT_NE(r.message.find("sample"), std::string::npos) << r.message;
}

// A run that cannot fit its samples is a WorkLimit result for every method, as solve() promises.
// A fixed-step method refused for its steps (1e9 of them) first sampled its initial state, and
// that sample's own refusal (6.7e10 samples) escaped solve() as an exception: in Python a
// RuntimeError, not the SolverError the other methods raise.
TEST(RunBounds, SamplesBeyondTheRunLimitAreAWorkLimitResultForEveryMethod) {
  const BallDrop model({});
  for (const std::string& name : methods_for(model)) {
    Method method{.name = name};
    if (method_info(name).fixed_step) method.dt = 1.0;
    RunResult r;
    ASSERT_NO_THROW(r = solve(model, method, {.t_end = 1e9, .sample_dt = 0.015})) << name;
    EXPECT_EQ(r.status, Status::WorkLimit) << name << ": " << r.message;
    EXPECT_NE(r.message.find("sample"), std::string::npos) << name << ": " << r.message;
  }
}

// A drop from 1e308 m has the energy m g h0 = 9.8e308 J, beyond the doubles: the penalty method
// 'succeeded' with an infinite energy at every sample (the CLI refused it; Python did not). Every
// method is refused now, before it runs.
TEST(RunBounds, ASceneWhoseEnergyIsNotADoubleIsRefused) {
  const BallDrop model({.h0 = 1e308});
  for (const char* name : {"penalty", "event-exact", "game-euler"}) {
    Method method{.name = name, .dt = 1e-3};
    try {
      solve(model, method, {.t_end = 1.0, .sample_dt = 0.1});
      ADD_FAILURE() << name << " ran a scene of infinite energy";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("initial energy is inf J"), std::string::npos) << e.what();
    }
  }
}

TEST(RunBounds, PenaltyStepsBeyondTheRunLimitFailTyped) {
  const BallDrop model({});
  PenaltyOptions o{};
  SolveOptions o_span{.t_end = 3.0};
  o_span.limits.max_steps = 5;  // the default run takes ~300 steps, the fall to the floor ~20
  const RunResult r = run_penalty(model, o, o_span);
  EXPECT_EQ(r.status, Status::WorkLimit);
  EXPECT_EQ(r.message, "more than 5 steps in the run");  // before the first contact
  // Past contacts, the message says how many were recorded and when the last began: where the
  // steps went (a run of ever more bounces reads as a hang until the limit).
  o_span.limits.max_steps = 100;
  const RunResult later = run_penalty(model, o, o_span);
  ASSERT_EQ(later.status, Status::WorkLimit);
  ASSERT_FALSE(later.contacts.empty());
  EXPECT_EQ(later.message,
            fmt::format("more than 100 steps in the run (contacts recorded by then: {}, the last "
                        "begun at t = {:.6g} s)",
                        later.contacts.size(), later.contacts.back().t_begin));
}

// A dense Jacobian beyond 4 GiB is refused before it is allocated (SUNDenseMatrix returned NULL
// for 1e5 balls, which was dereferenced): a typed work limit naming the sparse solvers instead.
// (Dense is asked for: the default takes band storage on the chain.)
TEST(RunBounds, ADenseJacobianBeyondFourGibIsAWorkLimit) {
  const BallChain chain({.n = 100000, .law = Hooke{1e6}});
  const RunResult r =
      solve(chain, {.name = "penalty", .integrator = {.linear_solver = LinearSolverKind::Dense}},
            {.t_end = 1e-3, .sample_dt = 1e-3});
  EXPECT_EQ(r.status, Status::WorkLimit);
  EXPECT_NE(r.message.find("a dense 200001 x 200001 Jacobian needs 298 GiB (at most 4)"), std::string::npos)
      << r.message;
  EXPECT_NE(r.message.find("band, klu or gmres"), std::string::npos) << r.message;
}

// GSL's implicit steppers hold dense n x n matrices too (bsimp and msbdf two each, and a one-step
// method a second stepper for dense output), which nothing counted: at 15000 balls bsimp's four
// would be 29 GB, each granted by overcommit on its own. The same 4 GiB bound now holds there:
// bsimp at 6000 balls (12001 states, 4 matrices: 4.29 GiB) and msbdf at 8200 (16401, 2: 4.01 GiB)
// are refused at t = 0, naming what scales.
TEST(RunBounds, GslsDenseMatricesBeyondFourGibAreAWorkLimit) {
  for (const auto& [integrator, balls] :
       {std::pair<std::string, std::size_t>{"gsl-bsimp", 6000}, {"gsl-msbdf", 8200}}) {
    const BallChain chain({.n = balls, .law = Hooke{1e6}});
    const RunResult r = solve(chain, {.name = "penalty", .integrator = {.method = integrator}},
                              {.t_end = 1e-9, .sample_dt = 1e-9});
    EXPECT_EQ(r.status, Status::WorkLimit) << integrator;
    EXPECT_EQ(r.t_reached, 0.0) << integrator;
    EXPECT_NE(r.message.find("(at most 4): use a SUNDIALS integrator"), std::string::npos) << r.message;
  }
}

// exact-linear holds six dense n x n matrices (the Jacobian, a probe's, four kept segments' A),
// which nothing counted either: a 4e5-ball chain threw std::bad_alloc at its first step (5 TB each)
// and 4800 balls would have taken 4.4 GB. The 4 GiB bound holds from 4730 balls (2 n + 1 = 9461
// states with the energy ledger: 6 x 8 x 9461^2 bytes = 4.0014 GiB); both are refused at t = 0,
// naming what scales.
TEST(RunBounds, ExactLinearsDenseMatricesBeyondFourGibAreAWorkLimit) {
  for (const std::size_t balls : {400000, 4800}) {
    const BallChain chain({.n = balls, .law = Hooke{1e6}});
    const RunResult r = solve(chain, {.name = "penalty", .integrator = {.method = "exact-linear"}},
                              {.t_end = 1e-9, .sample_dt = 1e-9});
    EXPECT_EQ(r.status, Status::WorkLimit) << balls << ": " << r.message;
    EXPECT_EQ(r.t_reached, 0.0) << balls;
    EXPECT_NE(r.message.find(fmt::format("a dense {0} x {0} Jacobian and 5 more", 2 * balls + 1)),
              std::string::npos)
        << r.message;
    EXPECT_NE(r.message.find("(at most 4): use an adaptive integrator"), std::string::npos) << r.message;
  }
}

// A drop of 1e-9 m with e = 1 at atol = 1e-10: every bounce is below what the flight resolves.
// It used to come to rest at the first impact having lost 99 % of its energy, with success.
TEST(RunBounds, EventFlightBelowItsToleranceFailsTyped) {
  for (double e : {1.0, 0.9}) {
    const BallDrop model({.h0 = 1e-9, .e = e});
    EventOptions o{};
    SolveOptions o_span{.t_end = 1e-3};
    o.integrator.atol = 1e-10;
    const RunResult r = run_event_driven(model, o, o_span);
    EXPECT_EQ(r.status, Status::Unresolved) << "e = " << e << ": " << to_string(r.status);
    EXPECT_NE(r.message.find("atol"), std::string::npos) << r.message;
  }
}

// The same drop with the tolerance scaled to it (1e-10 per metre of height: 1e-19) keeps the
// elastic ball's energy over 2000 bounces, to about the CVODE tolerance times the bounce count.
TEST(RunBounds, EventFlightWithAScaledToleranceResolvesATinyDrop) {
  const BallDrop model({.h0 = 1e-9, .e = 1.0});
  EventOptions o{};
  SolveOptions o_span{.t_end = 2000 * 2 * std::sqrt(2e-9 / 9.81), .sample_dt = 1e-3};
  o.integrator.atol = 1e-19;
  const RunResult r = run_event_driven(model, o, o_span);
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_NEAR(static_cast<double>(r.contacts.size()), 2000.0, 2.0);
  for (const auto& s : r.samples) EXPECT_NEAR(s.energy, r.energy0, 1e-4 * r.energy0) << "t = " << s.t;
}

// A drop scaled in length by 2^-540 (h0 about 3e-163 m, gravity, atol and rest_speed alike) is the
// metre drop in other units, and the methods whose thresholds scale with it must bounce it alike.
// CVODE's and ARKODE's root search tests a sign change by the product of two values, which
// underflows to 0 below about 1.6e-162: the penalty ball fell through the floor and the run
// succeeded without a contact, and the event-driven flight's impacts fired only 1e-150 m deep
// (its touch offset, now at most a millionth of atol), 'unresolved'; event-exact's impact time
// from v^2 + 2 g x, subnormal or zero here, let its ball through too (and put its apexes 5e-6 off
// at 1e-160 m), and the closed form's impact speed sqrt(v0^2 + 2 g h0) came out 0 (and with it
// every impact time, apex and Zeno time ball_drop printed). At 2^-700 as well, where every such
// product is zero; and at 2^520 (3e156 m), where v^2 + 2 g x overflows and event-exact's ball fell
// through the floor as well (its energies overflow: only its flight and closed form are held).
// Held: the metre drop's contacts, its first three apexes to 100 rtol of h0 (the two runs'
// tolerances' errors; the flights' exact e^(2n) h0 for event-exact, to rounding), and the closed
// form's times and apexes, to rounding.
TEST(RunBounds, ADropScaledFarFromTheMetreBouncesAsTheMetreDropDoes) {
  const double e = 0.8, k = 1e5, rtol = 1e-8;
  const auto drop = [&](double s) {
    return BallDrop({.g = 9.81 * s, .h0 = s, .e = e, .law = kelvin_voigt_for_restitution(k, 1.0, e, false)});
  };
  const RigidBounces rigid(1.0, 0.0, 9.81, e);
  const BallDrop metre = drop(1.0);
  for (const double s : {0x1p-540, 0x1p-700, 0x1p520}) {
    const BallDrop scaled_drop = drop(s);
    const RigidBounces scaled(s, 0.0, 9.81 * s, e);
    EXPECT_NEAR(scaled.T1, rigid.T1, 1e-15 * rigid.T1) << s;
    EXPECT_NEAR(scaled.zeno_time(), rigid.zeno_time(), 1e-15 * rigid.zeno_time()) << s;
    EXPECT_NEAR(scaled.apex_height(1) / s, rigid.apex_height(1), 1e-15) << s;
    const SolveOptions span{.t_end = 3.0, .sample_dt = 0.5};
    EventOptions o;
    o.integrator.rtol = rtol;
    o.integrator.atol = 1e-10 * s;
    o.rest_speed *= s;
    const RunResult exact = run_event_driven(scaled_drop, scaled_drop, o, span);
    ASSERT_TRUE(exact.ok()) << s << ": " << exact.message;
    ASSERT_GE(exact.apexes.size(), 3u) << s;
    for (std::size_t j = 0; j < 3; ++j)
      EXPECT_NEAR(exact.apexes[j].gap / s, rigid.apex_height(j + 1), 1e-14) << s;
    // The numerical runs integrate energies (the dashpot's ledger, the impacts' losses), which
    // overflow at 2^520: below the metre only.
    if (s > 1) continue;
    for (const char* integrator : {"cvode-bdf", "arkode-erk"}) {
      auto penalty = [&](double scale) {
        PenaltyOptions p;
        p.integrator.method = integrator;
        p.integrator.rtol = rtol;
        p.integrator.atol = 1e-10 * scale;
        return run_penalty(scale == 1.0 ? metre : scaled_drop, p, span);
      };
      const RunResult big = penalty(1.0), small = penalty(s);
      ASSERT_TRUE(small.ok()) << integrator << " at " << s << ": " << small.message;
      ASSERT_EQ(small.contacts.size(), big.contacts.size()) << integrator << " at " << s;
      ASSERT_GE(small.apexes.size(), 3u) << integrator << " at " << s;
      for (std::size_t j = 0; j < 3; ++j)
        EXPECT_NEAR(small.apexes[j].gap / s, big.apexes[j].gap, 100 * rtol) << integrator << " at " << s;
    }
    const RunResult flown = run_event_driven(scaled_drop, o, span);
    ASSERT_TRUE(flown.ok()) << s << ": " << flown.message;
    ASSERT_GE(flown.apexes.size(), 3u) << s;
    for (std::size_t j = 0; j < 3; ++j)
      EXPECT_NEAR(flown.apexes[j].gap / s, rigid.apex_height(j + 1), 100 * rtol) << s;
  }
}

// e = 0.9 and 0.99 used to stop short of t_inf (bounces below the tolerance were rested without
// a word). The flight lands each impact early by its position error eps = K atol (CVODE restarts
// at first order after every impact, which is not exact for the parabola): flight n is short by
// about 2 eps / v_n, and the impact speed low by eps g / v_n^2 relative to v_n. Summed over the
// geometric cascade down to the rest speed v_r = sqrt(2 g 100 atol) (the rest height, 100 atol):
//   relative speed deficit  D = eps g / (v_r^2 (1 - e^2)),
//   time lost to the bias   2 eps / (v_r (1 - e) (1 - e^2)),
//   Zeno time skipped       2 v_r / ((1 - D) g (1 - e))  (the exact ball is faster by 1/(1-D)).
// K = 1 ... 1.3 was measured (e = 0.99: 2.9 ms early, D = 25 %); K = 2 bounds it.
TEST(RunBounds, EventCascadeReachesTheZenoTimeForRestitutionsNearOne) {
  for (double e : {0.9, 0.99}) {
    const BallDrop model({.e = e});
    const RigidBounces ref(1.0, 0.0, 9.81, e);
    EventOptions o{};
    SolveOptions o_span{.t_end = ref.zeno_time() + 1.0, .sample_dt = 0.5};
    const RunResult r = run_event_driven(model, o, o_span);
    ASSERT_TRUE(r.ok()) << "e = " << e << ": " << r.message;
    const double g = 9.81, eps = 2 * o.integrator.atol, v_r = std::sqrt(2 * g * 100 * o.integrator.atol);
    const double D = eps * g / (v_r * v_r * (1 - e * e));
    const double early = 2 * eps / (v_r * (1 - e) * (1 - e * e));
    const double skipped = 2 * v_r / ((1 - D) * g * (1 - e));
    const double t_rest = r.contacts.back().t_end;
    EXPECT_LE(t_rest, ref.zeno_time()) << "e = " << e;
    EXPECT_GE(t_rest, ref.zeno_time() - skipped - early) << "e = " << e;
  }
}

// rigid_ball_state used to loop forever for t between the floating-point sum of the impact
// times and t_inf. Near t_inf the ball is in a leg that ends before t_inf: with Delta = t_inf - t,
// its speed is at most g Delta / 2 and its height at most g Delta^2 / 8.
TEST(RunBounds, RigidBallStateNearTheZenoTime) {
  for (double e : {0.5, 0.8, 0.9, 0.99}) {
    const RigidBounces ref(1.0, 0.0, 9.81, e);
    const double t_inf = ref.zeno_time();
    for (double t : {t_inf - 1e-3, t_inf - 1e-9, t_inf * (1 - 1e-14), std::nextafter(t_inf, 0.0)}) {
      const BallState s = rigid_ball_state(1.0, 0.0, 9.81, e, t);
      const double delta = t_inf - t;
      EXPECT_GE(s.x, 0.0) << "e = " << e << ", t_inf - t = " << delta;
      EXPECT_LE(s.x, 9.81 * delta * delta / 8 * (1 + 1e-9) + 1e-300)
          << "e = " << e << ", t_inf - t = " << delta;
      EXPECT_LE(std::abs(s.v), 9.81 * delta / 2 * (1 + 1e-9)) << "e = " << e << ", t_inf - t = " << delta;
    }
  }
}

// The direct leg index agrees with the closed-form bounce sequence at the impacts and apexes.
TEST(RunBounds, RigidBallStateMatchesTheBounceSequence) {
  for (double e : {0.3, 0.8, 1.0}) {
    const RigidBounces ref(1.0, 0.0, 9.81, e);
    for (std::size_t n = 1; n <= 20; ++n) {
      const BallState apex = rigid_ball_state(1.0, 0.0, 9.81, e, ref.apex_time(n));
      EXPECT_NEAR(apex.x, ref.apex_height(n), 1e-12) << "e = " << e << ", n = " << n;
      EXPECT_NEAR(apex.v, 0.0, 1e-11) << "e = " << e << ", n = " << n;
      // Just after impact n + 1 the ball leaves upwards at e^(n+1) V.
      const BallState after = rigid_ball_state(1.0, 0.0, 9.81, e, ref.impact_time(n + 1) + 1e-12);
      EXPECT_NEAR(after.v, std::pow(e, static_cast<double>(n + 1)) * ref.V, 1e-10)
          << "e = " << e << ", n = " << n;
    }
  }
}

// At an impact time, to rounding, the ball is on the floor arriving at e^(n-1) V or leaving at
// e^n V: the leg's index, taken from a logarithm, can land one leg off there, and the state was
// then read from a leg that had ended (a ball at rest in mid-cascade).
TEST(RunBounds, RigidBallStateAtTheImpactsIsOnTheFloorAtTheImpactSpeed) {
  for (double e : {0.3, 0.5, 0.8, 0.95}) {
    const RigidBounces ref(1.0, 0.0, 9.81, e);
    for (std::size_t n = 2; n <= 40; ++n) {
      const double t_n = ref.impact_time(n);
      const double in = std::pow(e, static_cast<double>(n - 1)) * ref.V, out = e * in;
      for (double t : {std::nextafter(t_n, 0.0), t_n, std::nextafter(t_n, 10.0)}) {
        const BallState s = rigid_ball_state(1.0, 0.0, 9.81, e, t);
        // Within a few ulps of t of the impact: heights of V ulp(t), speeds within g ulp(t).
        const double ulps = 8 * std::numeric_limits<double>::epsilon() * t_n;
        EXPECT_LE(std::abs(s.x), ref.V * ulps) << "e = " << e << ", n = " << n << ", t - t_n = " << t - t_n;
        const bool arriving = std::abs(s.v + in) <= 9.81 * ulps, leaving = std::abs(s.v - out) <= 9.81 * ulps;
        EXPECT_TRUE(arriving || leaving) << "e = " << e << ", n = " << n << ", t - t_n = " << t - t_n
                                         << ": v = " << s.v << " for -" << in << " or " << out;
      }
    }
  }
}
