// Penalty contact under CVODE against the closed forms of a spring contact
// (analysis/references.hpp): with gravity, duration (pi + 2 atan(g/(wV)))/w and maximum
// penetration g/w^2 + sqrt(g^2/w^4 + V^2/w^2); without it pi sqrt(m/k) and V sqrt(m/k).
//
// Tolerances: the runs use rtol = 1e-10, atol = 1e-12. CVODE keeps each step's local error below
// that; a contact takes O(100) steps and a bounce O(10) more, so the global error stays below
// ~1e-8 relative. Root location adds ~100 ulps of t. A relative tolerance of 1e-6 leaves two
// orders of margin and is still 10^3-10^4 times smaller than the effects the tests separate
// (e.g. the gravity correction to the contact time).
#include "contact_ode/analysis/fit.hpp"
#include "contact_ode/analysis/metrics.hpp"
#include "contact_ode/analysis/references.hpp"
#include "contact_ode/integrators/event_driven.hpp"
#include "contact_ode/integrators/penalty.hpp"
#include "contact_ode/models/ball_chain.hpp"
#include "contact_ode/models/ball_drop.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

using namespace contact;

namespace {

constexpr double kRel = 1e-6;

SolveOptions until(double t_end) { return {.t_end = t_end, .sample_dt = 0.01}; }

PenaltyOptions tight() {
  PenaltyOptions o;
  o.integrator.rtol = 1e-10;
  o.integrator.atol = 1e-12;
  return o;
}

RunResult drop(ContactLaw law, double g, double h0, double v0, double t_end, double e = 1.0) {
  return run_penalty(BallDrop({1.0, g, h0, v0, e, law}), tight(), until(t_end));
}

}  // namespace

TEST(PenaltyHooke, ContactDurationAndPenetrationWithGravityMatchTheClosedForm) {
  for (double k : {1e3, 1e5, 1e7}) {
    const RunResult r = drop(Hooke{k}, 9.81, 1.0, 0.0, 0.6);
    ASSERT_TRUE(r.ok()) << r.message;
    ASSERT_GE(r.contacts.size(), 1u);
    const double V = std::sqrt(2 * 9.81);
    const auto ref = hooke_contact(1.0, k, V, 9.81);
    const auto& c = r.contacts.front();
    EXPECT_NEAR(c.duration(), ref.duration, kRel * ref.duration) << "k = " << k;
    EXPECT_NEAR(c.max_penetration, ref.max_penetration, kRel * ref.max_penetration) << "k = " << k;
    EXPECT_NEAR(c.restitution(), 1.0, kRel) << "k = " << k;
    // The test separates the gravity forms from the gravity-free limits: at k = 1e3 the two
    // differ by g/(wV) ~ 7 % in duration.
    if (k == 1e3) {
      EXPECT_GT(std::abs(c.duration() - std::numbers::pi * std::sqrt(1.0 / k)), 1e3 * kRel * ref.duration);
    }
  }
}

TEST(PenaltyHooke, WithoutGravityTheContactLastsPiSqrtMOverK) {
  for (double k : {1e2, 1e4, 1e6, 1e8}) {
    const double v0 = 2.0;
    const RunResult r = drop(Hooke{k}, 0.0, 0.1, -v0, 0.1 / v0 + 4 * std::sqrt(1.0 / k));
    ASSERT_TRUE(r.ok()) << r.message;
    ASSERT_EQ(r.contacts.size(), 1u);
    const auto& c = r.contacts.front();
    EXPECT_NEAR(c.t_begin, 0.1 / v0, kRel * c.t_begin);
    EXPECT_NEAR(c.duration(), std::numbers::pi * std::sqrt(1.0 / k), kRel * c.duration()) << "k = " << k;
    EXPECT_NEAR(c.max_penetration, v0 * std::sqrt(1.0 / k), kRel * c.max_penetration) << "k = " << k;
  }
}

TEST(PenaltyHooke, UndampedBallKeepsItsApexHeightAndFollowsTheExactPenaltySequence) {
  const double k = 1e5;
  const RunResult r = drop(Hooke{k}, 9.81, 1.0, 0.0, 5.0);
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_GE(r.apexes.size(), 5u);
  for (const auto& a : r.apexes) EXPECT_NEAR(a.gap, 1.0, kRel) << "t = " << a.t;
  for (std::size_t n = 1; n <= r.contacts.size(); ++n) {
    const double Tn = hooke_impact_time(1.0, k, 1.0, 0.0, 9.81, n);
    EXPECT_NEAR(r.contacts[n - 1].t_begin, Tn, kRel * Tn) << "impact " << n;
  }
  EXPECT_LT(compute_metrics(r).max_energy_error, kRel);
}

// The closed-form trajectory (the reference of convergence_dt) is the penalty solution: CVODE at
// rtol 1e-10 follows it at every sample to 1e-6 of the drop height and impact speed, it is at the
// floor at each impact time, and it conserves E = v^2/2 + g x (+ k x^2 / 2m in contact).
TEST(PenaltyHooke, TrajectoryFollowsTheClosedForm) {
  const double k = 1e4, g = 9.81, V = std::sqrt(2 * g);
  const RunResult r = drop(Hooke{k}, g, 1.0, 0.0, 3.0);
  ASSERT_TRUE(r.ok()) << r.message;
  for (const auto& s : r.samples) {
    const BallState ref = hooke_ball_state(1.0, k, 1.0, 0.0, g, s.t);
    EXPECT_NEAR(s.y[0], ref.x, kRel) << "t = " << s.t;
    EXPECT_NEAR(s.y[1], ref.v, kRel * V) << "t = " << s.t;
    const double energy = 0.5 * ref.v * ref.v + g * ref.x + (ref.x < 0 ? 0.5 * k * ref.x * ref.x : 0.0);
    EXPECT_NEAR(energy, g, 1e-12) << "t = " << s.t;  // rounding of terms up to k x^2 / 2 ~ 10 J/kg
  }
  for (std::size_t n = 1; n <= 3; ++n)
    EXPECT_NEAR(hooke_ball_state(1.0, k, 1.0, 0.0, g, hooke_impact_time(1.0, k, 1.0, 0.0, g, n)).x, 0.0,
                1e-12)
        << n;
}

TEST(PenaltyKelvinVoigt, UnclampedRestitutionEqualsTheTargetWithoutGravity) {
  for (double e : {0.1, 0.5, 0.8, 0.95}) {
    const auto law = kelvin_voigt_for_restitution(1e6, 1.0, e, false);
    const RunResult r = drop(law, 0.0, 0.1, -1.0, 0.2);
    ASSERT_TRUE(r.ok()) << r.message;
    ASSERT_EQ(r.contacts.size(), 1u);
    const auto ref = kelvin_voigt_contact(1.0, 1e6, damping_ratio_for_restitution(e), 1.0);
    EXPECT_NEAR(r.contacts[0].restitution(), e, kRel) << "e = " << e;
    EXPECT_NEAR(r.contacts[0].duration(), ref.duration, kRel * ref.duration) << "e = " << e;
    EXPECT_NEAR(r.contacts[0].max_penetration, ref.max_penetration, kRel * ref.max_penetration);
  }
}

TEST(PenaltyKelvinVoigt, ClampedLawOvershootsTheTargetByTheClosedFormFactor) {
  for (double e : {0.1, 0.5, 0.8, 0.95}) {
    const auto law = kelvin_voigt_for_restitution(1e6, 1.0, e, true);
    const RunResult r = drop(law, 0.0, 0.1, -1.0, 0.2);
    ASSERT_TRUE(r.ok()) << r.message;
    ASSERT_EQ(r.contacts.size(), 1u);
    const double expected = clamped_kelvin_voigt_restitution(damping_ratio_for_restitution(e));
    EXPECT_NEAR(r.contacts[0].restitution(), expected, kRel) << "e = " << e;
    // The clamp raises restitution by far more than the tolerance (5e-4 even at e = 0.95).
    EXPECT_GT(r.contacts[0].restitution(), e + 10 * kRel) << "e = " << e;
  }
}

// Without gravity the clamped contact lasts until the overlap it lets go at closes: the push,
// (pi - 2 asin zeta) / w_d, plus 2 zeta / w at the exit speed (references.hpp).
TEST(PenaltyKelvinVoigt, ClampedContactLastsUntilTheOverlapCloses) {
  for (double e : {0.3, 0.8}) {
    const double k = 1e6, zeta = damping_ratio_for_restitution(e), w = std::sqrt(k);
    const RunResult r = drop(kelvin_voigt_for_restitution(k, 1.0, e, true), 0.0, 0.1, -1.0, 0.2);
    ASSERT_TRUE(r.ok()) << r.message;
    ASSERT_EQ(r.contacts.size(), 1u);
    const double expected =
        ((std::numbers::pi - 2 * std::asin(zeta)) / std::sqrt(1 - zeta * zeta) + 2 * zeta) / w;
    EXPECT_NEAR(r.contacts[0].duration() / expected, 1.0, kRel) << "e = " << e;
  }
}

// The first contact of either Kelvin–Voigt law against its exact closed form
// (linear_law_first_contact), from no gravity to gravity's share g / (w V) of order one, where the
// gravity-free limit is off by tens of percent. The clamped law's contact lasts until the overlap it
// let go at closes, and the reference said only until the release (4 % short at e = 0.8); with
// gravity both references were the gravity-free limit. A spring that holds the ball for good has
// an unending contact (duration +inf) and the run's first contact never closes.
TEST(PenaltyKelvinVoigt, FirstContactMatchesTheExactClosedFormWithAndWithoutGravity) {
  struct Case {
    double m, k, e, g, h0;
  };
  const double g = 9.81;
  for (const bool clamp : {false, true}) {
    const std::string law = clamp ? "kelvin-voigt-clamped" : "kelvin-voigt";
    for (const Case c : {Case{1, 1e6, 0.3, 0, 0.1}, Case{1, 1e6, 0.8, 0, 0.1}, Case{1, 1e3, 0.9, g, 0.01},
                         Case{1, 20, 0.9, g, 1.0}, Case{4, 300, 0.9, g, 0.05}, Case{1, 100, 0.5, g, 0.1}}) {
      const double V = c.g > 0 ? std::sqrt(2 * c.g * c.h0) : 1.0, w = std::sqrt(c.k / c.m);
      const SpringContact ref = linear_law_first_contact(law, c.m, c.k, c.e, V, c.g);
      // Thrown down from h0 at V without gravity; dropped from h0 with it. Three contact times
      // (unending ones: three undamped periods).
      const double t_end = (c.g > 0 ? V / c.g : c.h0 / V) +
                           3 * (std::isfinite(ref.duration) ? ref.duration : 2 * std::numbers::pi / w);
      const auto contact_law = kelvin_voigt_for_restitution(c.k, c.m, c.e, clamp);
      const RunResult r = run_penalty(BallDrop({c.m, c.g, c.h0, c.g > 0 ? 0.0 : -V, c.e, contact_law}),
                                      tight(), until(t_end));
      const std::string what = fmt::format("{} k = {} g / (w V) = {:.2f}", law, c.k, c.g / (w * V));
      ASSERT_TRUE(r.ok()) << what << ": " << r.message;
      ASSERT_GE(r.contacts.size(), 1u) << what;
      const ContactRecord& first = r.contacts.front();
      EXPECT_NEAR(first.max_penetration / ref.max_penetration, 1.0, kRel) << what;
      if (!std::isfinite(ref.duration)) {
        EXPECT_FALSE(first.closed()) << what;  // held: the run ends inside the first contact
        continue;
      }
      ASSERT_TRUE(first.closed()) << what;
      EXPECT_NEAR(first.duration() / ref.duration, 1.0, kRel) << what;
      EXPECT_NEAR(first.v_out / ref.exit_speed, 1.0, kRel) << what;
    }
  }
  // The comparison tells gravity's forms from the gravity-free limit: at g / (w V) = 1.1 they differ
  // by far more than kRel.
  const double V = std::sqrt(2 * g * 0.05);
  EXPECT_GT(std::abs(linear_law_first_contact("kelvin-voigt", 4, 300, 0.9, V, g).duration /
                         linear_law_first_contact("kelvin-voigt", 4, 300, 0.9, V, 0).duration -
                     1),
            1e4 * kRel);
}

// Under gravity at low stiffness (k = 300 N/m, m = 4 kg: w = 8.7 rad/s, g / (w V) = 1.1) the
// clamped law lets go while the ball still overlaps the floor and gravity still slows it. The
// contact used to end at the release, whose speed was 17 % off the next apex, and the spring
// energy left there (k delta^2 / 2) was booked as numerical drift (1.3e-2). Now the contact ends
// where the overlap closes, so its restitution gives the next apex (v_out^2 / 2g) and the next
// impact speed, and the released energy is booked as a physical loss: E + dissipated = E0 to the
// solver's tolerance (rtol 1e-10: ~1e-9 after a few hundred steps).
TEST(PenaltyKelvinVoigt, ClampedContactUnderGravityAgreesWithApexImpactAndLedger) {
  const double m = 4.0, g = 9.81, h0 = 0.05;
  const auto law = kelvin_voigt_for_restitution(300.0, m, 0.9, true);
  const RunResult r = run_penalty(BallDrop({m, g, h0, 0.0, 0.9, law}), tight(), until(1.0));
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_GE(r.contacts.size(), 2u);
  ASSERT_GE(r.apexes.size(), 1u);
  const ContactRecord& first = r.contacts[0];
  ASSERT_TRUE(first.closed());
  EXPECT_NEAR(first.v_in, -std::sqrt(2 * g * h0), 1e-8);
  EXPECT_NEAR(r.apexes[0].gap / (first.v_out * first.v_out / (2 * g)), 1.0, 1e-8);
  EXPECT_NEAR(r.contacts[1].v_in / -first.v_out, 1.0, 1e-8);
  // The ledger: the apex's energy plus what was booked equals the initial energy, to the global
  // error of the integration. The ledger is a quadrature, so its local errors add up without
  // growing: each step's within rtol = 1e-10 of a ledger below E0, ~500 steps in all (the soft
  // spring holds the ball for a third of a second), so rtol times the steps bounds the closure
  // (1.1e-8 measured).
  const double closure = 1e-10 * static_cast<double>(r.stats.steps);
  EXPECT_NEAR((r.apexes[0].energy + r.apexes[0].dissipated) / r.energy0, 1.0, closure);
  for (const auto& smp : r.samples)
    EXPECT_NEAR((smp.energy + smp.dissipated) / r.energy0, 1.0, closure) << "t = " << smp.t;
}

// As k grows the penalty bounce approaches the event-driven (rigid) one. For the undamped spring
// the second impact is late by exactly the contact time T_c = (pi + 2 atan(g/(wV)))/w, so the
// error falls as k^(-1/2) (exponent -1/2 up to the O(1/k) gravity term, < 0.01 over k = 1e4..1e8)
// with coefficient pi sqrt(m).
TEST(PenaltyConvergence, BounceTimesApproachTheEventDrivenOnesAsKToTheMinusOneHalf) {
  const BallDrop rigid({1.0, 9.81, 1.0, 0.0, 1.0, Hooke{1.0}});
  EventOptions eo;
  SolveOptions eo_span;
  eo_span.t_end = 1.5;
  const RunResult reference = run_event_driven(rigid, rigid, eo, eo_span);
  ASSERT_GE(reference.contacts.size(), 2u);
  std::vector<double> ks, errors;
  for (double k = 1e4; k <= 1e8 * 1.0001; k *= 10) {
    const RunResult r = drop(Hooke{k}, 9.81, 1.0, 0.0, 1.5);
    ASSERT_TRUE(r.ok()) << r.message;
    ASSERT_GE(r.contacts.size(), 2u);
    ks.push_back(k);
    errors.push_back(std::abs(r.contacts[1].t_begin - reference.contacts[1].t_begin));
  }
  const PowerFit fit = fit_power_law(ks, errors);
  EXPECT_NEAR(fit.exponent, -0.5, 0.01);
  EXPECT_NEAR(fit.coefficient, std::numbers::pi, 0.05 * std::numbers::pi);
}

// With damping tuned to e and gravity on, the achieved restitution differs from the target by
// the gravity term, O(g / (w V)), so it too converges as k^(-1/2).
TEST(PenaltyConvergence, DampedRestitutionApproachesTheTargetWithGravity) {
  const double e = 0.8;
  std::vector<double> ks, errors;
  for (double k = 1e4; k <= 1e8 * 1.0001; k *= 10) {
    const RunResult r = drop(kelvin_voigt_for_restitution(k, 1.0, e, false), 9.81, 1.0, 0.0, 0.6, e);
    ASSERT_TRUE(r.ok()) << r.message;
    ks.push_back(k);
    errors.push_back(std::abs(r.contacts.front().restitution() - e));
  }
  const PowerFit fit = fit_power_law(ks, errors);
  EXPECT_NEAR(fit.exponent, -0.5, 0.02);
}

TEST(PenaltyLocating, SwitchesLocatedOrNotGiveTheSameContactAtTightTolerance) {
  const BallDrop model({1.0, 9.81, 1.0, 0.0, 0.8, kelvin_voigt_for_restitution(1e5, 1.0, 0.8, false)});
  PenaltyOptions located = tight(), stepped = tight();
  const SolveOptions span_located = until(0.6);
  stepped.locate_switches = false;
  const RunResult a = run_penalty(model, located, span_located),
                  b = run_penalty(model, stepped, span_located);
  ASSERT_TRUE(a.ok() && b.ok());
  ASSERT_EQ(a.contacts.size(), b.contacts.size());
  // The unlocated run steps over the force's jump (c delta_dot at delta = 0): CVODE's error test
  // rejects and shrinks steps there, so it still meets the tolerance, at a cost.
  EXPECT_NEAR(a.contacts[0].restitution(), b.contacts[0].restitution(), 1e-5);
  EXPECT_GT(b.stats.failed_steps, a.stats.failed_steps);
}

// The energy ledger: E0 = E + dissipated + drift. The drift is the integration error of E and of
// the integrated dissipation, each controlled by the tolerance: it must fall with rtol, and stay
// within ~1000 rtol (global error over ~700 steps and 6 contacts, each within the local tolerance).
TEST(EnergyLedger, PenaltyDriftShrinksWithTheToleranceWhileTheLossIsPhysical) {
  const BallDrop model({1.0, 9.81, 1.0, 0.0, 0.8, kelvin_voigt_for_restitution(1e5, 1.0, 0.8, false)});
  double previous = 1.0;
  for (double rtol : {1e-6, 1e-8, 1e-10}) {
    PenaltyOptions o = tight();
    const SolveOptions o_span = until(3.0);
    o.integrator.rtol = rtol;
    o.integrator.atol = rtol * 1e-2;
    const RunResult r = run_penalty(model, o, o_span);
    ASSERT_TRUE(r.ok()) << r.message;
    const RunMetrics m = compute_metrics(r);
    EXPECT_LT(m.max_energy_drift, 1000 * rtol) << "rtol " << rtol;
    EXPECT_LT(m.max_energy_drift, previous) << "rtol " << rtol;
    previous = m.max_energy_drift;
    // The loss itself is physical and does not depend on the tolerance: e = 0.8 over six
    // bounces leaves about e^12 of the energy above the floor, so > 90 % was dissipated.
    EXPECT_GT(r.samples.back().dissipated / r.energy0, 0.9);
  }
}

// The unit of mass changes nothing: a drop of m = 2^-20 or 2^20 kg on a spring and dashpot scaled
// alike (k and c times m, powers of two, so every force / m is the same double) is the run at
// 1 kg, step for step. The ledger was kept in joules under an atol made for metres: at 1e-6 kg
// (E0 = 9.8e-6 J; 2^-20 kg alike) it fell out of the error test, the run took 686 steps for 766
// and its first apex came out 4.5e-7 m off (rtol 1e-8); at 1e6 kg it took 782.
TEST(EnergyLedger, TheUnitOfMassChangesNoStep) {
  const auto run = [](double m) {
    PenaltyOptions o;
    o.integrator.rtol = 1e-8;
    o.integrator.atol = 1e-10;
    return run_penalty(
        BallDrop({m, 9.81, 1.0, 0.0, 0.8, kelvin_voigt_for_restitution(1e5 * m, m, 0.8, false)}), o,
        until(3.0));
  };
  const RunResult one = run(1.0);
  ASSERT_TRUE(one.ok()) << one.message;
  ASSERT_GE(one.apexes.size(), 4u);
  for (const double m : {std::ldexp(1.0, -20), std::ldexp(1.0, 20)}) {
    const RunResult r = run(m);
    ASSERT_TRUE(r.ok()) << m << ": " << r.message;
    EXPECT_EQ(r.stats.steps, one.stats.steps) << "m = " << m;
    ASSERT_EQ(r.apexes.size(), one.apexes.size()) << "m = " << m;
    for (std::size_t n = 0; n < one.apexes.size(); ++n)  // 1e-15 m: a few ulps of a height below 1 m
      EXPECT_NEAR(r.apexes[n].gap, one.apexes[n].gap, 1e-15) << "m = " << m << ", apex " << n + 1;
    EXPECT_NEAR(r.samples.back().dissipated / r.energy0, one.samples.back().dissipated / one.energy0, 1e-15)
        << "m = " << m;
  }
}

// A spring energy beyond the doubles (k = 1e300: k x^2 / 2 overflows at an overlap of 1e-4 m)
// has no drift rate. energy_drift ended with "fit_line: x and y must be finite" and exit 2, as
// if the user's input were wrong; the gain says it is not finite now, and the rate is NaN.
TEST(EnergyLedger, AnEnergyBeyondTheDoublesHasNoRateAndSaysSo) {
  RunResult r;
  r.energy0 = 9.81;
  for (double t : {0.0, 0.5, 1.0})
    r.samples.push_back({t, Vector::Zero(2), t < 0.7 ? 9.81 : std::numeric_limits<double>::infinity(), 0.0});
  EnergyGain g;
  ASSERT_NO_THROW(g = energy_gain(r));
  EXPECT_TRUE(std::isnan(g.rate));
  EXPECT_TRUE(std::isnan(g.rate_sd));
  EXPECT_EQ(g.verdict(), "energy not finite");
  r.samples.back().energy = 9.81;  // finite again: a rate, and the verdict of a conserving run
  g = energy_gain(r);
  EXPECT_EQ(g.rate, 0.0);
  EXPECT_EQ(g.verdict(), "conserves");
}

// A stiff Hertz contact (K = 4.3e9 N/m^1.5, m = 0.53 kg, g = 100: a found case) under every GSL
// method: a trial stage of an over-long explicit step overflows before the error test can reject
// the step. GSL failed the run at the first non-finite value (rk8pd: 'non-finite-state' at
// t = 0.068 s); like SUNDIALS it now retries the step shorter, and the run matches CVODE BDF's.
TEST(PenaltyHertz, AnOverflowingTrialStepIsRetriedShorter) {
  const BallDrop model({0.53, 100.0, 0.043, 0.0, 0.0, HuntCrossley{4.3e9, 1.5, 0.256}});
  const auto run = [&](const std::string& method) {
    PenaltyOptions o = tight();
    o.integrator.method = method;
    o.integrator.max_steps = 10000000;
    return run_penalty(model, o, until(0.1));
  };
  const RunResult reference = run("cvode-bdf");
  ASSERT_TRUE(reference.ok()) << reference.message;
  ASSERT_GE(reference.contacts.size(), 2u);
  for (const char* method : {"gsl-rk8pd", "gsl-rkf45", "gsl-msbdf"}) {
    const RunResult r = run(method);
    ASSERT_TRUE(r.ok()) << method << ": " << r.message;
    ASSERT_EQ(r.contacts.size(), reference.contacts.size()) << method;
    // Both at rtol 1e-10 over ~2 contacts: the first contact's times agree to 1e-8 s.
    EXPECT_NEAR(r.contacts[0].t_begin, reference.contacts[0].t_begin, 1e-8) << method;
    EXPECT_NEAR(r.contacts[0].t_end, reference.contacts[0].t_end, 1e-8) << method;
  }
}

// A contact stiffer than the run resolves fails, Status::Unresolved, and one it resolves keeps the
// energy and its ledger. The undamped ball returns to its energy after every bounce; a switch is
// taken at 1e-3 atol of overlap and located in time to ~100 u t, and the spring starts from the
// energy it stores there, so past k ~ 1e20 N/m (contacts of 3e-10 s) that energy is the contact's
// error: at k = 1e29 the ball once left with 6 times its energy, a 'success'. In the contact's own
// time, sqrt(m / k), every stiff k is the same problem (only gravity's share, g / (w V), changes),
// so a resolved run's error in E and in the ledger E + D is the softest run's at that tolerance
// (measured within 0.2 to 2 times it): each run here either fails so or stays within 10 times
// it. The switch off, a little past touching, once left the spring's pull there out of D (half k
// thr^2: 70 times the softest run's ledger error at k = 1e20, rtol 1e-6). No contact of a
// material's stiffness (k <= 1e16 here) is refused.
TEST(PenaltyHooke, AContactTooStiffToResolveFailsAndOneResolvedKeepsItsEnergy) {
  for (const auto& [rtol, atol] : {std::pair{1e-6, 1e-8}, {1e-8, 1e-10}, {1e-10, 1e-12}}) {
    PenaltyOptions o;
    o.integrator.rtol = rtol;
    o.integrator.atol = atol;
    o.integrator.max_steps = 1000000;
    double soft_error = NAN, soft_ledger = NAN;
    for (double k = 1e8; k <= 1e30; k *= 100) {
      const RunResult r = run_penalty(BallDrop({1.0, 9.81, 1.0, 0.0, 1.0, Hooke{k}}), o, {.t_end = 2.5});
      const std::string at = fmt::format("k = {:g}, rtol = {:g}", k, rtol);
      if (r.status == Status::Unresolved) {
        EXPECT_GT(k, 1e16) << at;
        EXPECT_NE(r.message.find("too short or too shallow"), std::string::npos) << r.message;
        continue;
      }
      ASSERT_EQ(r.status, Status::Success) << at << ": " << r.message;
      ASSERT_GE(r.contacts.size(), 3u) << at;
      const Sample& end = r.samples.back();
      const double error = std::abs(end.energy - r.energy0);
      const double ledger = std::abs(end.energy + end.dissipated - r.energy0);
      if (std::isnan(soft_error)) {  // the softest run, k = 1e8 (never refused, as asserted above)
        soft_error = error;
        soft_ledger = ledger;
      }
      EXPECT_LE(error, 10 * soft_error) << at;
      EXPECT_LE(ledger, 10 * soft_ledger) << at;
    }
  }
}

// The same drop under exact-linear, exact to rounding between switches: it is held to the default
// rtol's bound, 1e-5 of a contact's energy, so a resolved run's energy is within that bound per
// contact, and its ledger closes to rounding, 1e-12 (measured 5e-16 to 5e-14: the switches' energy is
// booked exactly). It let the ball at k = 1e29 leave with 28 times its energy, and at 1e24 lose
// 2.3e-3 of it, both 'success'.
TEST(PenaltyExactLinear, AContactTooStiffToResolveFailsAndOneResolvedKeepsItsEnergy) {
  PenaltyOptions o;
  o.integrator.method = "exact-linear";
  const double bound = 1000 * o.integrator.rtol;
  for (double k = 1e8; k <= 1e30; k *= 100) {
    const RunResult r = run_penalty(BallDrop({1.0, 9.81, 1.0, 0.0, 1.0, Hooke{k}}), o, {.t_end = 2.5});
    const std::string at = fmt::format("k = {:g}", k);
    if (r.status == Status::Unresolved) {
      EXPECT_GT(k, 1e16) << at;
      continue;
    }
    ASSERT_EQ(r.status, Status::Success) << at << ": " << r.message;
    ASSERT_GE(r.contacts.size(), 3u) << at;
    const Sample& end = r.samples.back();
    const double contacts = static_cast<double>(r.contacts.size());
    EXPECT_LT(std::abs(end.energy - r.energy0), contacts * bound * r.energy0) << at;
    EXPECT_LT(std::abs(end.energy + end.dissipated - r.energy0), 1e-12 * r.energy0) << at;
  }
}

// Two balls of 0.1 kg meeting at 1 m/s under a Kelvin–Voigt law damped to e = 0 (k = 1e6 N/m,
// m_eff = 0.05 kg): the damping rate c / m_eff = 2 omega = 8944 1/s bounds an explicit step at
// a few 1e-4 s (the real stability interval of a fourth-order Runge–Kutta is about 2.8 / 8944).
// Below it the fixed-step ERK run ends as the exact one does: one contact, the balls moving on
// together at 0.5 m/s each, to rounding: every step conserves their momentum, and the critically
// damped relative speed decays as omega t exp(-omega t), to exp(-179) in the 0.04 s after the contact. Beyond
// it each step crosses the contact without resolving it, and the contact ends (its overlap
// closing) with the balls still approaching, which no trajectory does: the gap rises through
// zero there, so its rate is not negative. Main answered 'success' at dt = 3e-3 s with 35843
// such 'contacts'.
TEST(PenaltyFixedStep, AStepBeyondTheContactsStabilityFailsInsteadOfChattering) {
  const BallChain chain({.n = 2, .e = 0.0, .law = kelvin_voigt_for_restitution(1e6, 0.05, 0.0, false)});
  PenaltyOptions o;
  o.integrator.method = "arkode-erk";
  for (const double dt : {1e-5, 1e-4, 1e-3, 3e-3}) {
    o.integrator.dt = dt;
    const RunResult r = run_penalty(chain, o, {.t_end = 0.05, .sample_dt = 0.05});
    const std::string at = fmt::format("dt = {:g}", dt);
    if (dt < 3e-4) {
      ASSERT_EQ(r.status, Status::Success) << at << ": " << r.message;
      EXPECT_EQ(r.contacts.size(), 1u) << at;
      EXPECT_NEAR(r.samples.back().y[1], 0.5, 1e-12) << at;
      EXPECT_NEAR(r.samples.back().y[3], 0.5, 1e-12) << at;
      continue;
    }
    EXPECT_EQ(r.status, Status::Unresolved) << at << ": " << r.message;
    EXPECT_NE(r.message.find("still approaching"), std::string::npos) << r.message;
    EXPECT_NE(r.message.find(fmt::format("a fixed step of dt = {:g} s is too long", dt)), std::string::npos)
        << r.message;
    EXPECT_NEAR(r.t_reached, 0.01, 2 * dt) << at;  // at the first contact, 1 cm away at 1 m/s
  }
}
