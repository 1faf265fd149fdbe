#include "contact_ode/analysis/contact_advisor.hpp"

#include "contact_ode/models/law_registry.hpp"

#include "contact_ode/analysis/contact_measurement.hpp"
#include "contact_ode/analysis/references.hpp"
#include "contact_ode/integrators/game_step.hpp"
#include "contact_ode/integrators/gsl_handles.hpp"
#include "contact_ode/models/ball_drop.hpp"
#include "contact_ode/models/parameters.hpp"

#include <fmt/format.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace contact {

namespace {

using std::numbers::pi;

[[noreturn]] void bad(const std::string& option, double value, const std::string& accepted) {
  throw std::invalid_argument(
      fmt::format("{}: value '{}' is {}; accepted {}", option, value, outside(value), accepted));
}

// zeta in (0, 1) with e_clamped(zeta) = e, by GSL's Brent solver on [0, 1).
double clamped_damping_ratio(double e) {
  gsl::report_errors_by_return_code();
  if (e >= 1.0) return 0.0;
  auto f = [](double zeta, void* p) {
    return clamped_kelvin_voigt_restitution(zeta) - *static_cast<double*>(p);
  };
  gsl_function fn{+f, &e};
  gsl::RootSolver brent(gsl_root_fsolver_alloc(gsl_root_fsolver_brent));
  if (!brent) throw std::runtime_error("gsl_root_fsolver_alloc failed");
  if (gsl_root_fsolver_set(brent.get(), &fn, 0.0, 1.0 - 1e-12) != GSL_SUCCESS)
    throw std::runtime_error("clamped damping ratio: the root is not bracketed in [0, 1)");
  double lo = 0, hi = 1;
  for (int i = 0; i < 200; ++i) {
    gsl_root_fsolver_iterate(brent.get());
    lo = gsl_root_fsolver_x_lower(brent.get());
    hi = gsl_root_fsolver_x_upper(brent.get());
    if (gsl_root_test_interval(lo, hi, 1e-15, 1e-15) == GSL_SUCCESS) break;
  }
  return 0.5 * (lo + hi);
}

struct Designed {
  ContactLaw law;
  double k_lin, c_lin;
};

// Extreme inputs (a mass of 1e-300 kg, a penetration of 1e300 m) give a design double precision
// cannot hold or simulate: the refusal says so in terms of the inputs that made it.
[[noreturn]] void unresolvable(const ContactRequest& r, double k, const std::string& k_unit, double duration,
                               double penetration) {
  const std::string inputs =
      r.radius ? "--m, --v, --radius/--young/--poisson" : "--m, --v, --max-penetration/--duration";
  // A NaN here is inf / inf inside a closed form: "a contact of nan s" named no quantity.
  const auto shown = [](double x, const char* unit, const char* what) {
    return std::isnan(x) ? fmt::format("an undefined {}", what) : fmt::format("{:g} {}", x, unit);
  };
  throw std::invalid_argument(
      fmt::format("{}: m = {:g} kg, v = {:g} m/s give k = {:g} {}, a contact of {} and {} and an "
                  "energy m v^2 / 2 of {:g} J, outside what double precision resolves; accepted: inputs "
                  "giving a finite, positive stiffness, duration, penetration and 1e4 times the energy "
                  "above 1e-300",
                  inputs, r.m, r.v, k, k_unit, shown(duration, "s", "duration"),
                  shown(penetration, "m", "penetration"), 0.5 * r.m * r.v * r.v));
}

// The laws design() builds as Hunt–Crossley laws (every one but the linear spring-dashpots), the
// ones a damping rule applies to.
bool hunt_crossley_family(const std::string& law) {
  return law != "hooke" && law != "kelvin-voigt" && law != "kelvin-voigt-clamped";
}

Designed design(const ContactRequest& r) {
  const double m = r.m, V = r.v;
  if (r.law == "kelvin-voigt" || r.law == "kelvin-voigt-clamped") {
    const bool clamped = r.law == "kelvin-voigt-clamped";
    const double zeta = clamped ? clamped_damping_ratio(r.e) : damping_ratio_for_restitution(r.e);
    const double s = std::sqrt(1 - zeta * zeta), theta = std::atan2(s, zeta);
    // Duration times w: pi / s unclamped; clamped, the push until release, (pi - 2 asin zeta) / s,
    // then the overlap closing at the exit speed, 2 zeta (references.hpp).
    const double wT = clamped ? (pi - 2 * std::asin(zeta)) / s + 2 * zeta : pi / s;
    const double w =
        r.max_penetration ? V * std::exp(-zeta * theta / s) / *r.max_penetration : wT / *r.duration;
    const double k = m * w * w, c = 2 * zeta * m * w;  // 2 zeta sqrt(k m), without forming k m
    return {KelvinVoigt{k, c, clamped}, k, c};
  }
  if (r.law == "hooke") {
    // m (V / delta)^2, not m V^2 / delta^2: each square underflowed for a contact at 1e-165 m.
    const double k = r.max_penetration ? m * (V / *r.max_penetration) * (V / *r.max_penetration)
                                       : m * (pi / *r.duration) * (pi / *r.duration);
    return {Hooke{k}, k, 0.0};
  }
  // Hunt–Crossley family (hunt_crossley_family). The damping the rule gives lowers the
  // penetration and lengthens the contact: K designed for the undamped contact met neither (a
  // duration of 1.2e-4 s asked at e = 0.014 lasted 9.3e-4 s; a penetration asked at e = 0.18 came
  // out half). The penetration is exact with damping (hunt_crossley_max_penetration); the
  // duration has no closed form but scales exactly: with chi V fixed, x = delta / (V T), tau = t / T
  // and T^(n+1) = m V^(1-n) / K make the contact K-free, so the duration goes as K^(-1/(n+1)), and
  // one measured contact at a trial K gives the K that lasts as asked.
  const double n = r.law == "hertz" ? 1.5 : 1.0;
  const double chi = damping_factor(r.rule.value_or(kDefaultDampingRule), r.e, V);
  const std::string unit = fmt::format("N/m^{:g}", n);  // K's
  double K;
  if (r.radius) {
    K = hertz_stiffness(*r.radius, effective_modulus(*r.young, *r.poisson, INFINITY, 0.0));
  } else if (r.max_penetration) {
    // (n + 1) m f V^2 / delta^(n+1) as (V / delta)^2 delta^(1-n): V^2 underflowed at 1e-165 m/s.
    const double d = *r.max_penetration;
    K = (n + 1) * m * hunt_crossley_approach_factor(chi * V) * (V / d) * (V / d) * std::pow(d, 1 - n);
  } else {
    // The trial: the undamped contact that lasts as asked.
    const double dmax = *r.duration * V / (2 * power_law_time_factor(n));
    const double trial = (n + 1) * m * (V / dmax) * (V / dmax) * std::pow(dmax, 1 - n) / 2;
    if (!(std::isfinite(trial) && trial > 0)) unresolvable(r, trial, unit, *r.duration, dmax);
    const double lasted = measure_isolated_contact(HuntCrossley{trial, n, chi}, m, V).duration;
    K = trial * std::pow(lasted / *r.duration, n + 1);
  }
  // A stiffness out of the doubles' range has no contact to measure: refused here, in terms of the
  // inputs, before the closed form refuses it in terms of its own arguments.
  if (!(std::isfinite(K) && K > 0)) unresolvable(r, K, unit, NAN, NAN);
  const double dmax = hunt_crossley_max_penetration(m, K, n, chi, V);
  return {HuntCrossley{K, n, chi}, n * K * std::pow(dmax, n - 1),
          K * std::pow(dmax, n) * chi};  // K chi overflowed for a heavy, slow body
}

// Flores's and Gonthier's rules damp without bound as e -> 0 (chi V ~ 1 / e), and a dashpot near
// critical damping holds on long: such a contact outlasts the 100 undamped durations its
// measurement simulates. Its duration over the undamped one depends on e alone (at a fixed chi V or
// zeta the contact is free of K, m and V: design()), so a bisection of e on a unit contact finds the
// smallest e measured, and the refusal names it (it was a RuntimeError naming no option).
[[noreturn]] void refuse_restitution(const ContactRequest& r, const std::string& reason) {
  ContactRequest unit = r;
  unit.m = unit.v = 1;
  unit.max_penetration = 1e-3;
  unit.duration = unit.radius = unit.young = unit.poisson = std::nullopt;
  auto ends = [&](double e) {
    unit.e = e;
    try {
      measure_isolated_contact(design(unit).law, unit.m, unit.v);
      return true;
    } catch (const ContactDidNotEnd&) {
      return false;
    }
  };
  double fails = r.e, lasts = 1;  // e = 1 is undamped
  for (int i = 0; i < 60 && lasts > 1.0005 * fails; ++i) {
    const double e = std::sqrt(fails * lasts);
    (ends(e) ? lasts : fails) = e;
  }
  const double digit = std::pow(10.0, std::floor(std::log10(lasts)) - 2);
  const double least = std::ceil(lasts / digit) * digit;  // three digits, rounded up: accepted
  const std::string rule =
      hunt_crossley_family(r.law)
          ? fmt::format(" under the {} rule", to_string(r.rule.value_or(kDefaultDampingRule)))
          : "";
  bad("--e", r.e,
      fmt::format("range [{:.3g}, 1] for {}{}: below it the contact lasts longer than the advisor's check "
                  "simulates ({})",
                  least, r.law, rule, reason));
}

template <class F>
auto refusing_restitution(const ContactRequest& r, F&& f) {
  try {
    return f();
  } catch (const ContactDidNotEnd& why) {
    refuse_restitution(r, why.what());
  }
}

// A check runs 32 phases of at most this many steps each (about 0.6 s in all): a budget of 1e-18
// asked for steps of 1e-12 s, which the game loop refused for work, and the refusal's initial
// state read as an error of 0.
constexpr double kMaxCheckSteps = 2e5;

double check_steps(double duration, double dt) { return 2 + 4 * duration / dt; }

// The semi-implicit game loop on the isolated contact, with the spring: the worst energy drift
// after the contact (ledger: E0 - E - dissipated) over 32 phases of the step grid against the
// moment of impact. Each run spans four times the contact's measured duration, so that it is after
// the contact: four undamped durations end a heavily damped Hunt–Crossley contact half-way (at
// e = 0.014 it lasts 7.7 times as long; the error read there was the same to four digits, the
// slow end of such a contact adding little, but it is the error after the contact that is asked).
double game_energy_error(const ContactLaw& law, double m, double V, double duration, double dt) {
  double worst = 0;
  constexpr int kPhases = 32;
  for (int phase = 0; phase < kPhases; ++phase) {
    const double h0 = V * dt * (1.0 + phase / static_cast<double>(kPhases));
    const BallDrop model({m, 0.0, h0, -V, 1.0, law});
    const double t_end = h0 / V + 4 * duration;
    const RunResult r = run_game(
        model, {.dt = dt, .scheme = FixedStepScheme::SemiImplicitEuler, .resolution = GameResolution::Spring},
        {.t_end = t_end, .sample_dt = t_end});
    // An unstable step's error is unbounded (the step a strong dashpot allows is below the bound's).
    if (r.status == Status::Diverged || r.status == Status::NonFiniteState) return INFINITY;
    if (!r.ok())
      throw std::runtime_error(fmt::format("the game step's check at dt = {:g} s stopped at t = {:g} s: {}",
                                           dt, r.t_reached, r.message));
    const auto& s = r.samples.back();
    worst = std::max(worst, std::abs(r.energy0 - s.energy - s.dissipated) / r.energy0);
  }
  return worst;
}

// The bound (contact_advisor.hpp) is exact for the undamped spring; a dashpot or a power law
// breaks the conserved modified energy, so the step is then checked by the phase scan and shrunk
// until it meets the budget. With a dashpot the error is of first order in h (the study's
// Kelvin–Voigt contact: 1.84e-5 at 1.6e-7 s, 9.8e-6 at 8.6e-8 s), not the undamped second: the
// first shrink takes the second order, each after it the order its last two checks show (the
// second's square root alone took five checks at a budget of 1e-5, and at 1e-8 shrank the step
// until the game loop refused it for work).
// A step too small to check in kMaxCheckSteps is refused, naming the budget the check reaches.
std::pair<double, double> advised_game_step(const ContactLaw& law, const ContactRequest& r, double omega,
                                            double stable_dt, double duration) {
  const double budget = r.energy_error, smallest = 4 * duration / (kMaxCheckSteps - 2);
  auto check = [&](double dt) { return game_energy_error(law, r.m, r.v, duration, dt); };
  auto refuse = [&](double wanted, double at_smallest) {
    // (an error of 1 or more, unstable included, is no budget: the range is (0, 1))
    const std::string reached =
        at_smallest < 1
            ? fmt::format("accepted for this contact down to {:.3g}, the error the check measures",
                          at_smallest)
            : fmt::format("no budget below 1 is checked for this contact: the error is {:.3g}", at_smallest);
    throw std::invalid_argument(fmt::format(
        "--energy-error: value '{:g}' asks for a semi-implicit Euler step near {:.3g} s, {:.3g} steps per "
        "contact, more than the {:g} the advisor simulates to check it; {} at its smallest step, {:.3g} s",
        budget, wanted, check_steps(duration, wanted), kMaxCheckSteps, reached, smallest));
  };
  // The bound's step, within the scheme's stability limit (a strong dashpot's limit is below it:
  // Gonthier's rule at e = 2e-5 diverged at the bound's step), at least the smallest checked (the
  // bound is the worst phase's, which the 32 phases checked may not reach).
  double dt = std::max(std::min(2 * std::sqrt(budget / (1 + budget)) / omega, 0.95 * stable_dt), smallest),
         error = check(dt), order = 2.0;
  for (int shrink = 0; shrink < 20 && error > budget; ++shrink) {
    const double wanted = std::isinf(error) ? dt / 2 : dt * 0.95 * std::pow(budget / error, 1 / order);
    if (dt == smallest) refuse(wanted, error);
    const double dt_before = std::exchange(dt, std::max(wanted, smallest)),
                 error_before = std::exchange(error, check(dt));
    if (error > 0 && error < error_before && std::isfinite(error_before))
      order = std::clamp(std::log(error_before / error) / std::log(dt_before / dt), 1.0, 2.0);
  }
  if (error > budget)
    throw std::runtime_error(fmt::format(
        "the game step's check did not meet the energy budget {:g}: {:g} at {:g} s after 20 shrinks", budget,
        error, dt));
  return {dt, error};
}

}  // namespace

void validate(const ContactRequest& r) {
  // (and normal, as the command line takes them: a 1e-310 kg mass was refused by a formula inside)
  auto finite = [](double v) { return std::isfinite(v) && !is_subnormal(v); };
  if (!(finite(r.m) && r.m > 0)) bad("--m", r.m, "range (0, inf)");
  if (!(finite(r.v) && r.v > 0)) bad("--v", r.v, "range (0, inf)");
  if (!(finite(r.e) && r.e >= 0 && r.e <= 1)) bad("--e", r.e, "range [0, 1]");
  const auto laws = law_names();
  if (std::find(laws.begin(), laws.end(), r.law) == laws.end())
    throw std::invalid_argument(
        fmt::format("--law: value '{}' is not one of: {}", r.law, fmt::join(laws, ", ")));
  if (r.rule && !hunt_crossley_family(r.law)) {
    std::vector<std::string> takes_rule = laws;
    std::erase_if(takes_rule, [](const std::string& law) { return !hunt_crossley_family(law); });
    throw std::invalid_argument(
        fmt::format("--rule: value '{}' is for the Hunt-Crossley laws; accepted with --law {} (law {} has no "
                    "damping rule)",
                    to_string(*r.rule), fmt::join(takes_rule, " or "), r.law));
  }
  const bool material = r.radius || r.young || r.poisson;
  const int given = (r.max_penetration ? 1 : 0) + (r.duration ? 1 : 0) + (material ? 1 : 0);
  if (given != 1)
    throw std::invalid_argument(
        "--max-penetration / --duration: give exactly one requirement (or, for hertz, --radius, --young and "
        "--poisson)");
  if (r.max_penetration && !(finite(*r.max_penetration) && *r.max_penetration > 0))
    bad("--max-penetration", *r.max_penetration, "range (0, inf)");
  if (r.duration && !(finite(*r.duration) && *r.duration > 0))
    bad("--duration", *r.duration, "range (0, inf)");
  if (material) {
    if (r.law != "hertz")
      throw std::invalid_argument("--radius/--young/--poisson: a material defines only the hertz law");
    if (!(r.radius && r.young && r.poisson))
      throw std::invalid_argument("--radius, --young, --poisson: give all three");
    if (!(finite(*r.radius) && *r.radius > 0)) bad("--radius", *r.radius, "range (0, inf)");
    if (!(finite(*r.young) && *r.young > 0)) bad("--young", *r.young, "range (0, inf)");
    if (!(finite(*r.poisson) && *r.poisson > -1 && *r.poisson < 0.5))
      bad("--poisson", *r.poisson, "range (-1, 0.5)");
  }
  if (r.law == "hooke" && r.e != 1) bad("--e", r.e, "range [1, 1] for hooke, which is undamped");
  if (r.law == "kelvin-voigt" && r.e == 0)
    bad("--e", r.e, "range (0, 1] for kelvin-voigt (e = 0 is critical damping: the contact never ends)");
  if (r.law == "kelvin-voigt-clamped" && r.e < std::exp(-2.0))
    bad("--e", r.e,
        fmt::format("range [{:.4f}, 1] for kelvin-voigt-clamped (exp(-2), reached at critical damping)",
                    std::exp(-2.0)));
  if ((r.law == "hertz" || r.law == "hunt-crossley-linear") && r.e == 0)
    bad("--e", r.e, "range (0, 1] for the Hunt-Crossley laws");
  if (!(finite(r.energy_error) && r.energy_error > 0 && r.energy_error < 1))
    bad("--energy-error", r.energy_error, "range (0, 1)");
  if (!(finite(r.engine_step) && r.engine_step > 0)) bad("--engine-step", r.engine_step, "range (0, inf)");
  if (!(finite(r.g) && r.g > 0)) bad("--g", r.g, "range (0, inf)");
  const Designed d = refusing_restitution(r, [&] { return design(r); });
  // Extreme inputs (a mass of 1e-300 kg, a penetration of 1e300 m) give a design double precision
  // cannot hold or simulate: say so in terms of the inputs, before the check's own solver does.
  // (A stiffness that underflowed to 0 has no contact: NaN fails the checks below.)
  const double K = stiffness(d.law), nan = std::nan("");
  const SpringContact undamped = std::isfinite(K) && K > 0 ? power_law_contact(r.m, K, exponent(d.law), r.v)
                                                           : SpringContact{nan, nan, nan};
  const double scales[] = {d.k_lin, std::sqrt(d.k_lin / r.m), undamped.duration, undamped.max_penetration,
                           1e-13 * undamped.max_penetration, r.v * undamped.duration,
                           // The game step's energy budget is measured in joules, to 1e-4 of the
                           // contact's energy: at 1e-165 m/s the energies underflowed and game_dt
                           // came out 1.8 times too long.
                           1e4 * 0.5 * r.m * r.v * r.v};
  if (!std::all_of(std::begin(scales), std::end(scales),
                   [](double x) { return std::isfinite(x) && x > 1e-300; }) ||
      !std::isfinite(d.c_lin) || !(undamped.duration < 1e12))
    unresolvable(r, d.k_lin, "N/m", undamped.duration, undamped.max_penetration);
}

ContactAdvice advise(const ContactRequest& r) {
  validate(r);
  const Designed d = design(r);
  ContactAdvice a;
  a.law = d.law;
  a.k_lin = d.k_lin;
  a.c_lin = d.c_lin;
  a.omega = std::sqrt(d.k_lin / r.m);
  a.zeta = damping_ratio(d.k_lin, d.c_lin, r.m);
  a.frequency_hz = a.omega / (2 * pi);
  a.euler_max_dt =
      a.zeta < 1 ? 2 * a.zeta / a.omega : 2 / (a.omega * (a.zeta + std::sqrt(a.zeta * a.zeta - 1)));
  a.symplectic_max_dt = 2 * (std::sqrt(a.zeta * a.zeta + 1) - a.zeta) / a.omega;
  const SpringContact measured =
      refusing_restitution(r, [&] { return measure_isolated_contact(d.law, r.m, r.v); });
  std::tie(a.game_dt, a.game_energy_error) =
      advised_game_step(d.law, r, a.omega, a.symplectic_max_dt, measured.duration);
  a.ode = to_ode(d.k_lin, d.c_lin, r.engine_step);
  a.mujoco = to_mujoco(d.k_lin, d.c_lin, r.m);
  a.mujoco_direct = to_mujoco_direct(d.k_lin, d.c_lin, r.m);
  a.box2d = to_box2d(d.k_lin, d.c_lin, r.m);
  a.drake = to_drake(d.k_lin, r.m, r.g);
  a.achieved_penetration = measured.max_penetration;
  a.achieved_duration = measured.duration;
  a.achieved_restitution = measured.exit_speed / r.v;
  return a;
}

}  // namespace contact
