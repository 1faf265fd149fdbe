// Event-driven impulses on the ball drop against the closed-form bounce sequence
// (analysis/references.hpp): T1 = t0, T(n+1) = T(n) + 2 e^n t0, h_n = e^{2n} h0,
// t_inf = t0 (1+e)/(1-e).
#include "contact_ode/analysis/references.hpp"
#include "contact_ode/integrators/event_driven.hpp"
#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/models/ball_drop.hpp"
#include "contact_ode/models/ball_stack.hpp"
#include "contact_ode/models/rigid/rigid_scenes.hpp"
#include "contact_ode/models/scene_registry.hpp"
#include "unit_roundoff.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>

using namespace contact;

namespace {

BallDrop ball(double e, double h0 = 1.0) { return BallDrop({1.0, 9.81, h0, 0.0, e, Hooke{1e5}}); }

SolveOptions span(double t_end) { return {.t_end = t_end, .sample_dt = 0.05}; }

EventOptions options() {
  EventOptions o;
  o.integrator.rtol = 1e-10;
  o.integrator.atol = 1e-12;
  return o;
}

}  // namespace

class EventDrivenExact : public ::testing::TestWithParam<double> {};

TEST_P(EventDrivenExact, ImpactTimesAndApexHeightsMatchTheClosedForm) {
  const double e = GetParam();
  const BallDrop model = ball(e);
  const RigidBounces ref(1.0, 0.0, 9.81, e);
  const RunResult r = run_event_driven(model, model, options(), span(6.0));
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_GE(r.contacts.size(), 5u);
  ASSERT_GE(r.apexes.size(), 5u);
  // Each impact time is a sum of n closed-form flight times, each computed to a few ulps, so the
  // n-th time carries at most ~n*4 ulps of rounding: 64 ulps of the time covers n <= 16.
  for (std::size_t n = 1; n <= std::min<std::size_t>(r.contacts.size(), 16); ++n) {
    const double Tn = ref.impact_time(n);
    EXPECT_NEAR(r.contacts[n - 1].t_begin, Tn, 64 * kEps * Tn) << "impact " << n;
    EXPECT_NEAR(r.contacts[n - 1].restitution(), e, 8 * kEps) << "impact " << n;
  }
  // Apex heights e^{2n} h0: each is v^2/(2g) of a velocity that went through n impulses
  // (4 ulps each), so a relative error of 16 ulps per impact.
  for (std::size_t n = 1; n <= std::min<std::size_t>(r.apexes.size(), 16); ++n) {
    const double hn = ref.apex_height(n);
    EXPECT_NEAR(r.apexes[n - 1].gap, hn, 16.0 * static_cast<double>(n) * kEps * hn) << "apex " << n;
    EXPECT_NEAR(hn, std::pow(e, 2.0 * static_cast<double>(n)), 1e-14);  // the textbook form
  }
}

INSTANTIATE_TEST_SUITE_P(Restitutions, EventDrivenExact, ::testing::Values(0.5, 0.8, 0.95));

TEST(EventDriven, ZenoCascadeStopsAtTheZenoTimeAndTheBallRests) {
  const double e = 0.8;
  const BallDrop model = ball(e);
  const RigidBounces ref(1.0, 0.0, 9.81, e);
  EventOptions o = options();
  const SolveOptions o_span = span(6.0);
  o.rest_speed = 1e-7;
  for (bool exact : {true, false}) {
    const RunResult r =
        exact ? run_event_driven(model, model, o, o_span) : run_event_driven(model, o, o_span);
    ASSERT_TRUE(r.ok()) << r.message;
    // The rest guard stops the cascade at the first bounce slower than rest_speed; the bounces it
    // skips would have lasted 2 v / (g (1-e)) < 2 rest_speed / (g (1-e)) ~ 1e-7 s. The CVODE
    // flight adds the error of ~80 root locations, each within its tolerance (rtol 1e-10 of t).
    // The CVODE flight also stops resolving bounces lower than its absolute tolerance; taking
    // heights below 100 atol as unresolved, the speed at which it may stop is sqrt(2 g 100 atol).
    const double v_stop = exact ? o.rest_speed : std::sqrt(2 * 9.81 * 100 * o.integrator.atol);
    const double skipped = 2 * v_stop / (9.81 * (1 - e));
    const double t_rest = r.contacts.back().t_end;
    const double tol = exact ? 1e-12 : 1e-8;
    EXPECT_LE(t_rest, ref.zeno_time() + tol) << (exact ? "exact" : "cvode");
    EXPECT_GE(t_rest, ref.zeno_time() - skipped - tol) << (exact ? "exact" : "cvode");
    if (exact) {
      // log(rest_speed / V) / log(e) impacts happen before the guard fires.
      const double expected = std::ceil(std::log(o.rest_speed / ref.V) / std::log(e));
      EXPECT_NEAR(static_cast<double>(r.contacts.size()), expected, 1.0);
    }
    // At rest on the floor afterwards, never below it.
    for (const auto& s : r.samples) {
      EXPECT_GE(s.y[0], -1e-12) << "t = " << s.t;
      if (s.t > ref.zeno_time()) {
        EXPECT_EQ(s.y[0], 0.0) << "t = " << s.t;
        EXPECT_EQ(s.y[1], 0.0) << "t = " << s.t;
      }
    }
  }
}

// A numerical flight rests a bounce that would rise less than 100 atol (the default rest height;
// below it the flight cannot resolve the bounce). At e = 0.5 from 1 m the n-th bounce rises 0.25^n m:
// with atol 1e-9 the 11th (2.4e-7 m) flies and the 12th (6.0e-8 m) rests, so there are 11 apexes;
// a rest height of 5e-8 m lets the 12th fly too.
TEST(EventDriven, ByDefaultABounceRisingLessThan100AtolRests) {
  EventOptions o = options();
  o.integrator.atol = 1e-9;
  const auto apexes = [&](double rest_height) {
    o.rest_height = rest_height;
    const RunResult r = run_event_driven(ball(0.5), o, span(3.0));
    EXPECT_TRUE(r.ok()) << r.message;
    return r.apexes;
  };
  const auto by_default = apexes(-1);
  ASSERT_EQ(by_default.size(), 11u);
  EXPECT_NEAR(by_default.back().gap, std::pow(0.25, 11), 10 * o.integrator.atol);  // 22 flights' error
  EXPECT_EQ(apexes(1e-7).size(), 11u);
  EXPECT_EQ(apexes(5e-8).size(), 12u);
}

TEST(EventDriven, PerfectlyInelasticBallStopsAtFirstImpact) {
  const BallDrop model = ball(0.0);
  const RigidBounces ref(1.0, 0.0, 9.81, 0.0);
  const RunResult r = run_event_driven(model, model, options(), span(2.0));
  ASSERT_TRUE(r.ok());
  ASSERT_EQ(r.contacts.size(), 1u);
  EXPECT_NEAR(r.contacts[0].t_begin, ref.T1, 4 * kEps * ref.T1);
  EXPECT_EQ(r.contacts[0].v_out, 0.0);
  EXPECT_TRUE(r.apexes.empty());
  EXPECT_EQ(r.samples.back().y[0], 0.0);
}

// A ball released at rest on the floor stays there, under either flight, at every restitution:
// its contact starts at rest (closed, still, pushed down by gravity). It used to sink for
// ~1e-26 s, meet a bounce far below the flight's resolution and end the run as unresolved.
TEST(EventDriven, BallReleasedOnTheFloorStaysThere) {
  for (const double e : {0.0, 0.5, 1.0}) {
    const BallDrop model = ball(e, 0.0);
    for (const RunResult& r : {run_event_driven(model, options(), span(1.0)),
                               run_event_driven(model, model, options(), span(1.0))}) {
      ASSERT_TRUE(r.ok()) << e << ": " << r.message;
      for (const auto& s : r.samples) {
        EXPECT_EQ(s.y[0], 0.0) << e << " at " << s.t;
        EXPECT_EQ(s.y[1], 0.0) << e << " at " << s.t;
      }
      EXPECT_TRUE(r.apexes.empty());
    }
  }
}

// A plastic impact (e = 0) stops the ball on the floor at the first impact time t0 = sqrt(2 h0/g),
// its energy m g h0 all dissipated there. The numerical flight failed it as 'unresolved' (its
// bounce rises 0 m, below what the flight resolves, and it was the contact's first), advising a
// tighter absolute tolerance that could not help.
TEST(EventDriven, PlasticImpactStopsTheBallAtTheFirstImpact) {
  const BallDrop model = ball(0.0);
  const RigidBounces ref(1.0, 0.0, 9.81, 0.0);
  for (const RunResult& r : {run_event_driven(model, options(), span(1.0)),
                             run_event_driven(model, model, options(), span(1.0))}) {
    ASSERT_TRUE(r.ok()) << r.message;
    ASSERT_EQ(r.contacts.size(), 1u);
    // The numerical flight's impact time to its tolerance (as in CvodeFlightAgrees...).
    EXPECT_NEAR(r.contacts[0].t_begin, ref.impact_time(1), 1e-8);
    EXPECT_EQ(r.contacts[0].v_out, 0.0);
    EXPECT_TRUE(r.apexes.empty());
    const auto& last = r.samples.back();
    EXPECT_EQ(last.t, 1.0);
    EXPECT_EQ(last.y[0], 0.0);
    EXPECT_EQ(last.y[1], 0.0);
    // E0 = m g h0 = 9.81 J, all booked as dissipated (to the flight's tolerance in speed).
    EXPECT_NEAR(last.dissipated, 9.81, 1e-8);
  }
}

TEST(EventDriven, PerfectlyElasticBallReturnsToItsHeightForever) {
  const BallDrop model = ball(1.0);
  const RigidBounces ref(1.0, 0.0, 9.81, 1.0);
  EXPECT_TRUE(std::isinf(ref.zeno_time()));
  const RunResult r = run_event_driven(model, model, options(), span(20.0));
  ASSERT_TRUE(r.ok());
  // 20 s / (2 t0 = 0.903 s) = 22 impacts, all of speed V, all apexes at h0.
  EXPECT_EQ(r.contacts.size(), 22u);
  for (const auto& a : r.apexes) EXPECT_NEAR(a.gap, 1.0, 64 * kEps);
  for (const auto& c : r.contacts) EXPECT_NEAR(c.v_in, -ref.V, 64 * kEps * ref.V);
}

TEST(EventDriven, CvodeFlightAgreesWithTheExactFlightToItsTolerance) {
  const BallDrop model = ball(0.8);
  const RigidBounces ref(1.0, 0.0, 9.81, 0.8);
  const RunResult r = run_event_driven(model, options(), span(3.0));
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_GE(r.contacts.size(), 6u);
  // Free flight is a polynomial of degree 2, which BDF of order >= 2 integrates exactly, so the
  // error is set by root location and the first low-order steps: a few rtol of T.
  for (std::size_t n = 1; n <= 6; ++n)
    EXPECT_NEAR(r.contacts[n - 1].t_begin, ref.impact_time(n), 1e-8) << "impact " << n;
  for (std::size_t n = 1; n <= 5; ++n)
    EXPECT_NEAR(r.apexes[n - 1].gap, ref.apex_height(n), 1e-8) << "apex " << n;
}

TEST(EventDriven, ImpactCapEndsTheRunWithZenoStatus) {
  const BallDrop model = ball(0.8);
  EventOptions o = options();
  const SolveOptions o_span = span(6.0);
  o.max_events = 10;
  const RunResult r = run_event_driven(model, model, o, o_span);
  EXPECT_EQ(r.status, Status::ZenoLimit);
  const RigidBounces ref(1.0, 0.0, 9.81, 0.8);
  EXPECT_NEAR(r.t_reached, ref.impact_time(11), 1e-12);
  EXPECT_NE(r.message.find("more than 10 impacts"), std::string::npos);
}

// Each impulse books the kinetic energy it removes, (1 - e^2) of the normal part, so the ledger
// closes to rounding with the exact flight.
TEST(EventDriven, LedgerBooksEachImpulseLossExactly) {
  const BallDrop model = ball(0.8);
  const RunResult r = run_event_driven(model, model, options(), span(3.0));
  ASSERT_TRUE(r.ok());
  for (const auto& s : r.samples)
    EXPECT_NEAR(s.energy + s.dissipated, r.energy0, 64 * kEps * r.energy0) << "t = " << s.t;
  // After the first impact: m V^2 (1 - e^2) / 2 is gone.
  const RigidBounces ref(1.0, 0.0, 9.81, 0.8);
  const double first_loss = 0.5 * ref.V * ref.V * (1 - 0.64);
  for (const auto& s : r.samples) {
    if (s.t > ref.T1 && s.t < ref.impact_time(2)) {
      EXPECT_NEAR(s.dissipated, first_loss, 64 * kEps * r.energy0);
    }
  }
}

// The closed-form rigid trajectory (work_precision's reference) is the exact-flight solution at
// every sample (to rounding in the impact times, a few ulps times V), for elastic and lossy balls.
TEST(EventDriven, ExactFlightFollowsTheClosedFormTrajectory) {
  for (double e : {1.0, 0.8}) {
    const BallDrop model = ball(e);
    const RunResult r = run_event_driven(model, model, options(), span(3.5));
    ASSERT_TRUE(r.ok());
    const double V = std::sqrt(2 * 9.81);
    for (const auto& s : r.samples) {
      const BallState ref = rigid_ball_state(1.0, 0.0, 9.81, e, s.t);
      EXPECT_NEAR(s.y[0], ref.x, 1e-12) << "e = " << e << ", t = " << s.t;
      EXPECT_NEAR(s.y[1], ref.v, 1e-12 * V) << "e = " << e << ", t = " << s.t;
    }
  }
}

// A column of balls dropped onto the floor: impulses pass up and down the touching column within
// an instant, and contacts rest once their bounces are slow. Two defects ended such runs or made
// them silently wrong: a ball landing on one at rest on the floor pushed it into the floor without
// the floor's impact (the resting ball kept that velocity without moving, and the contact above
// closed again "not approaching": unresolved, for e = 0.5 and 0.8); and two balls leaving an impact
// together (e = 1) were put at rest on each other, which held the upper one in mid-air at its speed
// while the lower flew: the energy ledger ran off by 60 times the drop's energy. The ledger
// E + D = E0 holds now to the flight's tolerance (rtol 1e-8 over a few hundred impacts: 1e-6 of
// E0), and no pair overlaps by more than the flight resolves (100 atol, its rest height).
TEST(EventDriven, ADroppedColumnKeepsItsEnergyLedgerAndNeverOverlaps) {
  for (std::size_t n : {2u, 3u, 4u})
    for (double e : {0.0, 0.5, 0.8, 1.0}) {
      const BallStack column({.n = n, .drop = 0.02, .e = e});
      EventOptions o;
      o.integrator.rtol = 1e-8;
      o.integrator.atol = 1e-10;
      const RunResult r = run_event_driven(column, o, {.t_end = 1.0, .sample_dt = 1e-3});
      ASSERT_TRUE(r.ok()) << "n " << n << ", e " << e << ": " << r.message;
      for (const auto& s : r.samples) {
        ASSERT_NEAR(s.energy + s.dissipated, r.energy0, 1e-6 * r.energy0)
            << "n " << n << ", e " << e << ", t " << s.t;
        for (std::size_t i = 0; i < n; ++i)
          ASSERT_GT(column.gap(i, s.y), -100 * o.integrator.atol)
              << "n " << n << ", e " << e << ", contact " << i << ", t " << s.t;
      }
    }
}

// Plastic impacts between free bodies (no gravity presses them together): a chain of touching
// balls struck at one end, the 3-D cradle at elasticity 0. Each pair that leaves an impact together
// was put at rest, and resting took it out of the sequential rule and the root finding while the
// bodies it joins went on being struck: the ledger E + D = E0 was off by 1000 times E0 (chain) and
// 20000 times (cradle). They stay free now; the ledger holds to the flight's tolerance.
TEST(EventDriven, PlasticImpactsBetweenFreeBodiesKeepTheLedger) {
  std::vector<std::pair<std::string, std::unique_ptr<Dynamics>>> scenes;
  for (double n : {3.0, 4.0, 6.0})
    scenes.emplace_back(fmt::format("chain of {}", n),
                        make_scene("ball-chain", {{"n", n}, {"e", 0.0}}, "hooke"));
  scenes.emplace_back("3-D cradle", make_scene("cradle", {{"elasticity", 0.0}}));
  for (const auto& [what, scene] : scenes) {
    const RunResult r = solve(*scene, {.name = "event-ode"}, {.t_end = 0.05, .sample_dt = 1e-3});
    ASSERT_TRUE(r.ok()) << what << ": " << r.message;
    for (const auto& s : r.samples)
      ASSERT_NEAR(s.energy + s.dissipated, r.energy0, 1e-6 * r.energy0) << what << ", t " << s.t;
  }
}

// A ball that starts on the floor moving down strikes it at once. The exact flight looked for
// impacts strictly after each leg's start, so the ball fell through the floor (47 m down after
// 3 s, "success", E + D 2e8 times E0); the numerical flight found it. Now both: at e = 1 it leaves
// at 1 m/s and rises exactly v0^2 / (2g); at e = 0 it rests at once.
TEST(EventDriven, ABallThrownDownFromTheFloorStrikesItAtOnce) {
  for (const double e : {1.0, 0.0}) {
    const BallDrop model({.h0 = 0.0, .v0 = -1.0, .e = e});
    const RunResult exact = run_event_driven(model, model, {}, {.t_end = 1.0, .sample_dt = 0.01});
    const RunResult numerical = run_event_driven(model, {}, {.t_end = 1.0, .sample_dt = 0.01});
    for (const RunResult* r : {&exact, &numerical}) {
      ASSERT_TRUE(r->ok()) << r->message;
      ASSERT_FALSE(r->contacts.empty());
      EXPECT_NEAR(r->contacts.front().t_begin, 0.0, 1e-15) << r->method;  // (the numerical: 4e-26 s)
      for (const auto& x : r->samples) ASSERT_GE(x.y[0], -1e-12) << r->method << ", t " << x.t;
    }
    // The closed-form flight and Newton's law keep E + D = E0 (0.5 J) to a few ulps.
    for (const auto& x : exact.samples) EXPECT_NEAR(x.energy + x.dissipated, exact.energy0, 1e-15) << x.t;
    if (e == 1.0) {
      ASSERT_FALSE(exact.apexes.empty());
      EXPECT_NEAR(exact.apexes.front().gap, 1.0 / (2 * 9.81), 1e-15);
    } else {
      EXPECT_EQ(exact.contacts.size(), 1u);
      EXPECT_EQ(exact.samples.back().y[1], 0.0);
    }
  }
}

// A column that bounces to rest is still: every ball's velocity is zero once its contact rests.
// An impulse from above drove a resting contact together slower than the rest speed (1e-7 m/s) and
// left that approach in the rested ball's frozen state (a column of four, e = 0.5: -8e-8 ... -2.3e-7
// m/s at the end). The support takes it now; what remains is the sequential rule's rounding floor,
// 1e-12 of the drop's impact speed (1.4 m/s) per impulse a ball takes at an instant.
TEST(EventDriven, AColumnBouncedToRestIsStill) {
  for (double e : {0.0, 0.5, 0.9}) {
    const BallStack column({.n = 4, .drop = 0.1, .e = e});
    EventOptions o;
    o.integrator.method = "gsl-rk8pd";
    o.integrator.rtol = 1e-10;
    o.integrator.atol = 1e-13;
    const RunResult r = run_event_driven(column, o, {.t_end = 3.0, .sample_dt = 3.0});
    ASSERT_TRUE(r.ok()) << "e " << e << ": " << r.message;
    const Vector& y = r.samples.back().y;
    for (Eigen::Index b = 0; b < 4; ++b)
      EXPECT_LE(std::abs(y[2 * b + 1]), 1e-10) << "e " << e << ", ball " << b;
  }
}

// A ball that leaves the one below it slowly while that one still flies is not pushed into it and
// stays free; a later impulse of the same instant stops the lower ball on the floor, and the upper
// one's hop (1e-5 m/s, 5e-12 m) is then far below what the flight resolves: these drops (of 12 in
// 795 random columns) ended 'unresolved' at the next root, whatever atol or rest height the
// message advised. After the instant's sweeps every such hop rests now. Each column comes to rest
// with its ledger and gaps as ADroppedColumnKeepsItsEnergyLedgerAndNeverOverlaps holds them, and
// still to the sequential rule's rounding (AColumnBouncedToRestIsStill): measured, 1.3e-11 m/s.
// The last, a tall column, holds the rule that rests only pairs the flight pushes together: resting
// pairs that leave an impact together as well (both falling) ended it 'unresolved' (a bounce of
// 7e-18 m), which the shorter columns of the tests before did not notice.
TEST(EventDriven, AHopThatALaterImpulseOfItsInstantPushesDownRests) {
  struct Drop {
    std::size_t n;
    double e, drop;
  };
  for (const Drop d : {Drop{2, 0.3, 0.2}, Drop{5, 0.6, 0.05}, Drop{6, 0.7, 0.005}, Drop{6, 0.6, 0.2},
                       Drop{8, 0.7, 0.05}, Drop{30, 0.15, 2e-4}}) {
    const BallStack column({.n = d.n, .drop = d.drop, .e = d.e});
    const RunResult r = solve(column, {.name = "event-ode"}, {.t_end = 3.0, .sample_dt = 1e-3});
    const std::string what = fmt::format("{} balls, e {}, drop {} m", d.n, d.e, d.drop);
    ASSERT_TRUE(r.ok()) << what << ": " << r.message;
    for (const auto& s : r.samples) {
      ASSERT_NEAR(s.energy + s.dissipated, r.energy0, 1e-6 * r.energy0) << what << ", t " << s.t;
      for (std::size_t i = 0; i < d.n; ++i)
        ASSERT_GT(column.gap(i, s.y), -100 * IntegratorOptions{}.atol) << what << ", contact " << i;
    }
    const Vector& y = r.samples.back().y;
    for (std::size_t b = 0; b < d.n; ++b)
      EXPECT_LE(std::abs(y[static_cast<Eigen::Index>(2 * b + 1)]), 1e-10) << what << ", ball " << b;
  }
}

// A striker into a row of touching balls at e = 0: the sequential rule's impulses converge to the
// plastic answer, every ball at v0 / n (momentum, one common velocity). They pass back and forth
// along the row, and rescanning from the first contact after each impulse took exponentially many
// (4953 for five balls; eight ended at the million-impact limit). Swept in order, as Gauss–Seidel,
// they take ~n^3 (1112 for eight, 3856 for twelve). The iteration stops at approaches below 1e-12 of
// the striker's speed, so each velocity is v0 / n to ~n 1e-12 v0.
TEST(EventDriven, APlasticRowOfTouchingBallsMovesOffTogether) {
  for (const double n : {8.0, 12.0}) {
    const auto chain = make_scene("ball-chain", {{"n", n}, {"e", 0.0}}, "hooke");
    const RunResult r = solve(*chain, {.name = "event-ode"}, {.t_end = 0.05, .sample_dt = 0.05});
    ASSERT_TRUE(r.ok()) << n << " balls: " << r.message;
    const Vector& y = r.samples.back().y;
    for (Eigen::Index b = 0; b < static_cast<Eigen::Index>(n); ++b)
      EXPECT_NEAR(y[2 * b + 1], 1.0 / n, 1e-10) << n << " balls, ball " << b;
    EXPECT_NEAR(r.samples.back().energy + r.samples.back().dissipated, r.energy0, 1e-12 * r.energy0) << n;
  }
}

// Rigid impulses have no springs, but their energy counted the scene's spring at an overlap, which
// touching balls have to rounding (1e-17 m): newton_cradle's event row showed an energy error of
// 6e-11 at k = 1e20 and, at k = 1e300, 3e268 J in a 0.05 J cradle (which now ends a run as
// diverged). The law's k must not matter to an impulse method: the textbook cradle (the last
// ball leaves at v0, the rest stop) and its energy to rounding, at any k, in either contact order
// (the exact flight does not run a chain: no closed form for its pairs' flights).
TEST(EventDriven, TheLawsStiffnessDoesNotEnterTheEnergyOfRigidImpacts) {
  for (const double k : {1e6, 1e20, 1e300}) {
    const auto cradle = make_scene("ball-chain", {{"n", 5.0}, {"e", 1.0}, {"k", k}}, "hooke");
    for (const char* method : {"event-ode", "event-ode-reversed"}) {
      const RunResult r = solve(*cradle, {.name = method}, {.t_end = 0.05, .sample_dt = 0.01});
      ASSERT_TRUE(r.ok()) << method << " at k = " << k << ": " << r.message;
      const Vector& y = r.samples.back().y;
      for (Eigen::Index b = 0; b < 5; ++b)
        EXPECT_NEAR(y[2 * b + 1], b == 4 ? 1.0 : 0.0, 1e-10) << method << k;
      for (const auto& sample : r.samples)  // e = 1: nothing lost, the energy kept to rounding
        EXPECT_NEAR(sample.energy + sample.dissipated, r.energy0, 1e-13 * r.energy0)
            << method << " k = " << k;
    }
  }
}

// A ball striking a free cuboid off its centre at elasticity 0: the two leave the impact together
// and the cuboid's turn keeps pressing them into each other, a sustained contact between free
// bodies that impulses do not model. The ball passed into the cuboid with no impact located, and
// the run ended 'success' with 700 times its initial energy (the overlap's spring). It ends as
// unresolved now, at the first sample where the overlap exceeds the flight's resolution (100 atol),
// naming the contact; at e = 0.5 the bodies part and the run succeeds.
TEST(EventDriven, BodiesThatGoOnPressingTogetherAfterAnImpactEndTheRun) {
  const auto plastic = make_scene("off-centre", {{"elasticity", 0.0}});
  const RunResult r = solve(*plastic, {.name = "event-ode"}, {.t_end = 0.5, .sample_dt = 1e-3});
  EXPECT_EQ(r.status, Status::Unresolved) << r.message;
  EXPECT_NE(r.message.find("contact 0 overlaps by"), std::string::npos) << r.message;
  EXPECT_LT(r.t_reached, 0.01);
  // A scene that starts with its bodies inside each other says so (it ran on silently), built
  // directly (make_scene refuses it: Registries.AScenesBodiesMustStartApart).
  rigid::SceneParams big;
  big.radius = 0.194;
  const rigid::RigidScene inside = rigid::rigid_scene("spinning-box").make(big);
  const RunResult start = solve(inside, {.name = "event-ode"}, {.t_end = 0.1, .sample_dt = 1e-3});
  EXPECT_EQ(start.status, Status::Unresolved);
  EXPECT_NE(start.message.find("overlaps by 0.169 m at the start"), std::string::npos) << start.message;
  const auto elastic = make_scene("off-centre", {{"elasticity", 0.5}});
  const RunResult ok = solve(*elastic, {.name = "event-ode"}, {.t_end = 0.5, .sample_dt = 1e-3});
  ASSERT_TRUE(ok.ok()) << ok.message;
  EXPECT_NEAR(ok.samples.back().energy + ok.samples.back().dissipated, ok.energy0, 1e-6 * ok.energy0);
}

// A striker of small balls (m = 0.025 kg, r = 0.059 m) meeting two at once at elasticity 0: the
// sequential rule's plastic impulse left the second pair's gap rate at -6.9e-18 m/s (rounding,
// after an approach at 0.65 m/s) under GSL's flights, and the rule struck that pair again, each
// impulse lost to the same rounding, until the impact limit of a million (CVODE's flight happened
// to round to >= 0). An approach below 1e-12 of the instant's fastest is rounding now: every
// flight ends the instant in two impacts, and the runs agree to the flights' resolution (100 atol).
// Without gravity the balls' velocities are constant between impacts, whose losses are booked as the
// energy they take: the ledger holds to rounding.
TEST(EventDriven, APlasticImpulseLeftApproachingByRoundingIsNotStruckAgain) {
  const auto wedge = make_scene("wedge", {{"m", 0.025}, {"radius", 0.059}, {"elasticity", 0.0}});
  const SolveOptions span{.t_end = 0.05, .sample_dt = 0.05};
  const RunResult ref = solve(*wedge, {.name = "event-ode"}, span);
  ASSERT_TRUE(ref.ok()) << ref.message;
  for (const char* flight : {"gsl-msbdf", "gsl-rk8pd", "gsl-rkf45"}) {
    Method m{.name = "event-ode"};
    m.integrator.method = flight;
    const RunResult r = solve(*wedge, m, span);
    ASSERT_TRUE(r.ok()) << flight << ": " << r.message;
    EXPECT_EQ(r.contacts.size(), ref.contacts.size()) << flight;
    const double atol = m.integrator.atol;
    EXPECT_LT((r.samples.back().y - ref.samples.back().y).cwiseAbs().maxCoeff(), 100 * atol) << flight;
    EXPECT_NEAR(r.samples.back().energy + r.samples.back().dissipated, r.energy0, 1e-12 * r.energy0)
        << flight;
  }
}

// A state beyond the doubles ends a run as non-finite-state, whatever the method checks itself. The
// exact bounces of a 1e308 kg ball (an impulse of 8e308 N s) and of one thrown up at 1e308 m/s once
// reported success with a state of inf. Their energies are beyond the doubles, which solve() now
// refuses; the same two failures, with energies that are doubles: a 1.5e308 kg ball at 1 m/s
// (g = 1 m/s^2 from 0.5 m: 7.5e307 J; its impulse 2.7e308 N s) ends at its impact, naming the
// impulse; one thrown at 1e154 m/s without gravity (past 1.8e308 m after 1.8e154 s; the
// state-growth line, which would end it first, drawn off) at its first sample that is not finite
// (solve() looks at every method's samples), keeping only those before it.
TEST(EventDriven, AStateBeyondTheDoublesEndsTheRunInsteadOfSucceeding) {
  const Method exact{.name = "event-exact"};
  const RunResult heavy = solve(BallDrop({.m = 1.5e308, .g = 1.0, .h0 = 0.5}), exact, {.t_end = 3.0});
  EXPECT_EQ(heavy.status, Status::NonFiniteState) << heavy.message;
  EXPECT_NEAR(heavy.t_reached, 1.0, 1e-12);  // sqrt(2 h0 / g)
  EXPECT_NE(heavy.message.find("contact 0's impulse (inf N s) left the state not finite"), std::string::npos)
      << heavy.message;
  const RunResult thrown = solve(BallDrop({.g = 0.0, .v0 = 1e154}), exact,
                                 {.t_end = 3e154,
                                  .sample_dt = 1e152,
                                  .limits = {.max_state_growth = std::numeric_limits<double>::infinity()}});
  EXPECT_EQ(thrown.status, Status::NonFiniteState) << thrown.message;
  EXPECT_NEAR(thrown.t_reached, 1.8e154, 1e152);  // 1 + 1e154 t passes DBL_MAX at t = 1.797e154 s
  EXPECT_NE(thrown.message.find("the state is not finite at t = 1.8e+154 s (sample 180 of 301)"),
            std::string::npos)
      << thrown.message;
  for (const RunResult* r : {&heavy, &thrown}) {
    ASSERT_FALSE(r->samples.empty());
    for (const auto& s : r->samples) EXPECT_TRUE(s.y.allFinite()) << r->method << ", t " << s.t;
    EXPECT_LT(r->samples.back().t, r->t_reached);
  }
}
