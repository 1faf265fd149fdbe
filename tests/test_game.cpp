// Game-style resolution (the seed's projection + impulse) on the ball drop.
#include "contact_ode/analysis/references.hpp"
#include "contact_ode/integrators/capabilities.hpp"
#include "contact_ode/integrators/game_step.hpp"
#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/models/ball_drop.hpp"
#include "contact_ode/models/scene_registry.hpp"
#include "contact_ode/models/spring_mass.hpp"
#include "unit_roundoff.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace contact;

// One impulse: J = -(1+e) v / m^-1, v+ = v + J/m = -e v. Rounding: (1+e) v, times m, over m:
// a few ulps of v.
TEST(GameImpulse, OneBounceScalesTheNormalVelocityByE) {
  for (double e : {0.0, 0.3, 0.8, 1.0}) {
    for (double m : {0.1, 1.0, 70.0}) {
      const BallDrop model({m, 9.81, 1.0, 0.0, e, Hooke{1e5}});
      Vector y{{-0.003, -4.2}};
      model.project(0, y);
      EXPECT_EQ(y[0], 0.0);  // the floor does not move: the ball takes the whole overlap
      model.apply_impulse(0, e, y);
      EXPECT_NEAR(y[1], 4.2 * e, 4 * kEps * 4.2) << "e = " << e << ", m = " << m;
    }
  }
}

// The game loop and the energy ledger book an impulse's loss as -J (u- + u+) / 2 (ImpulseMap),
// not as the whole scene's energy before and after (which made a frame of an N-ball column cost
// O(N^2): 77 s for 2 s of 1000 balls, now 0.1 s). Exact for any impulse along a contact's normal
// Jacobian row, since the kinetic energy is quadratic in the velocities: checked on every scene
// with an impulse map, every contact, random velocities of every body an impulse moves (angular ones
// too; an immovable floor stays still: its kinetic energy would be infinite), against the energy an
// impulse method's ledger counts (without the penalty springs: RunRecorder::exclude_spring_energy;
// a clamped law's engagement depends on the velocities). Both sides are differences of energies of
// order E: a few ulps of E, 1e-13 allowed.
TEST(GameImpulse, AnImpulseTakesMinusJTimesTheMeanOfTheGapRatesFromTheEnergy) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> speed(-1.0, 1.0);
  for (const auto& name : scene_names()) {
    const auto scene = make_scene(name);
    if (!has_impulse_map(*scene)) continue;
    ASSERT_TRUE(has_normal_impulses(*scene)) << name;  // the probe below applies unit impulses
    const ImpulseMap& map = impulse_map(*scene, "test");
    const ContactGeometry& geo = contact_geometry(*scene);
    // The velocities some contact's impulse changes (a unit one, applied to the initial state).
    Mask moved = Mask::Constant(static_cast<Eigen::Index>(scene->state_size()), false);
    const Vector y0 = scene->initial_state();
    for (std::size_t i = 0; i < scene->contact_count(); ++i) {
      Vector x = y0;
      normal_impulses(*scene, "test").apply_normal_impulse(i, 1.0, x);
      moved = moved || (x.array() != y0.array());
    }
    ASSERT_TRUE(moved.any()) << name;
    const auto energy = [&](const Vector& y) {
      return scene->energy(y) - geo.engaged_elastic_energy(scene->contact_count(), y);
    };
    long checked = 0;
    for (int draw = 0; draw < 20; ++draw) {
      Vector y = scene->initial_state();
      for (Eigen::Index j = 0; j < y.size(); ++j)
        if (moved[j]) y[j] = speed(random);
      for (std::size_t i = 0; i < scene->contact_count(); ++i) {
        const double u = geo.gap_rate(i, y);
        if (!(u < 0)) continue;
        Vector x = y;
        const double before = energy(x), J = map.apply_impulse(i, map.restitution(i), x);
        EXPECT_GT(J, 0) << name << " contact " << i;
        EXPECT_NEAR(energy(x) - before, 0.5 * J * (u + geo.gap_rate(i, x)),
                    1e-13 * std::max(1.0, std::abs(before)))
            << name << " contact " << i;
        ++checked;
      }
    }
    EXPECT_GT(checked, 0) << name;
  }
}

TEST(GameImpulse, EveryLoggedBounceOfAGameRunHasRestitutionE) {
  for (auto scheme : {FixedStepScheme::ExplicitEuler, FixedStepScheme::SemiImplicitEuler}) {
    const BallDrop model({1.0, 9.81, 1.0, 0.0, 0.7, Hooke{1e5}});
    const RunResult r =
        run_game(model, {.dt = 1e-3, .scheme = scheme, .resolution = GameResolution::ProjectionImpulse},
                 {.t_end = 3.0, .sample_dt = 0.01});
    ASSERT_TRUE(r.ok());
    ASSERT_GE(r.contacts.size(), 4u);
    for (std::size_t n = 0; n < 4; ++n) {
      EXPECT_NEAR(r.contacts[n].restitution(), 0.7, 8 * kEps) << to_string(scheme) << " contact " << n;
      // Begins at the interpolated crossing inside the step, ends when resolved at its end.
      EXPECT_GE(r.contacts[n].duration(), 0.0);
      EXPECT_LE(r.contacts[n].duration(), 1e-3);
    }
  }
}

// Free fall: with v_n = -g n dt exact at step ends for both schemes, explicit Euler's height
// lags (x_n = h0 - g dt^2 n(n-1)/2) and semi-implicit Euler's leads (n(n+1)/2). The impact is
// detected at the first step end below the floor, n dt in [t0, t0 + 1.5 dt) for explicit and
// [t0 - dt/2, t0 + dt) for semi-implicit Euler, so the logged impact speed is off by less than
// 1.5 g dt and the interpolated impact time by less than 1.5 dt: first order. The time is the
// root of the line through the step ends' heights, which lie on x(t) = h0 - g t (t -+ dt) / 2:
// within g dt^2 / 8 of that parabola, so the logged time is within g dt^2 / (8 (V - g dt)) of its
// root t* = +-dt/2 + sqrt(dt^2/4 + 2 h0 / g) (taken at the step's end, it was up to a step late).
TEST(GameFreeFall, FirstImpactErrorIsBoundedByFirstOrderTerms) {
  const RigidBounces ref(1.0, 0.0, 9.81, 0.8);
  for (auto scheme : {FixedStepScheme::ExplicitEuler, FixedStepScheme::SemiImplicitEuler}) {
    for (double dt : {1e-2, 4e-3, 2e-3, 1e-3, 5e-4, 1e-4}) {
      const BallDrop model({1.0, 9.81, 1.0, 0.0, 0.8, Hooke{1e5}});
      const RunResult r =
          run_game(model, {.dt = dt, .scheme = scheme, .resolution = GameResolution::ProjectionImpulse},
                   {.t_end = 1.0, .sample_dt = 0.01});
      ASSERT_FALSE(r.contacts.empty());
      EXPECT_LT(std::abs(-r.contacts[0].v_in - ref.V), 1.5 * 9.81 * dt)
          << to_string(scheme) << " dt = " << dt;
      EXPECT_LT(std::abs(r.contacts[0].t_begin - ref.T1), 1.5 * dt) << to_string(scheme) << " dt = " << dt;
      const double lag = scheme == FixedStepScheme::ExplicitEuler ? dt / 2 : -dt / 2;
      const double root = lag + std::sqrt(dt * dt / 4 + 2 * 1.0 / 9.81);
      EXPECT_LT(std::abs(r.contacts[0].t_begin - root), 9.81 * dt * dt / (8 * (ref.V - 9.81 * dt)) + 1e-12)
          << to_string(scheme) << " dt = " << dt;
    }
  }
}

// Explicit Euler's ball never rests (the README's limit cycle). From the floor at speed u it is at
// x_n = n h u - g h^2 n (n - 1) / 2, v_n = u - n g h after n steps; projected at the first x_N < 0
// and struck to e (N g h - u), it repeats when u = e N g h / (1 + e), which needs
// (N - 2) / 2 <= u / (g h) < (N - 1) / 2: at e = 0.8, every N from 10 to 18 is such a cycle. The
// run from 1 m ends in one (N = 14 at h = 1 ms: 14 ms, as the README says), and each apex the
// recorder books, x_n + v_n^2 / (2 g) at the last n with v_n > 0, is the cycle's to 16 ulps.
TEST(GameFreeFall, ExplicitEulerBouncesForeverInACycleOfItsOwn) {
  const double g = 9.81, e = 0.8, h = 1e-3;
  const BallDrop model({1.0, g, 1.0, 0.0, e, Hooke{1e5}});
  const RunResult r = run_game(
      model,
      {.dt = h, .scheme = FixedStepScheme::ExplicitEuler, .resolution = GameResolution::ProjectionImpulse},
      {.t_end = 10.0, .sample_dt = 1.0});
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_GE(r.apexes.size(), 10u);
  const double period = r.apexes.back().t - r.apexes[r.apexes.size() - 2].t;
  const auto N = static_cast<int>(std::lround(period / h));
  EXPECT_EQ(N, 14);
  const double u = e * N * g * h / (1 + e);
  EXPECT_LE((N - 2) / 2.0, u / (g * h));
  EXPECT_LT(u / (g * h), (N - 1) / 2.0);
  const int n = static_cast<int>(std::floor(u / (g * h)));  // the last step with v_n > 0
  const double v = u - n * g * h, top = n * h * u - g * h * h * n * (n - 1) / 2 + v * v / (2 * g);
  for (std::size_t i = r.apexes.size() - 5; i < r.apexes.size(); ++i) {
    EXPECT_NEAR(r.apexes[i].gap, top, 16 * kEps * top) << i;
    EXPECT_NEAR(r.apexes[i].t - r.apexes[i - 1].t, N * h, 1e-9) << i;
  }
}

// Projection alone does not change velocity: the ball is held at the floor while gravity keeps
// adding g dt of downward speed every step, so its "contact" never ends (the seed's warning).
TEST(GameProjection, ProjectionAloneNeverLetsGo) {
  const BallDrop model({1.0, 9.81, 1.0, 0.0, 0.8, Hooke{1e5}});
  const RunResult r = run_game(
      model,
      {.dt = 1e-3, .scheme = FixedStepScheme::SemiImplicitEuler, .resolution = GameResolution::Projection},
      {.t_end = 2.0, .sample_dt = 0.01});
  ASSERT_EQ(r.contacts.size(), 1u);
  EXPECT_FALSE(r.contacts[0].closed());
  EXPECT_EQ(r.samples.back().y[0], 0.0);
  EXPECT_NEAR(r.samples.back().y[1], -9.81 * 2.0, 9.81 * 2e-3);  // still "falling" at g t
}

TEST(GameSpring, ExplicitEulerSpringGainsEnergyInEveryContact) {
  const BallDrop model({1.0, 9.81, 1.0, 0.0, 1.0, Hooke{1e5}});
  const RunResult r = run_game(
      model, {.dt = 1e-3, .scheme = FixedStepScheme::ExplicitEuler, .resolution = GameResolution::Spring},
      {.t_end = 3.0, .sample_dt = 0.01});
  ASSERT_GE(r.contacts.size(), 1u);
  // In contact each step multiplies the oscillator energy by 1 + (w dt)^2 = 1.1 (test_fixed_step),
  // over ~ pi / (w dt) = 10 steps: the ball must leave faster than it came.
  ASSERT_TRUE(r.contacts.front().closed());
  for (const auto& c : r.contacts) {
    if (c.closed()) {
      EXPECT_GT(c.restitution(), 1.5);
    }
  }
}

TEST(GameStep, NonFiniteStateIsReportedWithTheTimeReached) {
  // A spring so stiff that explicit Euler explodes: w dt = 1e4 multiplies the energy by 1 + 1e8
  // a step (test_fixed_step): the amplitude grows ~1e4 a step from |v| = w = 1e7, so v passes
  // the largest double (1.8e308) after (308 - 7) / 4 ~ 75 steps.
  const SpringMass spring(1.0, 1e14, 1.0, 0.0);
  const RunResult r = run_game(
      spring, {.dt = 1e-3, .scheme = FixedStepScheme::ExplicitEuler, .resolution = GameResolution::Spring},
      // The divergence guards (a sampled entry past 1e10 times its start, the energy past 1e6 E0)
      // would stop it first.
      {.t_end = 1.0,
       .sample_dt = 0.01,
       .limits = {.max_state_growth = std::numeric_limits<double>::infinity(),
                  .max_energy_gain = std::numeric_limits<double>::infinity()}});
  EXPECT_EQ(r.status, Status::NonFiniteState);
  EXPECT_NEAR(r.t_reached, 0.075, 0.002);
  EXPECT_NE(r.message.find("not finite"), std::string::npos);
}

// Notifications: for every contact exactly one Begin and one End, alternating; all delivered in
// batches at step ends, the callback seeing exactly the recorded events; End comes `persistence`
// frames after the last frame the contact was detected; a long (spring) contact is one pair, not
// a flicker (the refill that departs from the tutorial's set::insert). The implicit Euler spring
// is a game loop too and notifies as the others do (it delivered nothing, its callback never
// called).
TEST(GameNotifications, BeginAndEndOncePerContactInBatchesAfterTheStep) {
  const BallDrop model({1.0, 9.81, 1.0, 0.0, 0.7, kelvin_voigt_for_restitution(1e5, 1.0, 0.7, false)});
  for (int persistence : {1, 3}) {
    for (const char* method : {"game-symplectic", "game-symplectic-spring", "game-implicit-spring"}) {
      std::vector<CollisionEvent> seen;
      long calls = 0;
      const Method m{.name = method,
                     .dt = 1e-3,
                     .persistence = persistence,
                     .on_notifications = [&](const std::vector<CollisionEvent>& batch) {
                       ++calls;
                       ASSERT_FALSE(batch.empty());
                       for (const auto& e : batch) {
                         EXPECT_EQ(e.step, batch.front().step);                        // one step per batch
                         EXPECT_NEAR(e.t, static_cast<double>(e.step) * 1e-3, 1e-12);  // at its end
                       }
                       seen.insert(seen.end(), batch.begin(), batch.end());
                     }};
      const RunResult r = solve(model, m, {.t_end = 2.0, .sample_dt = 0.01});
      ASSERT_TRUE(r.ok()) << method << ": " << r.message;
      ASSERT_EQ(seen.size(), r.notifications.size()) << method;
      ASSERT_GE(r.contacts.size(), 3u) << method;
      long begins = 0;
      for (std::size_t k = 0; k < seen.size(); ++k) {
        EXPECT_EQ(seen[k].kind, k % 2 == 0 ? CollisionEvent::Kind::Begin : CollisionEvent::Kind::End)
            << method << ", " << k;
        begins += seen[k].kind == CollisionEvent::Kind::Begin;
        if (seen[k].kind == CollisionEvent::Kind::End) {
          EXPECT_GE(seen[k].step - seen[k - 1].step, persistence) << method;
        }
      }
      // One pair per bounce the loop logged (the last may still be open at the end).
      EXPECT_NEAR(static_cast<double>(begins), static_cast<double>(r.contacts.size()), 1.0) << method;
      if (std::string(method) == "game-symplectic") {
        // A one-frame contact ends exactly `persistence` frames after it began.
        EXPECT_EQ(seen[1].step - seen[0].step, persistence);
      }
      EXPECT_LE(calls, static_cast<long>(seen.size())) << method;
    }
  }
}

// Projection and impulses have no springs, so the scene's spring constant cannot change their
// energy. The ledger counted the scene's spring energy at the overlaps a touching row leaves when
// its pairs are resolved one after the other in a step: a chain of five at k = 1e9 was 820 times
// its energy off mid-run. Without gravity, at e = 1, impulses keep the energy and projection moves
// no energy: E + D = E0 to rounding, at every k.
TEST(GameProjection, ProjectionAndImpulsesCountNoSpringEnergy) {
  for (const char* method : {"game-symplectic", "game-euler", "game-symplectic-projection"})
    for (const double k : {1e6, 1e9}) {
      const auto chain = make_scene("ball-chain", {{"k", k}}, "hooke");
      const RunResult r = solve(*chain, {.name = method}, {.t_end = 0.05, .sample_dt = 1e-3});
      ASSERT_TRUE(r.ok()) << method << ": " << r.message;
      for (const Sample& x : r.samples)
        ASSERT_NEAR(x.energy + x.dissipated, r.energy0, 1e-12 * r.energy0)
            << method << ", k " << k << ", t " << x.t;
    }
}

// Projection alone never changes a velocity: the dropped ball it holds on the floor keeps falling
// in its state, v = -g t exactly under semi-implicit Euler (v += g dt each step), at y = 0. Its
// energy m g^2 t^2 / 2 grows without bound and passes E0 + 1e6 |E0| (E0 = m g h0) at
// t* = sqrt(2 (1e6 + 1) h0 / g) = 451.5 s, where the run ends 'diverged' at the first sample past
// it: the README's 'projection's is not bounded'.
TEST(GameProjection, AHeldBallsSpeedGrowsUntilTheRunDiverges) {
  const auto drop = make_scene("ball-drop", {{"h0", 1.0}, {"g", 9.81}, {"m", 1.0}});
  const double t_star = std::sqrt(2 * (1e6 + 1) * 1.0 / 9.81);
  const RunResult r =
      solve(*drop, {.name = "game-symplectic-projection", .dt = 1e-3}, {.t_end = 1000, .sample_dt = 0.5});
  ASSERT_EQ(r.status, Status::Diverged) << r.message;
  EXPECT_GE(r.t_reached, t_star);
  EXPECT_LE(r.t_reached, t_star + 0.5 + 1e-9);
  const Vector& y = r.samples.back().y;  // the last sample before the line
  EXPECT_EQ(y[0], 0.0);
  EXPECT_NEAR(y[1], -9.81 * r.samples.back().t, 1e-9 * 9.81 * r.samples.back().t);
}

// Projection by inverse-mass share undoes a normal displacement: pushed together along contact i
// (body a by w_a d, body b by w_b d, apply_normal_displacement) from touching, the bodies are moved
// back by exactly as much, so the state returns to the touching one (to rounding of the
// positions). On the line models, whose bodies do not turn; the rigid scenes' projection is
// RigidProjection's. A chain's projection that moved one ball by 0.4 of the overlap passed every
// test before this one.
TEST(GameProjection, ProjectionUndoesANormalDisplacementByInverseMassShare) {
  for (const char* name : {"ball-drop", "ball-chain", "ball-stack"}) {
    const auto scene = make_scene(name);
    const ImpulseMap& map = impulse_map(*scene, "test");
    const NormalImpulses& normal = normal_impulses(*scene, "test");
    const ContactGeometry& geo = contact_geometry(*scene);
    for (std::size_t i = 0; i < scene->contact_count(); ++i) {
      Vector touching = scene->initial_state();
      const double w = normal.inverse_mass(i, touching), overlap = 1e-3;
      normal.apply_normal_displacement(i, -geo.gap(i, touching) / w, touching);
      Vector y = touching;
      normal.apply_normal_displacement(i, -overlap / w, y);
      ASSERT_NEAR(geo.gap(i, y), -overlap, 1e-12) << name << " contact " << i;
      map.project(i, y);
      EXPECT_LT((y - touching).lpNorm<Eigen::Infinity>(),
                1e-14 * std::max(1.0, touching.lpNorm<Eigen::Infinity>()))
          << name << " contact " << i;
    }
  }
}
