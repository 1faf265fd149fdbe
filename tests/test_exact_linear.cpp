// exact-linear: the exact solution of a penalty scene with linear laws, to rounding, and a clear
// refusal of what it cannot solve exactly. Every step is the Taylor series of the exact solution
// summed below rounding, roots are located on it to 100 ulps of t, and the energy ledger is the
// exact integral of its quadratic dissipated power: so every number is held here to the closed
// forms at 1e-11 relative or better (rounding accumulated over tens of steps and restarts, and
// the closed forms' own bisection), a bound no tolerance-driven integrator meets at rtol 1e-6.
#include "contact_ode/analysis/references.hpp"
#include "contact_ode/integrators/integrator.hpp"
#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/integrators/penalty.hpp"
#include "contact_ode/models/ball_chain.hpp"
#include "contact_ode/models/ball_drop.hpp"
#include "contact_ode/models/ball_stack.hpp"
#include "contact_ode/models/scene_registry.hpp"
#include "contact_ode/models/spring_mass.hpp"
#include "refusal.hpp"
#include "time_scaled.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

using namespace contact;

namespace {

// Contacts begin and end at a thousandth of atol of overlap (contact_threshold), where the closed
// forms start at zero: at the default 1e-10 that offset moved a slow late contact's exit speed by
// 1e-10 of itself (2 zeta w delta / V at V = 5 cm/s), 1e-14 here.
PenaltyOptions exact() {
  PenaltyOptions o;
  o.integrator.method = "exact-linear";
  o.integrator.atol = 1e-14;
  return o;
}

ContactLaw law_named(const std::string& name, double k, double m, double e) {
  if (name == "hooke") return Hooke{k};
  return kelvin_voigt_for_restitution(k, m, e, name == "kelvin-voigt-clamped");
}

}  // namespace

// P1 (and its Hooke and clamped siblings): every contact's duration, deepest overlap and exit speed
// against the exact closed forms with gravity, entered at the run's own incoming speed; every apex
// at v_out^2 / 2g above the floor (the free flight between); the ledger E + D = E0 at every sample.
TEST(ExactLinear, EveryContactOfTheBallDropIsTheClosedFormToRounding) {
  const double m = 1, g = 9.81, k = 1e5, e = 0.8;
  for (const std::string name : {"hooke", "kelvin-voigt", "kelvin-voigt-clamped"}) {
    const BallDrop model({m, g, 1.0, 0.0, e, law_named(name, k, m, e)});
    const RunResult r = run_penalty(model, exact(), {.t_end = 4.6, .sample_dt = 0.01});
    ASSERT_TRUE(r.ok()) << name << ": " << r.message;
    // The first ten of the damped laws (entered at 4.4 down to 0.6 m/s), Hooke's five: later ones,
    // entered at centimetres per second, end where gravity nearly holds the ball (g / (w V) near
    // one), and the closed forms' own bisection of the exit, at a grazing zero of the overlap, is
    // no longer good to 1e-11.
    const std::size_t checked = name == "hooke" ? 5 : 10;
    ASSERT_GE(r.contacts.size(), checked) << name;
    for (std::size_t i = 0; i < checked; ++i) {
      const ContactRecord& c = r.contacts[i];
      ASSERT_TRUE(c.closed()) << name << " contact " << i;
      const SpringContact ref = linear_law_first_contact(name, m, k, e, -c.v_in, g);
      const std::string what = fmt::format("{} contact at t = {:.6f}", name, c.t_begin);
      // Both ends are roots located to 100 ulps of t (CVODE's root tolerance, 9e-14 s at 4 s).
      const double located = 2 * 100 * std::numeric_limits<double>::epsilon() * c.t_end;
      EXPECT_NEAR(c.duration(), ref.duration, located + 1e-12 * ref.duration) << what;
      EXPECT_NEAR(c.max_penetration / ref.max_penetration, 1.0, 1e-11) << what;
      EXPECT_NEAR(c.v_out / ref.exit_speed, 1.0, 1e-11) << what;
    }
    ASSERT_GE(r.apexes.size(), 5u) << name;
    for (std::size_t n = 0; n < 5; ++n) {
      const double v_out = r.contacts[n].v_out;
      EXPECT_NEAR(r.apexes[n].gap / (v_out * v_out / (2 * g)), 1.0, 1e-12) << name << " apex " << n + 1;
    }
    for (const Sample& s : r.samples)
      EXPECT_NEAR(s.energy + s.dissipated, r.energy0, 1e-13 * r.energy0) << name << " t = " << s.t;
  }
}

// The free spring: x = cos(w t), v = -w sin(w t) at every sample, to rounding (w = 100/s, 16 periods).
TEST(ExactLinear, TheFreeSpringIsItsClosedForm) {
  const SpringMass spring(1.0, 1e4, 1.0, 0.0);
  const RunResult r = solve(spring, [] {
    Method m{.name = "penalty"};
    m.integrator.method = "exact-linear";
    return m;
  }());
  ASSERT_TRUE(r.ok()) << r.message;
  for (const Sample& s : r.samples) {
    EXPECT_NEAR(s.y[0], std::cos(100 * s.t), 1e-13) << s.t;
    EXPECT_NEAR(s.y[1], -100 * std::sin(100 * s.t), 1e-11) << s.t;
  }
}

// P1 scaled in time (g and k / m times 1 / s^2, the span s times: the same motion, velocities
// 1 / s times) is the same motion, and its ledger closes, at every s: sped up 1e4 times its speeds
// of 4e4 m/s made the ledger's Hessian, taken on unit probes, a difference of nearly equal rates,
// and the run was refused as not quadratic. To 1e-9 m and m/s (scaled back): the rounding of the
// coordinates over a few contacts, measured 3e-11.
TEST(ExactLinear, ADropSpedUpOrSlowedDownIsTheSameMotion) {
  const auto run = [](double s) {
    const BallDrop ball({.m = 1.0,
                         .g = 9.81 / (s * s),
                         .h0 = 1.0,
                         .v0 = 0.0,
                         .e = 0.8,
                         .law = kelvin_voigt_for_restitution(1e5 / (s * s), 1.0, 0.8, false)});
    PenaltyOptions o;
    o.integrator.method = "exact-linear";
    return run_penalty(ball, o, {.t_end = 3 * s, .sample_dt = 0.15 * s});
  };
  expect_the_same_motion_in_other_time_units(run, {1e-4, 1e-8, 1e6}, 1e-9, [](const RunResult& r, double s) {
    for (const Sample& x : r.samples)
      EXPECT_NEAR(x.energy + x.dissipated, r.energy0, 1e-9 * r.energy0) << s << " at " << x.t;
  });
}

// Newton's cradle with damped springs: momentum is conserved to rounding (internal forces only),
// and E + D = E0 holds at every sample, whatever the tolerance-free steps were.
TEST(ExactLinear, TheDampedCradleKeepsMomentumAndItsLedgerToRounding) {
  BallChainParams p;
  p.e = 0.7;
  p.law = kelvin_voigt_for_restitution(1e6, p.m / 2, p.e, false);
  const BallChain chain(p);
  const RunResult r = run_penalty(chain, exact(), {.t_end = 0.05, .sample_dt = 1e-3});
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_GE(r.contacts.size(), 4u);
  for (const Sample& s : r.samples) {
    double momentum = 0;
    for (std::size_t b = 0; b < p.n; ++b) momentum += p.m * s.y[static_cast<Eigen::Index>(2 * b + 1)];
    EXPECT_NEAR(momentum, p.m * p.v0, 1e-15) << s.t;
    EXPECT_NEAR(s.energy + s.dissipated, r.energy0, 1e-13 * r.energy0) << s.t;
  }
}

// A falling column of touching balls, undamped: the ledger closes at every sample of the default
// spacing. Its step bound came from A's growth on a uniform vector, a rigid translation that no
// spring between the balls stretches: A took it to zero in two powers, the segment passed for a
// free flight, its steps spanned the contacts' oscillations and missed switches (E + D off by
// 7.6e-3 E0 from 0.29 s on).
TEST(ExactLinear, AFallingColumnSeesEverySwitch) {
  const BallStack column({.n = 3, .drop = 0.01, .law = Hooke{2.4877e5}});
  const RunResult r = run_penalty(column, exact(), {.t_end = 0.6, .sample_dt = 0.01});
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_GE(r.contacts.size(), 40u);
  for (const Sample& s : r.samples)
    EXPECT_NEAR(s.energy + s.dissipated, r.energy0, 1e-13 * r.energy0) << "t = " << s.t;
}

// A slow contact whose exit grazes: the eighth bounce of a soft ball (k = 3836 N/m, entered at
// 0.2 m/s, gravity's share g / (w V) = 0.8) leaves at 0.066 m/s, and in the held mode the spring's
// extension would pull it back within milliseconds, so the overlap crosses zero twice inside one
// step of 1 / w. Only the step's ends were looked at: the exit was stepped over and the contact
// ended later at zero speed (E + D off by 4.2e-5 E0). The exit
// speed is the closed form's for the incoming one, and the ledger closes.
TEST(ExactLinear, ASlowContactsGrazingExitIsNotSteppedOver) {
  const double m = 1, g = 9.81, k = 3835.711146279457, e = 0.8;
  const BallDrop ball({m, g, 0.19114771790873814, -0.380312195444382, e, law_named("kelvin-voigt", k, m, e)});
  PenaltyOptions o;  // the default atol, as the run that showed it
  o.integrator.method = "exact-linear";
  const RunResult r = run_penalty(ball, o, {.t_end = 2.011162045600101});
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_GE(r.contacts.size(), 8u);
  const ContactRecord& eighth = r.contacts[7];
  ASSERT_TRUE(eighth.closed());
  const SpringContact ref = linear_law_first_contact("kelvin-voigt", m, k, e, -eighth.v_in, g);
  // It ends at a thousandth of atol of overlap (1e-13 m), the closed form at zero: a delta / v^2 =
  // 2e-10 of the exit speed at 0.066 m/s.
  EXPECT_NEAR(eighth.v_out / ref.exit_speed, 1.0, 1e-9) << eighth.v_out;
  for (const Sample& s : r.samples)
    EXPECT_NEAR(s.energy + s.dissipated, r.energy0, 1e-13 * r.energy0) << "t = " << s.t;
}

// A heavy ball on a soft spring (sag m g / k = 153 m, dropped from 0.6 mm) swings 300 m deep for 25 s,
// leaves the spring at its entry speed V = 0.11 m/s and lands on it again 2 V / g = 23 ms later:
// both crossings fall within one step (a sixth of the 25 s period, and an eighth of that scanned).
// The flight's apex, a root of the gap rate inside the step, was located, and the gap, positive
// there, was reported as a root at the apex too: the contact ended at rest, 11 ms late. The roots
// are now narrowed again before such a root. Under exact-linear the exit is the closed form's (to
// a thousandth of atol of overlap, 1e-17 m, and the duration's bisection in the closed form);
// under RK8PD, which shares the stepping base, the exit is found at all.
TEST(ExactLinear, AFlightBetweenTwoContactsWithinOneStepIsNotSteppedOver) {
  const double m = 250, g = 9.81, k = 16, h0 = 6e-4, V = std::sqrt(2 * g * h0);
  const BallDrop ball({m, g, h0, 0.0, 1.0, Hooke{k}});
  const SpringContact ref = hooke_contact(m, k, V, g);
  const double t_end = std::sqrt(2 * h0 / g) + 1.5 * ref.duration;
  for (const char* method : {"exact-linear", "gsl-rk8pd"}) {
    PenaltyOptions o = exact();
    o.integrator.method = method;
    o.integrator.rtol = 1e-12;
    const RunResult r = run_penalty(ball, o, {.t_end = t_end, .sample_dt = t_end});
    ASSERT_TRUE(r.ok()) << method << ": " << r.message;
    ASSERT_EQ(r.contacts.size(), 2u) << method;
    const ContactRecord& first = r.contacts[0];
    // Left at its entry speed (a Hooke spring keeps the energy; RK8PD's exit is 7e-9 of V off), not
    // at rest at the apex; and the flight between is the parabola of that speed: its roots are
    // located to 100 ulps of t = 25 s (6e-13 s), and RK8PD's speed error shifts it by 2e-10 s.
    EXPECT_GT(first.v_out, 0.99 * V) << method << ": it left the spring, at its entry speed";
    EXPECT_NEAR(r.contacts[1].t_begin - first.t_end, 2 * first.v_out / g, 1e-9) << method;
    if (std::string(method) == "exact-linear") {
      EXPECT_NEAR(first.duration() / ref.duration, 1.0, 1e-12);
      EXPECT_NEAR(first.v_out / V, 1.0, 1e-9);
    }
  }
}

// What it cannot solve exactly it refuses, at the time it meets it, saying why: a nonlinear law
// (Hertz, Hunt–Crossley), a right-hand side that changes without a restart (switches not located),
// one that depends on time, a scene without a Jacobian (the rigid bodies), and a ledger over more
// than 64 entries (its quadratic form costs m (m + 3) / 2 right-hand sides per restart).
TEST(ExactLinear, RefusesWhatItCannotSolveExactlySayingWhy) {
  auto refused = [](const RunResult& r, const std::string& why, const std::string& what) {
    EXPECT_EQ(r.status, Status::SolverError) << what << ": " << to_string(r.status);
    EXPECT_NE(r.message.find(why), std::string::npos) << what << ": " << r.message;
  };
  const double m = 1, k = 1e5;
  // Hertz (n = 1.5, undamped) and the linear Hunt–Crossley law (n = 1, its dashpot k chi delta delta').
  for (const ContactLaw law :
       {ContactLaw{HuntCrossley{1e9, 1.5, 0.0}}, ContactLaw{HuntCrossley{k, 1.0, 0.2}}}) {
    const RunResult r = run_penalty(BallDrop({m, 9.81, 1.0, 0.0, 0.8, law}), exact(), {.t_end = 1.0});
    refused(r, "not affine", "a nonlinear law");
    EXPECT_NEAR(r.t_reached, std::sqrt(2 / 9.81), 1e-6);  // at the first contact: the flight is affine
  }
  PenaltyOptions unlocated = exact();
  unlocated.locate_switches = false;
  refused(run_penalty(BallDrop({m, 9.81, 1.0, 0.0, 0.8, Hooke{k}}), unlocated, {.t_end = 1.0}),
          "changed between restarts", "switches not located");
  // A scene without a Jacobian (the rigid ones) is refused by solve() before a run, by the setting's
  // name (it was a run failing at t = 0 as 'solver-error'); run_penalty itself still fails so.
  for (const char* name : {"penalty", "event-ode"}) {
    Method mt{.name = name};
    mt.integrator.method = "exact-linear";
    const std::string why = refusal([&] { solve(*make_scene("snooker"), mt); });
    EXPECT_NE(why.find("--integrator: value 'exact-linear' needs the scene's Jacobian"), std::string::npos)
        << name << ": " << why;
    EXPECT_NE(why.find("scene 'snooker' has none"), std::string::npos) << why;
  }
  refused(run_penalty(*make_scene("snooker"), exact(), {.t_end = 1e-3}), "needs the system's Jacobian",
          "a rigid scene");
  BallChainParams forty;
  forty.n = 40;
  forty.law = kelvin_voigt_for_restitution(1e6, forty.m / 2, 0.9, false);
  refused(run_penalty(BallChain(forty), exact(), {.t_end = 1e-3}), "beyond its 64", "a long damped chain");

  OdeSystem forced;  // x' = v, v' = -x + sin(t): affine in the state, but not autonomous
  forced.size = 2;
  forced.rhs = [](double t, ConstVectorRef y, VectorRef yd) { yd << y[1], -y[0] + std::sin(t); };
  forced.jacobian = [](double, ConstVectorRef, SparseMatrix& J) {
    J.resize(2, 2);
    J.setZero();
    J.insert(0, 1) = 1;
    J.insert(1, 0) = -1;
  };
  IntegratorOptions o;
  o.method = "exact-linear";
  auto integrator = make_integrator(o, forced, 0.5, Vector{{1.0, 0.0}});
  try {
    integrator->advance(1.0);
    FAIL() << "integrated a time-dependent right-hand side";
  } catch (const SolverFailure& f) {
    EXPECT_EQ(f.status(), Status::SolverError);
    EXPECT_NE(std::string(f.what()).find("depends on time"), std::string::npos) << f.what();
    EXPECT_EQ(f.t_reached(), 0.5);
  }
}
