#include "contact_ode/models/law_registry.hpp"

#include "contact_ode/models/registry.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace contact {

namespace {

const ParameterInfo kStiffness{"k", "N/m", 1e5, "stiffness", kPositive};
const ParameterInfo kPowerStiffness{"k", "N/m^n", 1e9, "stiffness K of K delta^n", kPositive};
const ParameterInfo kMass{"m", "kg", 1.0, "effective mass the damping is tuned for", kPositive};
const ParameterInfo kRestitution{"e", "", 0.8, "target restitution", kUnitInterval};
const ParameterInfo kSpeed{"v", "m/s", 1.0, "impact speed the damping is tuned at", kPositive};
// A Hunt-Crossley contact stops dead only in the limit chi V -> inf (hunt_crossley_chi_v(0) is inf;
// the Flores and Gonthier rules divide by e), so e = 0 makes no such law.
const ParameterInfo kHuntCrossleyRestitution{
    "e", "", 0.8, "target restitution", {.lo = 0, .hi = 1, .hi_open = false}};

LawInfo hunt_crossley(const std::string& name, std::string description, double n) {
  return {name,
          std::move(description),
          n,
          true,
          false,
          "restitution exact in chi V (hunt_crossley_restitution); undamped penetration and duration "
          "(power_law_contact)",
          {kPowerStiffness, kHuntCrossleyRestitution, kSpeed},
          [n, name](const LawSpec& s) {
            // An infinite chi made every run fail at the first touch, its right-hand side not finite
            // (ball_drop --law hertz --e 0: 'non-finite-state ... CV_FIRST_RHSFUNC_ERR').
            const double chi = damping_factor(s.rule, s.e, s.v);
            if (!std::isfinite(chi))
              throw std::invalid_argument(
                  s.e == 0
                      ? fmt::format("--e: value '0' asks the {} law for infinite damping: a Hunt-Crossley "
                                    "contact stops dead only as its damping grows without bound; accepted "
                                    "range {}",
                                    name, kHuntCrossleyRestitution.accepted.to_string())
                      : fmt::format("the {} law tuned to e = {:g} at an impact speed of {:g} m/s has a "
                                    "damping factor beyond the doubles (chi = {:g} s/m); a faster impact "
                                    "speed gives a finite one",
                                    name, s.e, s.v, chi));
            return ContactLaw{HuntCrossley{s.k, n, chi}};
          }};
}

}  // namespace

const std::vector<LawInfo>& law_registry() {
  static const std::vector<LawInfo> laws = {
      {"hooke",
       "the seed's spring, F = k delta (undamped)",
       1.0,
       false,
       false,
       "penetration and duration, with and without gravity (hooke_contact)",
       {kStiffness},
       [](const LawSpec& s) { return ContactLaw{Hooke{s.k}}; }},
      {"kelvin-voigt",
       "spring and dashpot, F = k delta + c delta', c tuned to e (pulls near the end)",
       1.0,
       true,
       true,
       "penetration, duration and exit speed, with and without gravity (kelvin_voigt_contact)",
       {kStiffness, kMass, kRestitution},
       [](const LawSpec& s) { return ContactLaw{kelvin_voigt_for_restitution(s.k, s.m, s.e, false)}; }},
      {"kelvin-voigt-clamped",
       "as kelvin-voigt, clamped to F >= 0 (lets go while overlapping)",
       1.0,
       true,
       false,
       "penetration, duration and exit speed, with and without gravity (clamped_kelvin_voigt_contact)",
       {kStiffness, kMass, kRestitution},
       [](const LawSpec& s) { return ContactLaw{kelvin_voigt_for_restitution(s.k, s.m, s.e, true)}; }},
      hunt_crossley("hertz",
                    "Hunt-Crossley, n = 3/2: F = K delta^1.5 (1 + chi delta'), chi by the damping rule", 1.5),
      hunt_crossley("hunt-crossley-linear", "Hunt-Crossley, n = 1: F = K delta (1 + chi delta')", 1.0),
  };
  return laws;
}

std::vector<std::string> law_names() { return names_of(law_registry()); }

const LawInfo& law_info(const std::string& name) { return find_named(law_registry(), name, "--law"); }

ContactLaw make_law(const std::string& name, const LawSpec& spec) { return law_info(name).make(spec); }

}  // namespace contact
