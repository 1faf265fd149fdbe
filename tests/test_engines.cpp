// The engines (MuJoCo, Bullet, ODE) against what can be derived for them:
//  - MuJoCo's direct solref and ODE's soft ERP/CFM, set from a Kelvin–Voigt law by the converters
//    of models/engine_conventions, reproduce that clamped contact without gravity (closed form)
//    to the first order of their step: the error halves with the step; so does XPBD. Their
//    contacts only push: given the law that pulls, each converges to the clamped one all the same
//    (its restitution 0.808 for the pulling law's 0.8 at e = 0.8), as their descriptions say;
//  - the stiffness and damping each engine really applies, measured back from a head-on impact
//    of two balls (duration and restitution inverted through the closed form), are the law's:
//    the round trip of the converters through the engines;
//  - Bullet tuned and ODE with bounce give Newton's law within their step's error;
//  - ODE's direct LCP step on a touching cradle is the simultaneous impact's answer;
//  - solves run in threads give their serial answers (ODE's and Siconos' global state);
//  - the energy ledger of impacts on contacts that share a body closes.
#include "contact_ode/analysis/references.hpp"
#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/models/ball_chain.hpp"
#include "contact_ode/models/ball_drop.hpp"
#include "contact_ode/models/ball_stack.hpp"
#include "contact_ode/models/scene_registry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <thread>

using namespace contact;

namespace {

bool built(const std::string& method) {
  for (const auto& name : method_names())
    if (name == method) return true;
  return false;
}

#define REQUIRE_ENGINE(method) \
  if (!built(method)) GTEST_FAIL() << method << " is not built: " << engines_missing()

constexpr double kE = 0.8, kV = 4.0;

// The clamped Kelvin–Voigt law of stiffness k on a ball of mass m tuned to e, and its damping ratio.
KelvinVoigt law_of(double k, double m) { return kelvin_voigt_for_restitution(k, m, kE, true); }

// A ball entering the floor at kV without gravity: its first contact, under the clamped law or
// the one that pulls.
ContactRecord gravity_free_impact(const std::string& method, double dt, bool pulls) {
  const KelvinVoigt law = pulls ? kelvin_voigt_for_restitution(1e5, 1.0, kE, false) : law_of(1e5, 1.0);
  const BallDrop ball({.m = 1.0, .g = 0.0, .h0 = 0.01, .v0 = -kV, .e = kE, .law = law});
  const RunResult r = solve(ball, {.name = method, .dt = dt}, {.t_end = 0.02, .sample_dt = 0.02});
  EXPECT_TRUE(r.ok()) << r.message;
  EXPECT_FALSE(r.contacts.empty()) << method;
  return r.contacts.empty() ? ContactRecord{} : r.contacts.front();
}

// Restitution error against the closed form at dt, dt/2, dt/4: first order, and within
// 2 w dt of it at the finest step (semi-implicit and implicit Euler's restitution errors are
// w dt times a constant of order one).
void expect_first_order_restitution(const std::string& method) {
  const double zeta = damping_ratio_for_restitution(kE), exact = clamped_kelvin_voigt_restitution(zeta);
  const double w = std::sqrt(1e5), dt = 2.5e-4;
  for (const bool pulls : {false, true}) {
    double err[3];
    for (int i = 0; i < 3; ++i)
      err[i] = std::abs(gravity_free_impact(method, dt / (1 << i), pulls).restitution() - exact);
    for (int i = 0; i < 2; ++i) {
      EXPECT_GT(err[i] / err[i + 1], 1.6) << method << " step " << dt / (1 << i) << " pulls " << pulls;
      EXPECT_LT(err[i] / err[i + 1], 2.5) << method << " step " << dt / (1 << i) << " pulls " << pulls;
    }
    EXPECT_LT(err[2], 2 * w * dt / 4) << method << " pulls " << pulls;
  }
}

// Two balls of 0.1 kg head-on at 1 m/s, touching law k = 1e4 N/m tuned to e: the contact's
// duration and restitution, inverted through the clamped closed form, give back k and c.
LinearLaw measured_law(const std::string& method, double dt) {
  const double m = 0.1, k = 1e4, w = 2 / m;
  const BallChain pair(
      {.n = 2, .m = m, .v0 = 1.0, .approach = 1e-3, .spacing = 0, .e = kE, .law = law_of(k, 1 / w)});
  const RunResult r = solve(pair, {.name = method, .dt = dt}, {.t_end = 0.02, .sample_dt = 0.02});
  EXPECT_TRUE(r.ok()) << r.message;
  if (r.contacts.empty() || !r.contacts.front().closed()) {
    ADD_FAILURE() << method << ": no closed contact";
    return {0, 0};
  }
  const ContactRecord& c = r.contacts.front();
  // e_c(zeta) decreases monotonically: bisection.
  double lo = 0, hi = 0.99;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (clamped_kelvin_voigt_restitution(mid) > c.restitution() ? lo : hi) = mid;
  }
  const double zeta = 0.5 * (lo + hi), s = std::sqrt(1 - zeta * zeta);
  // Duration until the overlap closes: ((pi - 2 asin zeta) / s + 2 zeta) / w0.
  const double w0 = ((std::numbers::pi - 2 * std::asin(zeta)) / s + 2 * zeta) / c.duration();
  return {w0 * w0 / w, 2 * zeta * w0 / w};
}

}  // namespace

TEST(MujocoSpring, IsTheClampedKelvinVoigtContactToFirstOrder) {
  REQUIRE_ENGINE("mujoco-spring");
  expect_first_order_restitution("mujoco-spring");
}

TEST(OdeSpring, IsTheClampedKelvinVoigtContactToFirstOrder) {
  REQUIRE_ENGINE("ode-spring");
  expect_first_order_restitution("ode-spring");
}

TEST(Xpbd, IsTheClampedKelvinVoigtContactToFirstOrder) { expect_first_order_restitution("xpbd"); }

// At dt = 2e-6 (w0 dt = 9e-4, 3500 steps per contact) the measured law is the given one to the
// step's error: 0.2 % in k (about 2 w0 dt: the duration is read to a step, w0 is first order),
// 1.5 % in c (the restitution's first-order error, ~1.5 w0 dt, divided by pi zeta ~ 0.2 in the
// inversion: ~7 w0 dt = 0.6 %, with room for the constant). Measured: MuJoCo 4e-4 and 6e-4,
// ODE 5e-4 and 7e-3.
TEST(EngineConventions, StiffnessAndDampingRoundTripThroughTheEngines) {
  const double m = 0.1, k = 1e4, c = law_of(k, m / 2).c;
  for (const char* method : {"mujoco-spring", "ode-spring"}) {
    REQUIRE_ENGINE(method);
    const LinearLaw got = measured_law(method, 2e-6);
    EXPECT_NEAR(got.k / k, 1.0, 0.002) << method;
    EXPECT_NEAR(got.c / c, 1.0, 0.015) << method;
  }
}

// Newton's law at the step: the engines' semi-implicit Euler falls g dt t / 2 ahead of the exact
// flight (half a step early at the impact, as V = g T1), and the ball is caught within a step of
// touching (overlap at most V dt) and leaves at e times the step's speed (within g dt of V): the
// first impact is within 2 dt of the exact time, the first apex e^2 h0 to within (1 + e^2) V dt.
TEST(BulletTunedAndOdeBounce, GiveNewtonsLawWithinTheirStep) {
  const double h0 = 1.0, g = 9.81, V = std::sqrt(2 * g * h0);
  const RigidBounces exact(h0, 0.0, g, kE);
  for (const char* method : {"bullet-tuned", "ode"}) {
    REQUIRE_ENGINE(method);
    for (double dt : {1e-3, 1e-4}) {
      const BallDrop ball({.m = 1.0, .g = g, .h0 = h0, .v0 = 0.0, .e = kE, .law = Hooke{1e5}});
      const RunResult r = solve(ball, {.name = method, .dt = dt}, {.t_end = 1.2, .sample_dt = 0.1});
      ASSERT_TRUE(r.ok()) << r.message;
      ASSERT_FALSE(r.contacts.empty() || r.apexes.empty()) << method;
      EXPECT_NEAR(r.contacts.front().t_begin, exact.T1, 2 * dt) << method << " dt " << dt;
      EXPECT_NEAR(r.apexes.front().gap, kE * kE * h0, (1 + kE * kE) * V * dt) << method << " dt " << dt;
      EXPECT_NEAR(r.contacts.front().restitution(), kE, kE * g * dt / V + 1e-12) << method << " dt " << dt;
    }
  }
}

// ODE's contact asks for the larger of the bounce, -e u, and its ERP push-out, ERP times the
// overlap per step (world ERP 0.2), and a landing leaves up to (V + g dt) dt of overlap: for
// e < 0.2 the push-out can win, and a plastic landing (e = 0) bounces, as high as (0.2 (V + g dt))^2 /
// 2g, 4 % of h0, and far outside the step's bound on Newton's law, V dt (3.4 cm at 1 ms and 2.7
// mm at 0.1 ms, measured: the overlap the landing step leaves is the step's phase). The README's
// ODE bullet says so.
TEST(Ode, ItsPushOutBouncesAPlasticLanding) {
  REQUIRE_ENGINE("ode");
  const double h0 = 1.0, g = 9.81, V = std::sqrt(2 * g * h0);
  for (double dt : {1e-3, 1e-4}) {
    const BallDrop ball({.m = 1.0, .g = g, .h0 = h0, .v0 = 0.0, .e = 0.0, .law = Hooke{1e5}});
    const RunResult r = solve(ball, {.name = "ode", .dt = dt}, {.t_end = 1.0, .sample_dt = 0.01});
    ASSERT_TRUE(r.ok()) << r.message;
    ASSERT_FALSE(r.apexes.empty()) << dt;
    EXPECT_GT(r.apexes.front().gap, V * dt) << dt;
    EXPECT_LE(r.apexes.front().gap, std::pow(0.2 * (V + g * dt), 2) / (2 * g)) << dt;
    EXPECT_NEAR(r.apexes.front().gap, dt == 1e-3 ? 0.034 : 0.0027, dt == 1e-3 ? 5e-4 : 5e-5);  // the README's
  }
}

// Bullet multiplies the two bodies' restitutions: spheres carry sqrt(e) and the floor e / sqrt(e),
// which for e = 0 was 0 / 0, a NaN restitution and a NaN state a few steps after a column dropped
// onto the floor landed. Perfectly inelastic, the bottom ball lands and stays on the floor (its
// contact never ends), and the column is at rest at the end.
TEST(Bullet, AnInelasticColumnLandsAndStays) {
  for (const char* method : {"bullet", "bullet-tuned"}) {
    REQUIRE_ENGINE(method);
    const BallStack column({.n = 2, .m = 3.0, .drop = 0.01, .e = 0.0, .law = Hooke{15782.0}});
    // 2941 whole steps: after a shorter last step Bullet's position correction (depth over step) is
    // no longer in balance with the earlier steps' and moves the resting balls by a few um/s.
    const RunResult r =
        solve(column, {.name = method, .dt = 1.7e-4}, {.t_end = 2941 * 1.7e-4, .sample_dt = 0.01});
    ASSERT_TRUE(r.ok()) << method << ": " << r.message;
    for (const auto& c : r.contacts) {
      if (c.contact == 0) {
        EXPECT_FALSE(c.closed()) << method << ": left the floor at " << c.t_end;
      }
    }
    // At rest: 1e-6 m/s, under a thousandth of g dt (1.7e-3 m/s, the speed one step of gravity
    // gives), so a ball still falling, or still being pushed out of an overlap, would show.
    const Vector& y = r.samples.back().y;
    ASSERT_TRUE(y.allFinite()) << method;
    EXPECT_LT(std::abs(y[1]), 1e-6) << method;
    EXPECT_LT(std::abs(y[3]), 1e-6) << method;
  }
}

// Bullet at its defaults pushes overlaps out through the velocities (Baumgarte below 4 cm), and on
// a touching row struck at e = 1 that push-out is bounced back: the row gains energy, no impact
// booking any loss (e = 1). Measured: 40 balls end 2 s with 83 times their energy, 100 diverge at
// 0.13 s (the run's energy guard, a typed failure). Tuned (split impulses, which leave the
// velocities alone), the row gains nothing (it loses six tenths of its energy, unbooked, which
// this test does not explain). The README's engines table says so.
TEST(Bullet, AtItsDefaultsATouchingRowStruckElasticallyGainsEnergy) {
  REQUIRE_ENGINE("bullet");
  const BallChain forty({.n = 40});
  const RunResult r = solve(forty, {.name = "bullet", .dt = 1e-3}, {.t_end = 2.0, .sample_dt = 2.0});
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_EQ(r.samples.back().dissipated, 0.0);
  // Half the 83 times measured: the growth is an instability, whose rate rounding may shift.
  EXPECT_GT(r.samples.back().energy, 40 * r.energy0);
  const RunResult tuned =
      solve(forty, {.name = "bullet-tuned", .dt = 1e-3}, {.t_end = 2.0, .sample_dt = 2.0});
  ASSERT_TRUE(tuned.ok()) << tuned.message;
  EXPECT_LT(tuned.samples.back().energy, tuned.energy0);
  const RunResult hundred = solve(BallChain({.n = 100}), {.name = "bullet", .dt = 1e-3}, {.t_end = 2.0});
  EXPECT_EQ(hundred.status, Status::Diverged) << hundred.message;
}

// Bullet at its defaults solves a contact before it touches. Its sphere-plane test makes a contact
// point once the gap d is below the contact-breaking threshold, 0.02 of the sphere's bounding
// radius sqrt(3) r (the corner of its box): tau = 3.46 mm for the drop's 0.1 m ball. Its solver
// then asks the step to bounce at e of the approach u it began with and to end no deeper than the
// floor: u' = e |u| - d / dt (btSequentialImpulseConstraintSolver, velocityError at a positive
// distance). A push at d > e |u| dt spends the bounce on slowing the ball short of the floor, and
// the pushes after it take e of ever slower approaches, until one falls below the 0.2 m/s threshold.
// A push comes at the first step with d < min(tau, (1 + e) |u| dt): so the drop always bounces when
// e V dt > tau (dt > 0.98 ms), never when (1 + e) V dt < tau (dt < 0.43 ms), and between them as its
// steps fall (measured from 0.3 to 1 ms: none below 0.54 ms, every one from 0.82 ms). The engines
// experiment's steps of 0.5 and 0.25 ms are why the paper finds that its ball stops bouncing.
TEST(Bullet, AtItsDefaultsABallDroppedWithSmallStepsIsStoppedShortOfTheFloor) {
  REQUIRE_ENGINE("bullet");
  const double e = 0.8, g = 9.81, V = std::sqrt(2 * g);
  for (const double h0 : {1.0, 1.01, 1.02}) {
    const BallDrop ball({.m = 1.0, .g = g, .h0 = h0, .e = e});
    const double tau = 0.02 * std::sqrt(3.0) * ball.sphere_line().radius;
    // 10 % below the never-bounce bound and 20 % above the always-bounce one: the speed at the first
    // push is V to 0.2 % (the ball is within tau of the floor).
    for (const double dt : {0.2e-3, 0.3e-3, 0.38e-3, 1.2e-3, 1.5e-3, 2e-3}) {
      ASSERT_TRUE((1 + e) * V * dt < 0.9 * tau || e * V * dt > 1.2 * tau) << dt;
      const RunResult r = solve(ball, {.name = "bullet", .dt = dt}, {.t_end = 1.0, .sample_dt = dt});
      ASSERT_TRUE(r.ok()) << r.message;
      ASSERT_FALSE(r.contacts.empty()) << dt;
      const bool bounces = e * V * dt > tau;
      EXPECT_EQ(r.contacts.front().v_out > 0, bounces) << "h0 " << h0 << ", dt " << dt;
      EXPECT_EQ(r.apexes.empty(), !bounces) << "h0 " << h0 << ", dt " << dt;
      // The first push: the first step whose velocity gains more than gravity takes from it (1e-9 m/s:
      // far above the rounding of u - g dt, 1e-15, far below any push). Where the ball does not bounce
      // it comes before the ball touches (at d >= e |u| dt > 0); wherever it comes before, it is Bullet's
      // target to a few ulps of d / dt ~ 10 m/s, 2e-15 each (measured 1.3e-15 at most).
      std::size_t j = 1;
      while (j < r.samples.size() && r.samples[j].y[1] - r.samples[j - 1].y[1] <= -g * dt + 1e-9) ++j;
      ASSERT_LT(j, r.samples.size()) << "no push, h0 " << h0 << ", dt " << dt;
      const double d = r.samples[j - 1].y[0], u = r.samples[j - 1].y[1], u_next = r.samples[j].y[1];
      if (!bounces) {
        EXPECT_GT(d, 0) << "h0 " << h0 << ", dt " << dt;
      }
      if (d > 0) {
        EXPECT_LT(d, tau) << dt;
        EXPECT_NEAR(u_next, e * std::abs(u) - d / dt, 1e-14) << "h0 " << h0 << ", dt " << dt;
      }
    }
  }
}

// A column resting on the floor from the start: each engine's first step pushes its contacts to
// hold the balls against gravity, which takes no energy (the balls stay where they are). The push
// was booked as an impact at the speed it implies, J w / (1 + e): 1.6e-6 J for one 0.1 kg ball at
// dt = 1 ms, and for the stack table's 8-ball column 1.8e-4 of its energy, all of Siconos' drift
// there while its state moved by rounding alone. The first step books nothing; Siconos' column
// books nothing in 0.5 s, and its state and ledger move by the rounding of its 500 steps' LCP
// solves (speeds of 1e-14 m/s after 0.5 s; 1e-13 is ten times what was measured).
TEST(EngineRuns, AColumnRestingFromTheStartLosesNothingToItsFirstPush) {
  for (const char* method : {"mujoco", "bullet", "bullet-tuned", "ode-quick", "siconos"}) {
    REQUIRE_ENGINE(method);
    for (std::size_t n : {1, 4}) {
      const BallStack column({.n = n});
      const RunResult r = solve(column, {.name = method, .dt = 1e-3}, {.t_end = 1e-3, .sample_dt = 1e-3});
      ASSERT_TRUE(r.ok()) << method << ": " << r.message;
      EXPECT_EQ(r.samples.back().dissipated, 0.0) << method << ", " << n << " balls";
    }
  }
  REQUIRE_ENGINE("siconos");
  const BallStack column({.n = 8});
  const RunResult r = solve(column, {.name = "siconos", .dt = 1e-3}, {.t_end = 0.5, .sample_dt = 0.1});
  ASSERT_TRUE(r.ok()) << r.message;
  for (const Sample& s : r.samples) {
    EXPECT_EQ(s.dissipated, 0.0) << s.t;
    EXPECT_LT(s.y.cwiseAbs().maxCoeff(), 1e-13) << s.t;
    EXPECT_NEAR(s.energy, r.energy0, 1e-13 * r.energy0) << s.t;
  }
}

// A ball dropped from 1 m lands at v = sqrt(2 g h0) and Newton's law takes (1 - e^2) m g h0 of it.
// Every engine's ledger books that at its landing, on the gap rate its landing step began with,
// within (1 +- g dt / v)^2 of it (the step begins up to dt before or after the touch). Booked at the
// speed the engine's impulse implies, J w / (1 + e), it was MuJoCo's soft impulse (0.013 J for
// 3.53) and ODE's push-out (14.5 J of a 9.81 J drop, e = 0); Siconos books the impact itself.
TEST(EngineRuns, TheLedgerBooksALandingAtItsApproachSpeed) {
  const double g = 9.81, h0 = 1.0, dt = 1e-3, slack = 2 * g * dt / std::sqrt(2 * g * h0);
  for (double e : {0.0, 0.8}) {
    const BallDrop ball({.m = 1.0, .g = g, .h0 = h0, .v0 = 0.0, .e = e, .law = Hooke{1e5}});
    for (const char* method : {"mujoco", "bullet", "bullet-tuned", "ode", "ode-quick", "siconos"}) {
      REQUIRE_ENGINE(method);
      const RunResult r = solve(ball, {.name = method, .dt = dt}, {.t_end = 0.5, .sample_dt = 0.5});
      ASSERT_TRUE(r.ok()) << method << ": " << r.message;
      ASSERT_EQ(r.contacts.size(), 1U) << method << ", e = " << e;
      const double newton = (1 - e * e) * g * h0;
      EXPECT_NEAR(r.samples.back().dissipated, newton, slack * newton) << method << ", e = " << e;
    }
  }
}

// The ledger of impacts on contacts that share a body. A plastic strike at v0 = 2 m/s into two
// touching balls ends with the three at v0 / 3 and loses 2/3 of the energy; booked contact by
// contact as if each were alone, at the approach speed each impulse implies, it was 1.11 E0 (the
// ledger 0.44 E0 off for every engine). Each engine here ends at v0 / 3 to its solver's precision,
// and its ledger closes to 1e-4 of E0 (Bullet's iterations leave 6e-7; MuJoCo's soft contacts end
// the balls unequal, and dWorldStep's LCP fails on touching contacts, as the cradle test says).
// Siconos books each impact as it resolves it: a column of four balls dropped 0.2 m on the floor,
// e = 0.5, bouncing into rest with many impacts in a step, closes to 1e-6 of E0 (LSODAR at rtol
// 1e-10); booked once a step, from a step's summed impulses, it was off by 5 E0.
TEST(EngineRuns, TheLedgerBooksImpactsOfContactsThatShareABody) {
  const BallChain strike({.n = 3, .v0 = 2.0, .e = 0.0});
  for (const char* method : {"bullet", "bullet-tuned", "ode-quick", "siconos"}) {
    REQUIRE_ENGINE(method);
    const RunResult r = solve(strike, {.name = method, .dt = 1e-3}, {.t_end = 0.05, .sample_dt = 0.05});
    ASSERT_TRUE(r.ok()) << method << ": " << r.message;
    const Sample& end = r.samples.back();
    for (Eigen::Index b = 0; b < 3; ++b)
      EXPECT_NEAR(end.y[2 * b + 1], 2.0 / 3, 1e-5) << method << ", ball " << b;
    EXPECT_NEAR(end.dissipated, 2.0 / 3 * r.energy0, 1e-4 * r.energy0) << method;
    EXPECT_NEAR(end.energy + end.dissipated, r.energy0, 1e-4 * r.energy0) << method;
  }
  const BallStack dropped({.n = 4, .drop = 0.2, .e = 0.5});
  const RunResult r = solve(dropped, {.name = "siconos", .dt = 1e-3}, {.t_end = 2.0, .sample_dt = 0.1});
  ASSERT_TRUE(r.ok()) << r.message;
  for (const Sample& s : r.samples) EXPECT_NEAR(s.energy + s.dissipated, r.energy0, 1e-6 * r.energy0) << s.t;
}

// A cradle of n balls a millimetre apart struck at v0 with e = 1: a sequence of two-ball
// impacts, each exchanging the velocities, leaves only the last ball moving, at v0. Touching, the
// impacts are simultaneous, one LCP per step in ODE's dWorldStep: either it solves it, and the
// answer is the simultaneous impact's (striker (2/n - 1) v0, the others 2 v0 / n, as Moreau–Jean
// gives), or it reports that it could not, and the run is a typed failure with ODE's message.
// dWorldStep's pivoting LCP, which ode-spring steps with too, stops on contacts that touch at rest
// ("LCP internal error", typed), and which do is the rounding of the positions: a two-ball column
// stops at t = 0 for 77 of 200 radii from 5 cm to 1 m (measured), the same radii under both, and
// runs for the others; QuickStep runs them all. The README says "about two radii in five".
TEST(Ode, ItsPivotingStepperStopsOnTwoBallColumnsAsTheirRoundingFalls) {
  REQUIRE_ENGINE("ode");
  REQUIRE_ENGINE("ode-spring");
  REQUIRE_ENGINE("ode-quick");
  const auto stops = [](const char* method, double radius) {
    const RunResult r = solve(BallStack({.n = 2, .radius = radius}), {.name = method, .dt = 1e-3},
                              {.t_end = 0.01, .sample_dt = 0.01});
    if (r.ok()) return false;
    EXPECT_EQ(r.status, Status::SolverError) << method << " " << radius;
    EXPECT_EQ(r.t_reached, 0.0) << method << " " << radius;
    EXPECT_NE(r.message.find("LCP internal error"), std::string::npos) << r.message;
    return true;
  };
  int stopped = 0;
  const int radii = 200;
  for (int j = 0; j < radii; ++j) {
    const double radius = 0.05 + j * (0.95 / (radii - 1));
    const bool a = stops("ode", radius);
    EXPECT_EQ(stops("ode-spring", radius), a) << radius;
    EXPECT_FALSE(stops("ode-quick", radius)) << radius;
    stopped += a;
  }
  EXPECT_GT(stopped, radii * 3 / 10);
  EXPECT_LT(stopped, radii / 2);
}

TEST(Ode, CradleImpactsExchangeTheVelocities) {
  REQUIRE_ENGINE("ode");
  const std::size_t n = 5;
  for (double spacing : {1e-3, 0.0}) {
    const BallChain cradle(
        {.n = n, .m = 0.1, .v0 = 1.0, .approach = 1e-3, .spacing = spacing, .e = 1.0, .law = Hooke{1e6}});
    const RunResult r = solve(cradle, {.name = "ode", .dt = 1e-4}, {.t_end = 0.01, .sample_dt = 0.01});
    if (!r.ok()) {
      EXPECT_EQ(spacing, 0.0) << r.message;
      EXPECT_EQ(r.status, Status::SolverError);
      EXPECT_NE(r.message.find("ODE"), std::string::npos) << r.message;
      EXPECT_LT(r.t_reached, 0.01);
      continue;
    }
    const Vector& y = r.samples.back().y;
    for (std::size_t b = 0; b < n; ++b) {
      const double expected = spacing > 0 ? (b + 1 == n ? 1.0 : 0.0) : (b == 0 ? 2.0 / n - 1 : 2.0 / n);
      EXPECT_NEAR(y[static_cast<Eigen::Index>(2 * b + 1)], expected, 1e-6)
          << "ball " << b << " spacing " << spacing;
    }
  }
}

// QuickStep shuffles its constraints with ODE's global random generator, which ran on from one
// world to the next: the same run of a dropped column twice in one process gave velocities ten
// times apart. Each world reseeds it, so a run is the same whatever ran before it.
TEST(Ode, QuickStepRunsAreReproducibleInOneProcess) {
  REQUIRE_ENGINE("ode-quick");
  const BallStack column({.n = 4, .drop = 0.05});
  const BallChain cradle({.n = 5});
  auto run = [&](const Dynamics& scene) {
    return solve(scene, {.name = "ode-quick", .dt = 1e-3}, {.t_end = 0.5, .sample_dt = 0.01});
  };
  const RunResult first = run(column);
  ASSERT_TRUE(first.ok()) << first.message;
  (void)run(cradle);  // draws from the generator in between
  const RunResult again = run(column);
  ASSERT_EQ(first.samples.size(), again.samples.size());
  for (std::size_t k = 0; k < first.samples.size(); ++k)
    ASSERT_EQ(first.samples[k].y, again.samples[k].y) << "t = " << first.samples[k].t;
}

// QuickStep makes energy on a long touching row struck at e = 1, in the strike: its contact set is
// the pairs that overlap as a step begins, parting ones included, and a parting pair that a
// neighbour's bounce drives together is held while the bounce takes Newton's e (traced: a block
// of four balls at 0.4 m/s strikes a ball whose other neighbour parts at 0.4; the two contacts
// solved at once leave that block's energy 1.1 times what it was). Nothing is booked (e = 1), and
// the gain is bounded, below the runs' divergence line (1e6 E0), so the run succeeds. A 10-ball
// row keeps its energy (4e-4 off, measured); 20 balls end with 2.6 E0 at either step (2.614 at 1
// and at 0.1 ms: the gain is the formulation's, not the step's); the README's row says so.
TEST(Ode, QuickStepMakesEnergyOnALongTouchingRowStruckElastically) {
  REQUIRE_ENGINE("ode-quick");
  for (double dt : {1e-3, 1e-4}) {
    const RunResult r =
        solve(BallChain({.n = 20}), {.name = "ode-quick", .dt = dt}, {.t_end = 0.5, .sample_dt = 0.5});
    ASSERT_TRUE(r.ok()) << r.message;
    EXPECT_EQ(r.samples.back().dissipated, 0.0);
    EXPECT_NEAR(r.samples.back().energy / r.energy0, 2.6, 0.05) << "dt = " << dt;
  }
  const RunResult ten =
      solve(BallChain({.n = 10}), {.name = "ode-quick", .dt = 1e-3}, {.t_end = 0.5, .sample_dt = 0.5});
  ASSERT_TRUE(ten.ok()) << ten.message;
  EXPECT_LT(ten.samples.back().energy, ten.energy0);
}

// Restitution only on approach (SequentialImpulses.ABounceThatMeetsAPartingContactLiftsItAndMakes-
// Energy): a column of three dropped 0.1 m at e = 0.8, whose bottom ball lands while the two above
// rise from it, gains energy in a step under tuned Bullet and QuickStep too (0.29 and 0.41 E0,
// measured, against sequential impulses' 0.16); the README says they make more there.
TEST(EngineRuns, TheEnginesBounceMakesEnergyWhereItMeetsAPartingContact) {
  const BallStack column({.n = 3, .drop = 0.1, .e = 0.8});
  for (const char* method : {"bullet-tuned", "ode-quick"}) {
    REQUIRE_ENGINE(method);
    const RunResult r = solve(column, {.name = method, .dt = 1e-3}, {.t_end = 1.0, .sample_dt = 1e-3});
    ASSERT_TRUE(r.ok()) << method << ": " << r.message;
    double rise = 0;
    for (std::size_t k = 1; k < r.samples.size(); ++k)
      rise = std::max(rise, r.samples[k].energy - r.samples[k - 1].energy);
    EXPECT_GT(rise, 0.16 * r.energy0) << method;
  }
}

// An assertion inside ODE's step (a 1e300 kg ball: its orientation quaternion cannot be
// normalised) ends the run as a solver error carrying ODE's message; the half-stepped world is
// not destroyed, since destroying it asserted again inside a destructor (std::terminate, the
// process gone), and ODE keeps working for the next world.
TEST(Ode, AnAssertionInsideAStepIsASolverErrorNotAnAbort) {
  REQUIRE_ENGINE("ode");
  const BallDrop heavy({.m = 1e300, .law = Hooke{1e5}});
  const RunResult r = solve(heavy, {.name = "ode", .dt = 1e-3}, {.t_end = 0.5, .sample_dt = 0.5});
  EXPECT_EQ(r.status, Status::SolverError);
  EXPECT_NE(r.message.find("ODE error 1: assertion"), std::string::npos) << r.message;
  const RunResult next = solve(BallDrop({}), {.name = "ode", .dt = 1e-3}, {.t_end = 0.5, .sample_dt = 0.5});
  EXPECT_TRUE(next.ok()) << next.message;
}

// The same for an assertion in its collision detection, which ran outside that guard: its hash
// space indexes bounding boxes by integer cells, and a ball dropped from 1e300 m (or falling at
// 1e150 m/s) is past them; the space was left locked and its destruction asserted in a destructor
// (std::terminate: the Python interpreter gone). Every ODE method now fails typed, and runs again.
TEST(Ode, AnAssertionInItsCollisionDetectionIsASolverErrorNotAnAbort) {
  REQUIRE_ENGINE("ode");
  for (const char* method : {"ode", "ode-quick", "ode-spring"}) {
    for (const BallDrop& far :
         {BallDrop({.h0 = 1e300, .law = Hooke{1e5}}), BallDrop({.v0 = -1e150, .law = Hooke{1e5}})}) {
      const RunResult r = solve(far, {.name = method, .dt = 1e-3}, {.t_end = 0.01, .sample_dt = 0.01});
      EXPECT_EQ(r.status, Status::SolverError) << method << ": " << r.message;
      EXPECT_NE(r.message.find("ODE error"), std::string::npos) << r.message;
    }
    const RunResult next =
        solve(BallDrop({}), {.name = method, .dt = 1e-3}, {.t_end = 0.5, .sample_dt = 0.5});
    EXPECT_TRUE(next.ok()) << method << ": " << next.message;
  }
}

// Bullet's own tree rebuild (btDbvt::optimizeTopDown) freed memory twice on a ball 1e300 m up
// beside the floor's unbounded plane (the process gone: "double free or corruption"); it is not
// called (the bodies' insertion order keeps the tree shallow). The ball falls freely in 10 ms.
TEST(Bullet, ABallFarAboveTheFloorFallsWithoutAnAbort) {
  REQUIRE_ENGINE("bullet");
  for (const char* method : {"bullet", "bullet-tuned"}) {
    const RunResult r = solve(BallDrop({.h0 = 1e300, .law = Hooke{1e5}}), {.name = method, .dt = 1e-3},
                              {.t_end = 0.01, .sample_dt = 0.01});
    ASSERT_TRUE(r.ok()) << method << ": " << r.message;
    EXPECT_EQ(r.samples.back().y[0], 1e300) << method;  // a fall of 0.5 mm: below its rounding
    EXPECT_NEAR(r.samples.back().y[1], -9.81 * 0.01, 1e-12) << method;  // -g t after whole steps, to rounding
  }
}

// A scene an engine refuses to load (MuJoCo: masses below its mjMINVAL) is a run that fails at
// t = 0 with the engine's message, as its other failures are; it used to be an exception out of
// solve() (a RuntimeError in Python, not the documented SolverError).
TEST(Mujoco, ASceneItRefusesIsASolverErrorAtTheStart) {
  REQUIRE_ENGINE("mujoco");
  const RunResult r =
      solve(BallDrop({.m = 1e-300, .law = Hooke{1e5}}), {.name = "mujoco", .dt = 1e-3}, {.t_end = 0.5});
  EXPECT_EQ(r.status, Status::SolverError);
  EXPECT_EQ(r.t_reached, 0.0);
  EXPECT_NE(r.message.find("MuJoCo could not load the scene"), std::string::npos) << r.message;
}

// MuJoCo's contact buffer holds 100 contacts unless the model says more. A 150-ball column at its
// defaults dropped every contact past the hundredth: the top fifty balls fell through the rest
// as in free fall, g t^2 / 2 = 4.9 m in 1 s, and the run 'succeeded' (MuJoCo only warned, into
// MUJOCO_LOG.TXT). Given room for the scene's 150 contacts, the top ball is held: its soft
// contacts at MuJoCo's defaults let the column sink 2.7 m (measured), not 4.9. The line at 0.8 of
// free fall lies between the two (semi-implicit Euler's own free fall is 0.1 % past g t^2 / 2 at
// this step, so a dropped top ball cannot pass it).
TEST(Mujoco, AColumnTallerThanItsDefaultContactBufferKeepsEveryContact) {
  REQUIRE_ENGINE("mujoco");
  const std::size_t n = 150;
  const RunResult r =
      solve(BallStack({.n = n}), {.name = "mujoco", .dt = 1e-3}, {.t_end = 1.0, .sample_dt = 1.0});
  ASSERT_TRUE(r.ok()) << r.message;
  const double free_fall = 0.5 * 9.81 * 1.0 * 1.0;
  EXPECT_GT(r.samples.back().y[static_cast<Eigen::Index>(2 * (n - 1))], -0.8 * free_fall);
}

// MuJoCo's buffers are sized to the scene (its own sizes made a small world six times as long to
// build), but at its defaults it collides every pair of geoms, and its soft contacts let a column
// of small spheres sink until spheres that are not neighbours overlap: 40 spheres of 2 mm, where
// spheres i and i + 2 come closer than 2 r. Buffers for the neighbours' contacts alone filled at
// 0.078 s ("Pre-allocated contact buffer is full"); there is room for every pair, up to MuJoCo's own.
// Bullet's pools, sized to the scene's pairs too (82 here), take from the heap when they run out:
// its broad phase pairs each sphere with every one within 2 cm (its contact breaking threshold),
// 814 pairs in this column.
TEST(Mujoco, AtItsDefaultsASinkingColumnsContactsBetweenNonNeighboursFitItsBuffers) {
  REQUIRE_ENGINE("mujoco");
  REQUIRE_ENGINE("bullet");
  const double r0 = 0.002;
  const BallStack column({.n = 40, .radius = r0});
  const SolveOptions span{.t_end = 0.1, .sample_dt = 1e-3};
  const RunResult bullet = solve(column, {.name = "bullet", .dt = 1e-3}, span);
  EXPECT_TRUE(bullet.ok()) << bullet.message;
  const RunResult r = solve(column, {.name = "mujoco", .dt = 1e-3}, span);
  ASSERT_TRUE(r.ok()) << r.message;
  double closest = 4 * r0;  // of spheres i and i + 2, at rest 4 r apart (y: displacements)
  for (const auto& s : r.samples)
    for (Eigen::Index i = 0; i + 2 < 40; ++i)
      closest = std::min(closest, 4 * r0 + s.y[2 * (i + 2)] - s.y[2 * i]);
  EXPECT_LT(closest, 2 * r0);
}

// A bad number in MuJoCo's state (NaN, or past 1e10, in qacc here: the ball-drop spring at
// k = 1e14 with a 1 ms step) makes MuJoCo reset the simulation to its initial state and go on, and
// the run 'succeeded' with a ball back at its drop height. It is a typed failure, with MuJoCo's
// warning, at the impact (t0 = sqrt(2 h0 / g) = 0.4515 s, the step after it).
TEST(Mujoco, AStateMujocoResetsForItsBadNumbersIsASolverError) {
  REQUIRE_ENGINE("mujoco-spring");
  const RunResult r =
      solve(BallDrop({.law = Hooke{1e14}}), {.name = "mujoco-spring", .dt = 1e-3}, {.t_end = 1.0});
  EXPECT_EQ(r.status, Status::SolverError);
  EXPECT_NEAR(r.t_reached, std::sqrt(2 / 9.81), 2e-3);
  EXPECT_NE(r.message.find("MuJoCo: Nan, Inf or huge value in QACC"), std::string::npos) << r.message;
}

// Siconos event-driven: the impacts are events located by LSODAR (rtol 1e-10, atol 1e-12), so
// the apexes after them, which the sampling loop interpolates exactly in free flight, are the
// closed form's e^(2n) h0 at the closed form's times to that tolerance (1e-8 on ~1 m and ~1 s),
// and after the Zeno time the ball rests on the floor. At e = 0.3 and 0.606 Siconos's gap
// tolerance (2.2e-12) was below LSODAR's atol, and the run ended at the Zeno time with "output of
// level 0 must be positive".
TEST(Siconos, EventDrivenBouncesAreTheExactOnes) {
  REQUIRE_ENGINE("siconos");
  const double h0 = 1.0, g = 9.81;
  for (double e : {0.3, 0.606057, kE}) {
    const RigidBounces exact(h0, 0.0, g, e);
    const BallDrop ball({.m = 1.0, .g = g, .h0 = h0, .v0 = 0.0, .e = e, .law = Hooke{1e5}});
    const RunResult r = solve(ball, {.name = "siconos", .dt = 1e-3}, {.t_end = 4.5, .sample_dt = 0.01});
    ASSERT_TRUE(r.ok()) << "e = " << e << ": " << r.message;
    // Every apex above 10 um (e = 0.3's fifth, 6 um, falls in the last 2 ms before the Zeno time,
    // where Siconos brings the ball to rest).
    std::size_t resolved = 0;
    while (resolved < 5 && exact.apex_height(resolved + 1) > 1e-5) ++resolved;
    ASSERT_GE(r.apexes.size(), resolved) << e;
    for (std::size_t n = 1; n <= std::min<std::size_t>(5, r.apexes.size()); ++n) {
      EXPECT_NEAR(r.apexes[n - 1].gap, exact.apex_height(n), 1e-8) << "e = " << e << ", apex " << n;
      EXPECT_NEAR(r.apexes[n - 1].t, exact.apex_time(n), 1e-8) << "e = " << e << ", apex " << n;
    }
    ASSERT_LT(exact.zeno_time(), 4.5);
    EXPECT_NEAR(r.samples.back().y[0], 0.0, 1e-9) << e;
    EXPECT_NEAR(r.samples.back().y[1], 0.0, 1e-9) << e;
  }
}

// Drops under other gravities, at rest after their Zeno times. Siconos counted a contact closed
// below 10 atol of gap, and on 54 of 120 random drops (h0 1 mm to 100 m, g 0.1 to 50 m/s^2, e 0.05
// to 0.97) a bounce near the Zeno time then found the ball below the floor ("output of level 0
// must be positive", a typed failure): these four among them (a Moon drop). At 100 atol all 320
// tried reach rest, the apexes unchanged (to 3e-9 of the drop's height, as before). Siconos rests
// a contact whose approach is below that tolerance after Newton's law, so the ball keeps up to
// e 100 atol of speed and creeps up at it (e 1e-10 m/s, measured exactly) from within the gap
// tolerance where it came to rest (by the Zeno time).
TEST(Siconos, DropsUnderOtherGravitiesComeToRestAfterTheirZenoTimes) {
  REQUIRE_ENGINE("siconos");
  const double h0 = 1.0;
  for (const auto& [g, e] : {std::pair{1.62, 0.3}, {2.0, 0.606057}, {1.0, 0.8}, {0.5, 0.95}}) {
    const RigidBounces exact(h0, 0.0, g, e);
    const BallDrop ball({.m = 1.0, .g = g, .h0 = h0, .v0 = 0.0, .e = e, .law = Hooke{1e5}});
    const double t_end = 1.2 * exact.zeno_time();
    const RunResult r =
        solve(ball, {.name = "siconos", .dt = 1e-3}, {.t_end = t_end, .sample_dt = t_end / 10});
    ASSERT_TRUE(r.ok()) << "g = " << g << ": " << r.message;
    ASSERT_GE(r.apexes.size(), 3u) << g;
    for (std::size_t n = 1; n <= 3; ++n)
      EXPECT_NEAR(r.apexes[n - 1].gap, exact.apex_height(n), 1e-8) << g << " " << n;
    // Its atol is 1e-12; the last approaches measured up to 0.14 % above the tolerance, 1 % allowed.
    const double creep = e * 100 * 1e-12 * 1.01;
    EXPECT_LE(std::abs(r.samples.back().y[1]), creep) << g;
    EXPECT_LE(std::abs(r.samples.back().y[0]), 100 * 1e-12 + creep * (t_end - exact.zeno_time())) << g;
  }
}

// Siconos' LSODAR stops on an impact that falls within rounding of one of its steps' ends, after
// two such: a 1 mm approach and 1 mm gaps struck at 1 m/s, stepped by 1 ms, put the impacts at 1, 2
// and 3 ms, and the third ends the run, a typed failure with Siconos' message; 1e-15 m more
// approach, and the run goes through. The README's Siconos bullet says so.
TEST(Siconos, AnImpactOnItsStepsEndCanStopItsIntegrator) {
  REQUIRE_ENGINE("siconos");
  const auto run = [](double approach) {
    const BallChain chain({.n = 4, .v0 = 1.0, .approach = approach, .spacing = 1e-3});
    return solve(chain, {.name = "siconos", .dt = 1e-3}, {.t_end = 0.01, .sample_dt = 0.01});
  };
  const RunResult on = run(1e-3);
  EXPECT_EQ(on.status, Status::SolverError);
  EXPECT_NE(on.message.find("LsodarOSI, integration failed"), std::string::npos) << on.message;
  EXPECT_NEAR(on.t_reached, 3e-3, 1e-12);
  const RunResult off = run(1e-3 + 1e-15);
  ASSERT_TRUE(off.ok()) << off.message;
  EXPECT_NEAR(off.samples.back().y[7], 1.0, 1e-12);  // the striker's speed passed to the last ball
}

// A flight's top that falls in the step its contact's record ends in was not looked for (the
// shared loop checked for tops before it ended the record): a 1 um drop (e = 0.8) stepped by 0.45
// T1 puts the first top, at 1.8 T1, at the end of the step after the impact's, and Siconos' first
// apex was reported as e^4 h0. Its flights are exact parabolas (LSODAR at rtol 1e-10), and a top
// read from a step's ends is exact on a parabola: the first four apexes to 1e-8 of h0 (4e-9
// measured at other steps), their times to 1e-7 T1 (the impacts' located times carry LSODAR's
// error from flight to flight: 1.05e-8 T1 at the fourth, measured).
TEST(Siconos, AnApexInTheStepItsContactEndsInIsReported) {
  REQUIRE_ENGINE("siconos");
  const double h0 = 1e-6, g = 9.81, e = 0.8;
  const RigidBounces exact(h0, 0.0, g, e);
  const BallDrop ball({.m = 1.0, .g = g, .h0 = h0, .v0 = 0.0, .e = e, .law = Hooke{1e5}});
  const double t_end = 1.5 * exact.zeno_time();
  const RunResult r =
      solve(ball, {.name = "siconos", .dt = 0.45 * exact.T1}, {.t_end = t_end, .sample_dt = t_end});
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_GE(r.apexes.size(), 4u);
  for (std::size_t n = 1; n <= 4; ++n) {
    EXPECT_NEAR(r.apexes[n - 1].gap, exact.apex_height(n), 1e-8 * h0) << n;
    EXPECT_NEAR(r.apexes[n - 1].t, exact.apex_time(n), 1e-7 * exact.T1) << n;
  }
}

// Siconos on a cradle with 1 mm gaps, e = 1: each event-driven impact exchanges two balls'
// velocities exactly, so only the last ball moves on, at v0, to rounding.
TEST(Siconos, CradleWithGapsHandsTheStrikersSpeedToTheLastBall) {
  REQUIRE_ENGINE("siconos");
  const std::size_t n = 5;
  const BallChain cradle(
      {.n = n, .m = 0.1, .v0 = 1.0, .approach = 1.5e-3, .spacing = 1e-3, .e = 1.0, .law = Hooke{1e6}});
  const RunResult r = solve(cradle, {.name = "siconos", .dt = 1e-3}, {.t_end = 0.02, .sample_dt = 0.02});
  ASSERT_TRUE(r.ok()) << r.message;
  const Vector& y = r.samples.back().y;
  for (std::size_t b = 0; b < n; ++b)
    EXPECT_NEAR(y[static_cast<Eigen::Index>(2 * b + 1)], b + 1 == n ? 1.0 : 0.0, 1e-12) << "ball " << b;
}

// A gapped chain at low e clumps (inelastic collapse), and Siconos' Newton law, an LCP over the
// contacts at an impact, gives impulses to contacts that are parting where a neighbour's impulse
// would close them; complementarity leaves such a contact at -e u, and it gains J (1 - e) u / 2.
// The ledger booked approaches only and left 8e-4 of E0 unbooked (8 balls, e = 0.1, 0.1 mm gaps);
// booking every impulse of an impact, it closes to rounding over the run's impacts (7e-16
// measured on 144 chains of 3 to 8 balls, e = 0 to 1; 1e-12 leaves room for more of them).
TEST(Siconos, TheLedgerBooksTheImpulsesItsLcpGivesToPartingContacts) {
  REQUIRE_ENGINE("siconos");
  for (double e : {0.1, 0.3}) {
    const BallChain chain({.n = 8, .spacing = 1e-4, .e = e});
    const RunResult r = solve(chain, {.name = "siconos", .dt = 1e-3}, {.t_end = 0.2, .sample_dt = 0.2});
    ASSERT_TRUE(r.ok()) << r.message;
    const Sample& end = r.samples.back();
    EXPECT_GT(end.dissipated, 0.1 * r.energy0) << e;  // it clumps: most of the energy goes
    EXPECT_NEAR(end.energy + end.dissipated, r.energy0, 1e-12 * r.energy0) << e;
  }
}

// A span that dt does not divide: every engine's last step is the rest of the span, as the game
// methods' is. Each engine stepped a whole dt past the end (0.30035 s: to 0.301 s), and the run
// reported that later state at 0.30035 s. In free fall the velocity after steps summing to t is
// -g t for the semi-implicit Euler of MuJoCo, Bullet and ODE (to rounding over 430 steps) and for
// Siconos's LSODAR flight (exact on a parabola, to its rtol 1e-10).
TEST(EngineRuns, EndAtTheSpansEndWhereTheStepDoesNotDivideIt) {
  const double g = 9.81, t_end = 0.30035;  // the ball lands at 0.45 s
  const BallDrop ball({.m = 1.0, .g = g, .h0 = 1.0, .v0 = 0.0, .e = kE, .law = law_of(1e5, 1.0)});
  for (const char* method :
       {"mujoco", "mujoco-spring", "bullet", "bullet-tuned", "ode", "ode-quick", "ode-spring", "siconos"}) {
    REQUIRE_ENGINE(method);
    const RunResult r = solve(ball, {.name = method, .dt = 7e-4}, {.t_end = t_end, .sample_dt = 0.1});
    ASSERT_TRUE(r.ok()) << method << ": " << r.message;
    EXPECT_EQ(r.samples.back().t, t_end) << method;
    EXPECT_NEAR(r.samples.back().y[1], -g * t_end, 1e-10 * g * t_end) << method;
  }
}

// An engine builds its own world from the scene before it steps (MuJoCo compiles an XML model and
// zeroes its buffers; Bullet fills its pools): up to a millisecond, paid once per world, which the
// engines experiment counted in its CPU per simulated second (MuJoCo's on the 50-step head-on pair
// was 20 ms, its stepping 2.4 ms). A run reports it apart; the project's methods build no world.
TEST(EngineRuns, ReportTheirWorldsConstructionApart) {
  const BallDrop ball({.m = 1.0, .g = 9.81, .h0 = 1.0, .v0 = 0.0, .e = kE, .law = law_of(1e5, 1.0)});
  for (const char* method :
       {"mujoco", "mujoco-spring", "bullet", "bullet-tuned", "ode", "ode-quick", "ode-spring", "siconos"}) {
    REQUIRE_ENGINE(method);
    const RunResult r = solve(ball, {.name = method, .dt = 1e-3}, {.t_end = 0.1, .sample_dt = 0.1});
    ASSERT_TRUE(r.ok()) << method << ": " << r.message;
    EXPECT_GT(r.stats.setup_cpu_s, 0.0) << method;
  }
  for (const char* method : {"penalty", "sequential-impulses", "moreau-jean", "event-exact"})
    EXPECT_EQ(solve(ball, {.name = method, .dt = 1e-3}, {.t_end = 0.1, .sample_dt = 0.1}).stats.setup_cpu_s,
              0.0)
        << method;
}

// Siconos keeps event times as integers of 1e-16 s ticks converted from doubles: a step beyond the
// integer's double range raised SIGFPE inside GMP, killing the program. A typed failure now.
// Siconos' LSODAR integrates every state with a dense Jacobian, (2 n)^2 numbers for n balls: the
// run's memory check counts it, so a chain whose matrix cannot fit is refused before Siconos
// allocates it (3e4 balls: 29 GB, past half of a 24 GB machine). Here the limit is lowered to 1 MB:
// 300 balls' 600 x 600 matrix (2.9 MB) is refused, while their vectors alone (8 of 600 values,
// and the two samples) fit, as they do for a method without the matrix.
TEST(Siconos, AChainWhoseDenseJacobianCannotFitIsRefusedBeforeItStarts) {
  REQUIRE_ENGINE("siconos");
  const BallChain chain({.n = 300});
  SolveOptions span{.t_end = 1e-3, .sample_dt = 1e-3};
  span.limits.max_memory_bytes = 1e6;
  try {
    solve(chain, {.name = "siconos", .dt = 1e-3}, span);
    ADD_FAILURE() << "a 600 x 600 dense matrix passed a 1 MB limit";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("a dense 600 x 600 matrix"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(solve(chain, {.name = "sequential-impulses", .dt = 1e-3}, span).ok());
}

// A column of 1e-30 kg balls chatters under Siconos: an impact every 4e-11 s, 2.4e7 for a 1 ms
// step, each a few microseconds: the run met the bound of a million events a step after a minute
// (Python's Ctrl-C unheard meanwhile). The first 1e4 events' progress judges the step now.
TEST(Siconos, AChatterItDoesNotEndIsJudgedByItsFirstEvents) {
  REQUIRE_ENGINE("siconos");
  const BallStack column({.m = 1e-30});
  const RunResult r = solve(column, {.name = "siconos", .dt = 1e-3}, {.t_end = 2e-3, .sample_dt = 1e-3});
  EXPECT_EQ(r.status, Status::SolverError) << r.message;
  EXPECT_NE(r.message.find("took 10000 events to cover"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("more than the 1000000 a step may take"), std::string::npos) << r.message;
  EXPECT_EQ(r.t_reached, 0.0);
}

TEST(Siconos, AStepBeyondItsClockIsASolverError) {
  REQUIRE_ENGINE("siconos");
  const BallDrop ball({.m = 1.0, .law = Hooke{1e5}});
  const RunResult r = solve(ball, {.name = "siconos", .dt = 1e300}, {.t_end = 3.0, .sample_dt = 3.0});
  EXPECT_EQ(r.status, Status::SolverError);
  EXPECT_NE(r.message.find("Siconos cannot step by 1e+300 s"), std::string::npos) << r.message;
}

// A span below Siconos's tick (1e-300 s): no event can fall inside it, and the one placed at its
// end fell on its start, after which the state read back was NaN ('non-finite-state'). The state
// stays where it is: it would move by g t = 1e-299 m/s.
TEST(Siconos, ASpanBelowItsClockTickLeavesTheStateWhereItIs) {
  REQUIRE_ENGINE("siconos");
  const BallDrop ball({.m = 1.0, .law = Hooke{1e5}});
  const RunResult r = solve(ball, {.name = "siconos", .dt = 1e-3}, {.t_end = 1e-300, .sample_dt = 1e-300});
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_EQ(r.samples.back().y[0], 1.0);
  EXPECT_EQ(r.samples.back().y[1], 0.0);
}

// A stack of 3e307 kg balls weighs more than the doubles hold (m g overflows): Siconos's LCP solver
// asserted on it and aborted the process. Its energy is beyond the doubles too, and solve() refuses
// the scene before any method sees it (the Siconos adapter still checks every body's numbers).
TEST(Siconos, AnInfiniteWeightIsRefusedNotAnAbort) {
  REQUIRE_ENGINE("siconos");
  const BallStack column({.m = 3e307});
  try {
    solve(column, {.name = "siconos", .dt = 1e-3}, {.t_end = 2e-3, .sample_dt = 1e-3});
    ADD_FAILURE() << "a stack of infinite weight ran";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("its initial energy is inf J"), std::string::npos) << e.what();
  }
}

// Siconos prints a failing initialisation's interactions on standard output: a stack dropped from
// 3e9 m, whose gaps round below its tolerance, put some 40 lines into the caller's output beside the
// typed error. Its standard output is held aside while it initialises, as while it steps.
TEST(Siconos, AFailedInitialisationPrintsNothing) {
  REQUIRE_ENGINE("siconos");
  const BallStack column({.drop = 3e9});
  testing::internal::CaptureStdout();
  const RunResult r = solve(column, {.name = "siconos", .dt = 1e-3}, {.t_end = 2e-3, .sample_dt = 1e-3});
  const std::string printed = testing::internal::GetCapturedStdout();
  EXPECT_EQ(r.status, Status::SolverError) << r.message;
  EXPECT_NE(r.message.find("Siconos could not initialise the simulation"), std::string::npos) << r.message;
  EXPECT_EQ(printed, "");
}

// ODE and Siconos keep process-wide state: ODE's random generator, which QuickStep draws from at
// every step, and Siconos' tolerance globals. Engine solves run three threads at a time gave
// answers that differed from their serial runs (ode and ode-quick, on the drop and the stack). One
// world of each of those at a time: every engine's solves in threads give the serial answers,
// bitwise.
TEST(Engines, SolvesInThreadsGiveTheirSerialAnswers) {
  struct Job {
    std::string scene, method;
  };
  std::vector<Job> jobs;
  for (const std::string scene : {"ball-drop", "ball-stack"}) {
    const auto model = make_scene(scene);
    for (const auto& method : methods_for(*model))
      if (method_info(method).family == "engine") jobs.push_back({scene, method});
  }
  ASSERT_GE(jobs.size(), 16u);  // MuJoCo's, Bullet's, ODE's and Siconos' methods on both scenes
  const auto run = [](const Job& job) {
    const auto model = make_scene(job.scene);
    return solve(*model, Method{.name = job.method}, {.t_end = 1.0, .sample_dt = 0.01});
  };
  std::vector<RunResult> serial;
  for (const Job& job : jobs) serial.push_back(run(job));
  constexpr std::size_t kThreads = 3, kRounds = 2;
  std::vector<RunResult> side_by_side(kThreads * kRounds * jobs.size());
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < kThreads; ++t)
    threads.emplace_back([&, t] {
      for (std::size_t k = t; k < side_by_side.size(); k += kThreads)
        side_by_side[k] = run(jobs[k % jobs.size()]);
    });
  for (auto& thread : threads) thread.join();
  for (std::size_t k = 0; k < side_by_side.size(); ++k) {
    const RunResult &a = serial[k % jobs.size()], &b = side_by_side[k];
    const Job& job = jobs[k % jobs.size()];
    ASSERT_EQ(a.status, b.status) << job.scene << " " << job.method;
    ASSERT_EQ(a.samples.size(), b.samples.size()) << job.scene << " " << job.method;
    bool same = true;
    for (std::size_t i = 0; i < a.samples.size(); ++i) same = same && a.samples[i].y == b.samples[i].y;
    EXPECT_TRUE(same) << job.scene << " " << job.method;
  }
}
