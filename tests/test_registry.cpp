// The registries and solve(): every scene, law and method reachable by name; a method refuses a
// scene that lacks a capability it needs, naming it; solve() by name gives the physics the
// paradigm functions give (closed forms checked through the registry route).
#include "contact_ode/analysis/references.hpp"
#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/models/ball_drop.hpp"
#include "contact_ode/models/law_registry.hpp"
#include "contact_ode/models/mechanical_system.hpp"
#include "contact_ode/models/memory_limit.hpp"
#include "contact_ode/models/scene_registry.hpp"
#include "refusal.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <set>

using namespace contact;

TEST(Registries, NamesAreUniqueAndEveryEntryIsDescribed) {
  for (const auto& names : {method_names(), law_names(), scene_names()}) {
    EXPECT_EQ(std::set<std::string>(names.begin(), names.end()).size(), names.size());
    EXPECT_FALSE(names.empty());
  }
  for (const auto& m : method_registry()) EXPECT_FALSE(m.description.empty() || m.needs.empty()) << m.name;
  for (const auto& l : law_registry()) EXPECT_FALSE(l.description.empty() || l.parameters.empty()) << l.name;
  for (const auto& s : scene_registry()) EXPECT_GT(s.t_end, 0) << s.name;
}

// Every scene at its defaults under every method that says it can run it, over a short span:
// each runs to the end (or fails with a typed status, never an exception); every method that says
// it cannot is refused by solve() with what it needs.
TEST(Registries, EveryMethodRunsEverySceneItCanAndRefusesTheOthersByName) {
  for (const auto& s : scene_registry()) {
    const auto scene = make_scene(s.name);
    for (const auto& m : method_registry()) {
      Method method{.name = m.name, .dt = 1e-5};
      const SolveOptions span{.t_end = 1e-3, .sample_dt = 1e-3};
      if (m.can_run(*scene)) {
        const RunResult r = solve(*scene, method, span);
        EXPECT_TRUE(r.ok()) << s.name << " " << m.name << ": " << r.message;
        EXPECT_EQ(r.method, m.name);
      } else {
        const std::string why = refusal([&] { solve(*scene, method, span); });
        EXPECT_NE(why.find(m.needs), std::string::npos) << s.name << " " << m.name << ": " << why;
      }
    }
  }
  // The free spring has no impulse map and no closed-form flight: impulses and exact flight refuse it.
  const auto spring = make_scene("spring-mass");
  EXPECT_FALSE(method_info("game-symplectic").can_run(*spring));
  EXPECT_FALSE(method_info("event-ode").can_run(*spring));
  EXPECT_FALSE(method_info("event-exact").can_run(*make_scene("ball-chain")));
  EXPECT_TRUE(method_info("game-symplectic-spring").can_run(*spring));
}

TEST(Registries, UnknownNamesAndParametersAreRefusedWithWhatIsAccepted) {
  EXPECT_NE(refusal([] { method_info("rk45"); }).find("--method: value 'rk45' is not one of: penalty"),
            std::string::npos);
  EXPECT_NE(refusal([] { law_info("spring"); }).find("--law: value 'spring' is not one of: hooke"),
            std::string::npos);
  // Scenes refused at construction: what is given, and what the message must say.
  struct BadScene {
    std::string scene;
    ParameterValues given;
    std::string law, says;
  };
  const BadScene bad_scenes[] = {
      {"ball-drop", {{"height", 1.0}}, "", "parameter 'height' is not one of: m, g, h0"},
      {"snooker", {}, "hooke", "fixes its own contact law"},
      {"ball-chain",
       {{"n", 2.5}},
       "",
       "'n' = 2.5 is out of range; accepted range whole numbers in [2, 1e+09)"},
      // A ball count's range is its entry's, as every parameter's: listed by scenes(), checked by resolve().
      {"ball-chain", {{"n", 1.0}}, "", "accepted range whole numbers in [2, 1e+09)"},
      {"ball-stack", {{"n", 1e7}}, "", "accepted range whole numbers in [1, 1e+07)"},
      // Every parameter has a range: a massless ball, a restitution above one, a NaN anywhere.
      {"ball-drop",
       {{"m", 0.0}},
       "",
       "ball-drop: parameter 'm' = 0 is out of range; accepted range (0, inf)"},
      {"ball-stack", {{"e", 1.5}}, "", "accepted range [0, 1]"},
      {"snooker", {{"radius", std::nan("")}}, "", "'radius' = nan"},
      {"spring-mass", {{"x0", INFINITY}}, "", "(-inf, inf)"},
  };
  for (const auto& b : bad_scenes) {
    const std::string why = refusal([&] { make_scene(b.scene, b.given, b.law); });
    EXPECT_NE(why.find(b.says), std::string::npos) << b.scene << ": " << why;
  }
  const auto ball = make_scene("ball-drop");
  EXPECT_NE(refusal([&] { solve(*ball, {.name = "game-symplectic", .dt = 0.0}); }).find("--dt: value '0'"),
            std::string::npos);
  EXPECT_NE(refusal([&] { solve(*ball, {.name = "penalty"}, {.t_end = -1.0}); }).find("--t-end"),
            std::string::npos);
}

// The laws by name are the laws the closed forms describe: Kelvin–Voigt tuned to e has the
// damping ratio of e (contact_law.hpp), Hertz has exponent 3/2, Hooke k.
TEST(Registries, LawsByNameAreTunedAsTheirEntriesSay) {
  const LawSpec spec{.k = 1e6, .m = 0.5, .e = 0.7, .v = 2.0};
  EXPECT_EQ(stiffness(make_law("hooke", spec)), 1e6);
  const auto kv = std::get<KelvinVoigt>(make_law("kelvin-voigt", spec));
  EXPECT_NEAR(kv.c / (2 * std::sqrt(kv.k * spec.m)), damping_ratio_for_restitution(0.7), 1e-15);
  EXPECT_FALSE(kv.no_pull);
  EXPECT_TRUE(std::get<KelvinVoigt>(make_law("kelvin-voigt-clamped", spec)).no_pull);
  EXPECT_EQ(exponent(make_law("hertz", spec)), 1.5);
  EXPECT_EQ(exponent(make_law("hunt-crossley-linear", spec)), 1.0);
  for (const auto& l : law_registry()) EXPECT_EQ(exponent(l.make(spec)), l.exponent) << l.name;
}

// A Hunt-Crossley contact stops dead only as its damping grows without bound: tuned to e = 0, the
// law had chi = inf, and every penalty run on it failed at the first touch, its right-hand side not
// finite. The law is refused, naming e and its range, which the registry entry states; a damping
// factor that overflows at a tiny impact speed is refused too. e = 0 stays a Kelvin-Voigt law
// (critical damping).
TEST(Registries, AHuntCrossleyLawForEZeroIsRefusedNamingE) {
  for (const char* name : {"hertz", "hunt-crossley-linear"}) {
    const LawInfo& info = law_info(name);
    const auto e = std::find_if(info.parameters.begin(), info.parameters.end(),
                                [](const ParameterInfo& p) { return p.name == "e"; });
    ASSERT_NE(e, info.parameters.end()) << name;
    EXPECT_EQ(e->accepted.to_string(), "(0, 1]") << name;
    try {
      (void)make_law(name, {.e = 0.0});
      ADD_FAILURE() << name << " tuned to e = 0 was made";
    } catch (const std::invalid_argument& ex) {
      EXPECT_NE(std::string(ex.what()).find("--e: value '0'"), std::string::npos) << ex.what();
      EXPECT_NE(std::string(ex.what()).find("(0, 1]"), std::string::npos) << ex.what();
    }
    EXPECT_THROW((void)make_law(name, {.e = 0.5, .v = 1e-320}), std::invalid_argument) << name;
    EXPECT_TRUE(std::isfinite(std::get<HuntCrossley>(make_law(name, {.e = 1e-6})).chi)) << name;
  }
  EXPECT_NO_THROW((void)make_law("kelvin-voigt", {.e = 0.0}));
}

// Through the registry route: the exact event-driven ball's apexes are e^(2n) h0 to rounding, and
// the penalty spring-mass follows x = x0 cos(w t) to the integrator's tolerance (rtol 1e-10 over
// one period: a global error of a few hundred rtol at most).
TEST(Solve, ByNameGivesTheClosedForms) {
  const auto ball = make_scene("ball-drop", {{"e", 0.8}, {"h0", 2.0}});
  const RunResult r = solve(*ball, {.name = "event-exact"}, {.t_end = 4.0, .sample_dt = 0.1});
  ASSERT_TRUE(r.ok()) << r.message;
  const RigidBounces ref(2.0, 0.0, 9.81, 0.8);
  ASSERT_GE(r.apexes.size(), 3u);
  for (std::size_t n = 1; n <= 3; ++n) EXPECT_NEAR(r.apexes[n - 1].gap, ref.apex_height(n), 1e-12 * 2.0) << n;

  const auto spring = make_scene("spring-mass", {{"m", 1.0}, {"k", 100.0}, {"x0", 0.1}});
  Method penalty{.name = "penalty"};
  penalty.integrator.rtol = 1e-10;
  penalty.integrator.atol = 1e-12;
  const double period = 2 * std::numbers::pi / 10.0;
  const RunResult s = solve(*spring, penalty, {.t_end = period, .sample_dt = period / 8});
  ASSERT_TRUE(s.ok()) << s.message;
  for (const auto& smp : s.samples) EXPECT_NEAR(smp.y[0], 0.1 * std::cos(10.0 * smp.t), 1e-8) << smp.t;
}

// Apexes are the tops of bounces, counted from 1 (apex n follows impact n). A ball thrown up rises
// to h0 + v0^2 / 2g before its first impact; every method recorded that rise as its first apex, so
// ball_drop --v0 2 gave 1.204 m as every method's first apex where the rigid one is (e V)^2 / 2g =
// 0.770 m, and apexes[n - 1] was apex n - 1. Event-exact flies exactly: its apexes are the closed
// form's to round-off. Any other method's first apex follows its first contact and is the free
// flight from that contact's exit, v_out^2 / 2g: for the adaptive integrators at rtol 1e-10 to ten
// times the tolerance on that height (measured 4e-12 m of 0.77); for the fixed steps of dt = 1e-4 s
// to 2 v_out dt = 8e-4 m (measured at most 1.09 v_out dt): v_out is read at a
// step's end, off by up to g dt (v_out dt in height), explicit Euler's flight overshoots its top by
// g dt t / 2 = v_out dt / 2, and a parabola's top is found within a step to (g dt)^2 / 8g = 1e-9 m.
TEST(Solve, ApexesAreTheTopsOfBouncesNotTheRiseOfABallThrownUp) {
  const double h0 = 1, v0 = 2, g = 9.81, e = 0.8, dt = 1e-4, rtol = 1e-10;
  const auto ball = make_scene("ball-drop", {{"h0", h0}, {"v0", v0}, {"g", g}, {"e", e}}, "kelvin-voigt");
  const RigidBounces rigid(h0, v0, g, e);
  const RunResult exact = solve(*ball, {.name = "event-exact"}, {.t_end = 2.0, .sample_dt = 0.1});
  ASSERT_TRUE(exact.ok()) << exact.message;
  ASSERT_GE(exact.apexes.size(), 2u);
  for (std::size_t n = 1; n <= 2; ++n) EXPECT_NEAR(exact.apexes[n - 1].gap, rigid.apex_height(n), 1e-12) << n;
  for (const auto& m : method_registry()) {
    if (!m.can_run(*ball) || m.name == "event-exact") continue;
    Method method{.name = m.name, .dt = dt};
    method.integrator.rtol = rtol;
    method.integrator.atol = 1e-12;
    const RunResult r = solve(*ball, method, {.t_end = 1.2, .sample_dt = 0.1});
    ASSERT_TRUE(r.ok()) << m.name << ": " << r.message;
    ASSERT_FALSE(r.contacts.empty()) << m.name;
    const ContactRecord& first = r.contacts.front();
    for (const Apex& a : r.apexes) EXPECT_GT(a.t, first.t_begin) << m.name;
    // Projection alone pushes from the contact's start to the end; Bullet at its defaults ends the
    // contact still approaching (v_out < 0: solved before the touch) and does not bounce.
    if (!first.closed() || !(first.v_out > 0)) continue;
    ASSERT_FALSE(r.apexes.empty()) << m.name;
    EXPECT_GE(r.apexes.front().t, first.t_end) << m.name;
    const double flight = first.v_out * first.v_out / (2 * g);
    const bool adaptive = m.family == "penalty" || m.family == "event-driven";
    EXPECT_NEAR(r.apexes.front().gap, flight, adaptive ? 10 * rtol * flight : 2 * first.v_out * dt) << m.name;
  }
}

// A run's contact log is in the order the contacts began, and its apexes in time order, whatever
// the method: the fixed-step loops look at a step's contacts by index, each begun at its own time
// within the step, and logged a four-ball column's (and the 3D cradle's) contacts out of order
// under the symplectic spring, MuJoCo's spring its apexes; the first record was not the first
// contact.
TEST(Solve, ContactsAndApexesAreLoggedInTimeOrder) {
  for (const char* name : {"ball-stack", "cradle"}) {
    const auto scene = make_scene(name);
    for (const auto& m : method_registry()) {
      if (!m.can_run(*scene)) continue;
      const RunResult r = solve(*scene, {.name = m.name}, {.t_end = 1.0, .sample_dt = 1.0});
      const auto begun_before = [](const ContactRecord& a, const ContactRecord& b) {
        return a.t_begin < b.t_begin;
      };
      const auto topped_before = [](const Apex& a, const Apex& b) { return a.t < b.t; };
      EXPECT_TRUE(std::is_sorted(r.contacts.begin(), r.contacts.end(), begun_before))
          << name << " " << m.name;
      EXPECT_TRUE(std::is_sorted(r.apexes.begin(), r.apexes.end(), topped_before)) << name << " " << m.name;
    }
  }
}

// A scene tunes its damped law to the drop's impact speed: for a drop of 2^-560 m (1e-169; g
// alike, Hertz's K by 2^280 for the same contact in those units) that speed's terms underflow,
// and the law was tuned at V = 0 (chi = 0.27 s/m for 6e168): its contact bounced elastically.
// Its first restitution is the metre drop's, to 100 rtol.
TEST(Solve, AScaledDropsLawIsTunedAtItsOwnImpactSpeed) {
  const auto first_restitution = [](double s) {
    const auto ball =
        make_scene("ball-drop", {{"h0", s}, {"g", 9.81 * s}, {"k", 1e5 / std::sqrt(s)}}, "hertz");
    Method penalty{.name = "penalty"};
    penalty.integrator.rtol = 1e-8;
    penalty.integrator.atol = 1e-10 * s;
    const RunResult r = solve(*ball, penalty, {.t_end = 1.0, .sample_dt = 1.0});
    EXPECT_TRUE(r.ok()) << s << ": " << r.message;
    return r.contacts.empty() ? std::nan("") : r.contacts.front().restitution();
  };
  const double metre = first_restitution(1.0);
  EXPECT_NEAR(first_restitution(0x1p-560), metre, 1e-6);
}

TEST(Registries, MethodsForASceneAreThoseThatCanRunIt) {
  const auto ball = make_scene("ball-drop");
  const auto spring = make_scene("spring-mass");
  EXPECT_EQ(methods_for(*ball), method_names());  // the ball drop runs every method
  for (const auto& name : methods_for(*spring)) EXPECT_TRUE(method_info(name).can_run(*spring)) << name;
  const auto for_spring = methods_for(*spring);
  EXPECT_EQ(std::find(for_spring.begin(), for_spring.end(), "event-ode"), for_spring.end());
}

// The closed forms by law name: Hooke's contact time pi sqrt(m/k) without gravity, the clamped
// Kelvin–Voigt law's exit speed e_clamped(zeta) V, and NaN for a law without one.
TEST(Registries, LinearLawClosedFormsByName) {
  const double m = 2.0, k = 1e4, V = 3.0, e = 0.5;
  EXPECT_NEAR(linear_law_first_contact("hooke", m, k, e, V, 0.0).duration,
              std::numbers::pi * std::sqrt(m / k), 1e-14);
  const double zeta = damping_ratio_for_restitution(e);
  const SpringContact clamped = linear_law_first_contact("kelvin-voigt-clamped", m, k, e, V, 0.0);
  EXPECT_NEAR(clamped.exit_speed, clamped_kelvin_voigt_restitution(zeta) * V, 1e-14);
  EXPECT_DOUBLE_EQ(clamped.max_penetration,
                   linear_law_first_contact("kelvin-voigt", m, k, e, V, 0.0).max_penetration);
  EXPECT_TRUE(std::isnan(linear_law_first_contact("hertz", m, k, e, V, 0.0).duration));
}

// The closed forms outside their documented domains (references.hpp) are refused, naming the
// argument and its range: before, a restitution of 1.5 gave a negative damping ratio (-0.128), an
// overdamped Kelvin-Voigt contact NaN, a rigid bounce at e = 1.5 apexes above the drop, and g = 0
// a Zeno time of NaN, each returned as if it were an answer.
TEST(Registries, ClosedFormsRefuseArgumentsOutsideTheirDomain) {
  EXPECT_NE(refusal([] {
              damping_ratio_for_restitution(1.5);
            }).find("damping_ratio_for_restitution: e = 1.5 is out of range; accepted range [0, 1]"),
            std::string::npos);
  EXPECT_NE(refusal([] { kelvin_voigt_contact(1, 1, 1.5, 1); }).find("zeta = 1.5"), std::string::npos);
  EXPECT_NE(refusal([] { hooke_contact(0, 1, 1, 0); }).find("hooke_contact: m = 0"), std::string::npos);
  EXPECT_NE(refusal([] { hooke_contact(1, 1, 0, 0); }).find("V = 0"), std::string::npos);  // no contact
  EXPECT_NE(refusal([] { RigidBounces(1, 0, 9.81, 1.5); }).find("rigid bounces: e = 1.5"), std::string::npos);
  EXPECT_NE(refusal([] { RigidBounces(1, 0, 0, 0.5); }).find("g = 0"), std::string::npos);
  EXPECT_NE(refusal([] { hunt_crossley_restitution(-1); }).find("chi V = -1"), std::string::npos);
  EXPECT_NE(refusal([] { linear_law_first_contact("hooke", 1, -1, 1, 1, 0); }).find("k = -1"),
            std::string::npos);
  // Impacts and apexes are counted from 1: n = 0 was impact 1 to impact_time and V^2 / 2g to
  // apex_height, so a 0-based loop read the first impact twice.
  const RigidBounces drop(1, 0, 9.81, 0.8);
  const std::string counted =
      " n (counted from 1: apex n follows impact n) = 0 is out of range; accepted "
      "range whole numbers in [1, inf)";
  EXPECT_NE(refusal([&] { drop.impact_time(0); }).find("impact time" + counted), std::string::npos);
  EXPECT_NE(refusal([&] { drop.apex_height(0); }).find("apex height" + counted), std::string::npos);
  EXPECT_NE(refusal([&] { drop.apex_time(0); }).find("apex time" + counted), std::string::npos);
  // Inside them, the edges are answers: V = 0 under gravity is a ball set down on the spring (a
  // full period 2 pi / w), and a critically damped contact gives e = 0 (zeta = 1).
  EXPECT_NEAR(hooke_contact(1, 1e4, 0, 9.81).duration, 2 * std::numbers::pi / 100, 1e-14);
  EXPECT_EQ(damping_ratio_for_restitution(0.0), 1.0);
}

// The rigid bounces' impact times are a closed form: T(n) summed term by term took n steps (n = 2^63
// never returned, from Python too) and passed the Zeno time by rounding (n = 1e6: 4 ulps past it).
// The closed form agrees with the sum in long double to a few ulps of the tail (log and expm1 are
// correct to an ulp; the fraction 1 - e^(n-1) is formed without cancellation), and never passes
// zeno_time(). A first impact beyond the doubles' range (g = h0 = 1.5e308: V = 2.1e308) is refused;
// every apex was NaN. (g = 1e308 at h0 = 1 m, whose 2 g h0 overflows, has V = 1.4e154 m/s.)
TEST(Registries, RigidImpactTimesAreAClosedFormBoundedByTheZenoTime) {
  const std::string why = refusal([] { RigidBounces(1.5e308, 0.0, 1.5e308, 0.8); });
  EXPECT_NE(why.find("rigid bounces: the first impact (speed sqrt(v0^2 + 2 g h0) = inf"), std::string::npos)
      << why;
  EXPECT_NE(why.find("h0 = 1.5e+308, v0 = 0, g = 1.5e+308"), std::string::npos) << why;
  EXPECT_NEAR(RigidBounces(1.0, 0.0, 1e308, 0.8).V / (std::sqrt(2.0) * 1e154), 1.0, 1e-15);
  const std::vector<double> restitutions{0.0, 0.5, 0.8, 0.999999, 1.0};
  for (const double e : restitutions) {
    const RigidBounces ref(1.0, 0.5, 9.81, e);
    long double sum = ref.T1, en = 1;
    for (std::size_t n = 1; n <= 200; ++n) {
      if (n > 1) sum += 2 * (en *= e) * static_cast<long double>(ref.V) / ref.g;
      EXPECT_NEAR(ref.impact_time(n), static_cast<double>(sum), 8e-16 * static_cast<double>(sum))
          << e << " " << n;
    }
    EXPECT_LE(ref.impact_time(1000000), ref.zeno_time()) << e;
  }
  // Last, as on the old code it never returns (the test's timeout ends it).
  for (const double e : restitutions) {
    const RigidBounces ref(1.0, 0.5, 9.81, e);
    const std::size_t n = std::numeric_limits<std::size_t>::max();
    EXPECT_LE(ref.impact_time(n), ref.zeno_time()) << e;
    EXPECT_TRUE(std::isfinite(ref.apex_time(n))) << e;
    if (e < 1) {
      EXPECT_EQ(ref.impact_time(n), ref.zeno_time()) << e;  // e^(n-1) underflows: the fraction is 1
    }
  }
}

// A ball thrown down fast under weak gravity reaches the floor at T1 = 2 h0 / (V - v0), h0 / |v0| to
// first order in g h0 / v0^2. (v0 + V) / g, the same root, cancelled: 0.0142 s for 0.01 s at
// h0 = 1 m, v0 = -100 m/s, g = 1e-12 m/s^2, 7.9e-7 of it off at g = 1e-6. The exact flight
// (event-exact) finds it too; both are held to the series h0 / |v0| (1 - g h0 / (2 v0^2)) to 1e-15.
TEST(Registries, ABallThrownDownUnderWeakGravityLandsAtItsClosedFormTime) {
  for (const double g : {1e-12, 1e-6, 1e-4}) {  // the series's next term, (g h0 / v0^2)^2 / 2, below 1e-16
    const double h0 = 1, v0 = -100, series = h0 / -v0 * (1 - g * h0 / (2 * v0 * v0));
    EXPECT_NEAR(RigidBounces(h0, v0, g, 0.8).T1, series, 1e-15 * series) << g;
    const BallDrop ball({.m = 1, .g = g, .h0 = h0, .v0 = v0, .e = 0.8, .law = Hooke{1e5}});
    const RunResult r = solve(ball, {.name = "event-exact"}, {.t_end = 0.02, .sample_dt = 0.02});
    ASSERT_TRUE(r.ok()) << r.message;
    ASSERT_FALSE(r.contacts.empty()) << g;
    EXPECT_NEAR(r.contacts.front().t_begin, series, 1e-15 * series) << g;
  }
}

// The spring contacts' closed forms at the edges of the doubles. A contact scaled by lambda = 2^1020
// in speed and gravity is the same contact, lambda times deeper and faster, equally long (the
// scaling is exact in binary); the clamped law formed w^2 x and v_r^2 and called it a contact that
// never let go. Hooke's depth under a heavy mass, 2 g m / k to 1e-15 here, was inf (s^2 overflowed).
// A k / m outside the doubles' normal range, or a sag g m / k beyond it, is refused: each gave NaN.
TEST(Registries, SpringContactClosedFormsScaleToTheEdgesOfTheDoubles) {
  const double lambda = std::ldexp(1.0, 1020), m = 1.0, k = 1e4, zeta = 0.1, V = 1.0, g = 9.81;
  for (const auto form : {&kelvin_voigt_contact, &clamped_kelvin_voigt_contact}) {
    const SpringContact unit = form(m, k, zeta, V, g), big = form(m, k, zeta, lambda * V, lambda * g);
    ASSERT_TRUE(std::isfinite(unit.duration));
    EXPECT_NEAR(big.duration, unit.duration, 1e-14 * unit.duration);
    EXPECT_NEAR(big.max_penetration / lambda, unit.max_penetration, 1e-14 * unit.max_penetration);
    EXPECT_NEAR(big.exit_speed / lambda, unit.exit_speed, 1e-14 * unit.exit_speed);
  }
  EXPECT_NEAR(hooke_contact(1e308, 1e4, 1.0, 9.81).max_penetration, 2 * 9.81e304, 1e-15 * 2 * 9.81e304);
  EXPECT_NE(refusal([] { kelvin_voigt_contact(1e-306, 1e4, 0.1, 1.0, 9.81); }).find("k / m = inf"),
            std::string::npos);
  EXPECT_NE(
      refusal([] { clamped_kelvin_voigt_contact(1e10, 1e-300, 0.1, 1.0, 0.0); })
          .find(
              "k / m = 1e-310 (k = 1e-300, m = 10000000000), the contact's frequency squared, is out of the "
              "doubles' normal range"),
      std::string::npos);
  EXPECT_NE(refusal([] { hooke_contact(1.0, 1e-300, 1.0, 1e10); }).find("the static sag g m / k = inf"),
            std::string::npos);
}

// Critical damping (e = 0): the Kelvin–Voigt formulas divide by w_d = 0, and every quantity of a
// contact tuned to e = 0 was NaN. The motion is V t e^(-w t) without gravity: deepest V / (w e) at
// 1 / w; the unclamped overlap never closes (duration +inf, exit speed 0); the clamped force,
// w^2 x + 2 w x' = V w^2 e^(-w t) (2 / w - t), lets go at 2 / w at speed V e^-2, and the overlap
// (2 V / (w e^2)) closes 2 / w later. exact-linear, the exact solution, agrees (to 1e-11, as on
// every linear contact: tests/test_exact_linear.cpp), with gravity too, where both hold the ball
// for good.
TEST(Registries, ACriticallyDampedContactHasItsClosedForms) {
  const double m = 1, k = 1e4, w = 100, V = 1;
  const SpringContact open = linear_law_first_contact("kelvin-voigt", m, k, 0.0, V, 0.0);
  EXPECT_EQ(open.duration, std::numeric_limits<double>::infinity());
  EXPECT_EQ(open.exit_speed, 0.0);
  EXPECT_NEAR(open.max_penetration, V / (w * std::numbers::e), 1e-17);
  const SpringContact clamped = linear_law_first_contact("kelvin-voigt-clamped", m, k, 0.0, V, 0.0);
  EXPECT_NEAR(clamped.duration, 4 / w, 1e-16);
  EXPECT_NEAR(clamped.exit_speed, V * std::exp(-2.0), 1e-16);
  EXPECT_EQ(clamped_kelvin_voigt_restitution(1.0), std::exp(-2.0));
  for (const double g : {0.0, 9.81})
    for (const std::string law : {"kelvin-voigt", "kelvin-voigt-clamped"}) {
      const double h0 = 1e-2;
      const double v0 = g > 0 ? 0.0 : -V, speed = std::sqrt(v0 * v0 + 2 * g * h0);
      const SpringContact ref = linear_law_first_contact(law, m, k, 0.0, speed, g);
      Method exact{.name = "penalty"};
      exact.integrator.method = "exact-linear";
      exact.integrator.atol = 1e-16;
      const auto ball =
          make_scene("ball-drop", {{"m", m}, {"k", k}, {"e", 0.0}, {"g", g}, {"h0", h0}, {"v0", v0}}, law);
      const RunResult r = solve(*ball, exact, {.t_end = 0.3, .sample_dt = 0.3});
      ASSERT_TRUE(r.ok()) << r.message;
      ASSERT_FALSE(r.contacts.empty()) << law << " g = " << g;
      const ContactRecord& c = r.contacts.front();
      EXPECT_NEAR(c.max_penetration, ref.max_penetration, 1e-11 * ref.max_penetration) << law << " g = " << g;
      if (std::isinf(ref.duration)) {
        EXPECT_FALSE(c.closed()) << law << " g = " << g << ": held for good";
      } else {
        EXPECT_NEAR(c.duration(), ref.duration, 1e-11 * ref.duration) << law << " g = " << g;
        EXPECT_NEAR(c.v_out, ref.exit_speed, 1e-11 * ref.exit_speed) << law << " g = " << g;
      }
    }
}

// A value below the smallest normal double is refused by every entry to the library, as the command
// line refuses it, naming the option and its range: before, a 1e-310 s span under CVODE 'succeeded'
// with a NaN state, and a 1e-310 kg ball, step or tolerance ended each method in another failure
// that did not name it (a right-hand side not finite, ODE's LCP, MuJoCo's mass check).
TEST(Solve, ValuesBelowTheSmallestNormalDoubleAreRefusedNamingThem) {
  const auto ball = make_scene("ball-drop");
  const auto tiny = [&](const Method& m, const SolveOptions& span) {
    return refusal([&] { solve(*ball, m, span); });
  };
  const std::string below = "is below the smallest normal double (2.22507e-308); accepted range";
  EXPECT_NE(
      tiny({.name = "penalty"}, {.t_end = 1e-310}).find("--t-end: value '1e-310' " + below + " (0, inf)"),
      std::string::npos);
  EXPECT_NE(tiny({.name = "penalty"}, {.t_end = 1.0, .sample_dt = 5e-324})
                .find("--sample-dt: value '5e-324' " + below),
            std::string::npos);
  Method penalty{.name = "penalty"};
  penalty.integrator.atol = 1e-310;
  EXPECT_NE(tiny(penalty, {.t_end = 1.0}).find("--atol: value '1e-310' " + below + " (0, inf)"),
            std::string::npos);
  EXPECT_NE(tiny({.name = "game-euler", .dt = 1e-310}, {.t_end = 1.0}).find("--dt: value '1e-310' " + below),
            std::string::npos);
  EXPECT_NE(refusal([] {
              make_scene("ball-drop", {{"m", 1e-310}});
            }).find("ball-drop: parameter 'm' = 1e-310 " + below + " (0, inf)"),
            std::string::npos);
  EXPECT_NE(refusal([] {
              make_scene("ball-drop", {{"v0", -1e-310}});
            }).find("'v0' = -1e-310 " + below),
            std::string::npos);
  EXPECT_NO_THROW(make_scene("ball-drop", {{"v0", 0.0}}));  // zero is no subnormal
}

// A run that cannot fit is refused before it starts, naming what it would hold: its output samples
// (the whole state each) and MethodInfo::working_doubles per state entry (128 for an ODE integrator,
// 20 for a fixed-step loop). A chain of 1e8 balls (the scene accepts up to 1e9), or 1e5 balls
// sampled every 10 us for 0.1 s (16 GB), filled the machine until the kernel killed the process.
// Here the limit is set to 2.5 MB: 1000 balls (2000 values) at 101 samples need 8 * 2000 * (128 +
// 101) B = 3.66 MB, at 6 samples 2.14 MB (penalty) and 0.42 MB (a fixed step).
TEST(Solve, ARunThatCannotFitIsRefusedBeforeItStarts) {
  const auto chain = make_scene("ball-chain", {{"n", 1000.0}}, "hooke");
  SolveOptions many{.t_end = 1e-4, .sample_dt = 1e-6};
  many.limits.max_memory_bytes = 2.5e6;
  const std::string why = refusal([&] { solve(*chain, {.name = "penalty"}, many); });
  EXPECT_EQ(why.rfind("penalty on ball-chain needs about 0.003664 GB (101 output samples of its 2e+03 state "
                      "values, and 128 working doubles per value); a run may hold 0.0025 GB",
                      0),
            0u)
      << why;
  // A fixed-step method's samples are its steps at most: dt = 2e-5 s takes 5 steps, 6 samples.
  SolveOptions few = many;
  EXPECT_TRUE(solve(*chain, {.name = "game-symplectic-spring", .dt = 2e-5}, few).ok());
  few.sample_dt = 2e-5;
  EXPECT_TRUE(solve(*chain, {.name = "penalty"}, few).ok());
  EXPECT_GT(RunLimits{}.max_memory_bytes, 1e8);  // half of what any machine this runs on lets it use
}

// make_scene builds the initial state (it checks the bodies' gaps on one): a chain of 5e8 balls
// allocated its 8 GB there and ended in std::bad_alloc, or the OOM killer, before solve() could
// refuse the run. A chain whose state alone (2n doubles) is more than a run may hold is refused by
// the scene now, before any state is built.
TEST(Scenes, AStateThatAloneCannotBeHeldIsRefusedBeforeItIsBuilt) {
  const double n = std::ceil(half_the_memory_limit() / 16) + 1;
  if (!(n < 1e9)) GTEST_SKIP() << "this machine may hold the largest chain the scene accepts";
  const std::string why = refusal([&] { make_scene("ball-chain", {{"n", n}}); });
  const std::string expected =
      fmt::format("scene 'ball-chain' at n = {:g}: its state alone is {:.3g} values", n, 2 * n);
  EXPECT_EQ(why.rfind(expected, 0), 0u) << why;
  EXPECT_NE(why.find("(half the memory this process may use): fewer bodies"), std::string::npos) << why;
  // The bound is the state alone: a chain of 1000 balls (16 kB) is made as before.
  EXPECT_EQ(refusal([&] { make_scene("ball-chain", {{"n", 1000.0}}); }), "");
}

// A scene whose bodies start inside each other was built and run: the spinning box places its ball
// at the first angle that clears the box's swept edge, and a ball too large to clear it anywhere
// stayed where the search ended, 0.17 m inside the box at radius 0.194 m (0.68 m at 0.70); the
// penalty run launched it at 378 m/s and the table said success. Refused now by the scene, naming
// the parameters given, for every scene; touching bodies (a resting column, a touching cradle:
// gaps of zero to rounding) are apart, and so is every scene at its defaults.
TEST(Registries, AScenesBodiesMustStartApart) {
  const std::string inside = refusal([] { make_scene("spinning-box", {{"radius", 0.194}}); });
  EXPECT_NE(inside.find("radius = 0.194"), std::string::npos) << inside;
  EXPECT_NE(inside.find("0.169 m inside each other"), std::string::npos) << inside;
  for (const auto& name : scene_names()) EXPECT_NO_THROW(make_scene(name)) << name;
  EXPECT_NO_THROW(make_scene("ball-stack", {{"n", 50.0}}));                    // touching
  EXPECT_NO_THROW(make_scene("ball-chain", {{"n", 50.0}, {"spacing", 0.0}}));  // touching
  EXPECT_NO_THROW(make_scene("spinning-box", {{"radius", 0.1}}));
  // Sizes whose squared distances overflow: a gap of inf, once run as no contact at all.
  const std::string overflow = refusal([] { make_scene("wedge", {{"radius", 1e300}}); });
  EXPECT_NE(overflow.find("radius = 1e+300"), std::string::npos) << overflow;
  EXPECT_NE(overflow.find("a gap of inf m"), std::string::npos) << overflow;
  EXPECT_NO_THROW(make_scene("wedge", {{"radius", 1e150}}));
}

// The batched gaps, gap rates and switching functions (what root functions read at every step)
// are each contact's own, for every scene and law, on states that put contacts apart, touching,
// overlapping, approaching and separating: the overrides (a chain's and a stack's loops, a one-law
// scene's single dispatch) must not differ from the per-contact definitions they replace.
TEST(Scenes, BatchedGapsAndSwitchingAreEachContactsOwn) {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 1.0);
  int checked = 0;
  for (const auto& name : scene_names())
    for (const auto& law : law_names()) {
      std::unique_ptr<Dynamics> scene;
      try {
        scene = make_scene(name, {}, law);
      } catch (const std::invalid_argument&) {
        continue;  // a law the scene does not take
      }
      const auto* geo = dynamic_cast<const ContactGeometry*>(scene.get());
      const std::size_t nc = scene->contact_count();
      if (!geo || nc == 0) continue;
      const Vector y0 = scene->initial_state();
      std::vector<double> d(nc), r(nc), s(nc), r2(nc);
      for (int trial = 0; trial < 20; ++trial) {
        Vector y = y0;
        const double scale = trial == 0 ? 0.0 : std::pow(10.0, -(trial % 5) - 1);
        for (Eigen::Index k = 0; k < y.size(); ++k) y[k] += scale * (1.0 + std::abs(y0[k])) * noise(rng);
        geo->gaps_and_rates(y, d, r);
        geo->switching_and_rates(y, s, r2);
        for (std::size_t i = 0; i < nc; ++i) {
          ASSERT_EQ(d[i], geo->gap(i, y)) << name << ' ' << law << " contact " << i;
          ASSERT_EQ(r[i], geo->gap_rate(i, y)) << name << ' ' << law << " contact " << i;
          ASSERT_EQ(s[i], geo->switching(i, y)) << name << ' ' << law << " contact " << i;
          ASSERT_EQ(r2[i], geo->gap_rate(i, y)) << name << ' ' << law << " contact " << i;
        }
      }
      ++checked;
    }
  // The ball drop, chain, stack and rigid scenes under the laws each takes: 15 pairs today, and a
  // registry that lost scenes or laws would check fewer than 10.
  EXPECT_GE(checked, 10) << checked;
}

// SolveOptions::progress hears of every sample as it is recorded, in order, the last at t_end:
// what an experiment's progress line shows of a long run. Every method of the ball drop, each
// family's sampling (the fixed steps', the adaptive drivers', the event loop's, the engines').
TEST(Registries, ARunsProgressHearsOfEverySampleInOrder) {
  const auto ball = make_scene("ball-drop", {}, "kelvin-voigt");
  for (const auto& name : methods_for(*ball)) {
    std::vector<double> heard;
    const RunResult r =
        solve(*ball, {.name = name},
              {.t_end = 1.0, .sample_dt = 0.1, .progress = [&](double t) { heard.push_back(t); }});
    ASSERT_TRUE(r.ok()) << name << ": " << r.message;
    ASSERT_EQ(heard.size(), r.samples.size()) << name;
    for (std::size_t i = 0; i < heard.size(); ++i) EXPECT_EQ(heard[i], r.samples[i].t) << name << " " << i;
    EXPECT_EQ(heard.back(), 1.0) << name;
  }
}
