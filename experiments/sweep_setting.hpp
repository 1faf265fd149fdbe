#pragma once
// The one setting a sweep varies, set the same way in every experiment: a fixed step, or a
// relative tolerance with atol = rtol / 100 (the study's states are of order one in SI units:
// metres and metres per second).
#include "cli.hpp"
#include "contact_ode/integrators/integrator.hpp"
#include "contact_ode/integrators/method_registry.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace contact {

inline constexpr double kAtolPerRtol = 1e-2;
// The most steps a sweep's run may take (its max_steps): a bound on the work of the finest step.
inline constexpr long kSweepMaxSteps = 10000000;

// The integrators among `names` (the list `given` to --integrators, expanded) that have a step or a
// tolerance to converge in: the exact one is left out of 'all' and refused by name.
inline std::vector<std::string> converging_integrators(std::vector<std::string> names,
                                                       const std::string& given) {
  for (const auto& name : names)
    if (is_exact(integrator_info(name)) && given != "all")
      throw std::invalid_argument(fmt::format(
          "--integrators: value '{}' has no step or tolerance to converge in; accepted: the fixed-step and "
          "adaptive integrators",
          name));
  std::erase_if(names, [](const std::string& name) { return is_exact(integrator_info(name)); });
  return names;
}

// The fixed steps of a sweep: dt_max / 2^j, j = 0 .. halvings. Refused (std::invalid_argument naming
// `option`, the value and the accepted range from `least`) where the finest would take more than
// kSweepMaxSteps steps over `span`: such a run could only fail, after minutes. Where even dt_max
// would, no number of halvings is at fault: the refusal begins with `largest`, the options that set
// dt_max and their values ("--k: value '1e+300' makes the ball's largest step").
inline std::vector<double> halved_steps(const std::string& option, double dt_max, long halvings, long least,
                                        double span, const std::string& largest) {
  const double most = std::floor(std::log2(static_cast<double>(kSweepMaxSteps) * dt_max / span));
  const int h = static_cast<int>(std::min(halvings, 4096L));
  const auto most_steps = static_cast<double>(kSweepMaxSteps);
  if (most < static_cast<double>(least)) {
    const double fewest = std::ldexp(span / most_steps, static_cast<int>(least));
    const std::string halved = least == 0   ? ""
                               : least == 1 ? " halved once, the sweep's least"
                                            : fmt::format(" halved {} times, the sweep's least", least);
    throw std::invalid_argument(
        fmt::format("{} {:.3g} s, {:.3g} steps over {:g} s{} (a run takes at most {:g}); accepted: a largest "
                    "step >= {:g} s",
                    largest, dt_max, std::ldexp(span / dt_max, static_cast<int>(least)), span, halved,
                    most_steps, cli::rounded_up(fewest)));
  }
  if (static_cast<double>(halvings) > most)
    throw std::invalid_argument(
        fmt::format("{}: value '{}' makes the finest step {:.3g} s, {:.3g} steps over {:g} s (a run takes at "
                    "most {:g}); accepted [{}, {:g}]",
                    option, halvings, std::ldexp(dt_max, -h), std::ldexp(span / dt_max, h), span, most_steps,
                    least, most));
  std::vector<double> steps;
  for (int j = 0; j <= h; ++j) steps.push_back(std::ldexp(dt_max, -j));
  return steps;
}

// convergence_dt's and method_orders' steps: --dt-max halved --halvings times, over (and below)
// --t-final.
inline std::vector<double> halved_dt_max(double dt_max, long halvings, double t_final) {
  if (dt_max >= t_final)
    throw std::invalid_argument(fmt::format(
        "--dt-max: value '{}' is not below --t-final = {}; accepted range (0, t-final)", dt_max, t_final));
  return halved_steps(
      "--halvings", dt_max, halvings, 1, t_final,
      fmt::format("--dt-max, --t-final: values '{}', '{}' make the largest step", dt_max, t_final));
}

// Tolerances from `loosest` down to `tightest` (within rounding), a decade apart.
inline std::vector<double> decades(double loosest, double tightest) {
  std::vector<double> out;
  for (double tol = loosest; tol >= tightest * (1 - 1e-9); tol /= 10) out.push_back(tol);
  return out;
}

// `o` with dt = value (fixed_step), or with rtol = value and atol = value * kAtolPerRtol.
inline IntegratorOptions with_setting(IntegratorOptions o, bool fixed_step, double value) {
  if (fixed_step) {
    o.dt = value;
  } else {
    o.rtol = value;
    o.atol = value * kAtolPerRtol;
  }
  return o;
}

// `m` with its accuracy setting at `value`: dt for a fixed-step method, the tolerances otherwise.
inline Method with_setting(Method m, double value) {
  if (method_info(m.name).fixed_step)
    m.dt = value;
  else
    m.integrator = with_setting(m.integrator, false, value);
  return m;
}

// The cost sweeps' (contact_cost, resting_cost) checks and runs: a k range that is one, the
// adaptive integrators among --integrators (one without error control refused by name), and the
// penalty method under `integrator` at rtol (atol = rtol * kAtolPerRtol) with a sweep's step bound.
inline void require_k_range(double k_min, double k_max) {
  if (!(k_max >= k_min))
    throw std::invalid_argument(
        fmt::format("--k-max: value '{}' is below --k-min = {}; accepted range [k-min, inf)", k_max, k_min));
}

inline std::vector<std::string> adaptive_integrators(const std::string& given) {
  const auto chosen = cli::chosen(given, integrator_names());
  for (const auto& name : chosen)
    if (!integrator_info(name).adaptive)
      throw std::invalid_argument(fmt::format(
          "--integrators: value '{}' has no error control; accepted: the adaptive integrators", name));
  return chosen;
}

inline Method penalty_under(const std::string& integrator, double rtol) {
  Method penalty{.name = "penalty"};
  penalty.integrator = with_setting(penalty.integrator, false, rtol);
  penalty.integrator.method = integrator;
  penalty.integrator.max_steps = kSweepMaxSteps;
  return penalty;
}

// The methods the rigid-body experiments compare (rigid_scenes, energy_drift, rigid_impacts): the
// penalty ODE, the game loop with projection + impulse and with projection alone, and
// event-driven impulses in both sequential orders.
inline const std::vector<std::string> kRigidMethods = {
    "penalty", "game-symplectic", "game-symplectic-projection", "event-ode", "event-ode-reversed"};
// The game step and the tolerances the rigid experiments run at unless they sweep them.
inline Method rigid_method(const std::string& name) {
  Method m{.name = name, .dt = 1e-4};
  m.integrator.rtol = 1e-8;
  m.integrator.atol = 1e-10;
  return m;
}

}  // namespace contact
