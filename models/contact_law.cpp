#include "contact_ode/models/contact_law.hpp"

#include "contact_ode/models/parameters.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <numbers>

namespace contact {

double damping_ratio_for_restitution(double e) {
  require_in("damping_ratio_for_restitution: e", e, kUnitInterval);
  if (e <= 0.0) return 1.0;
  // |ln e|, not -ln e: at e = 1 that is -0, and an undamped law was printed with c=-0.
  const double l = std::abs(std::log(e));
  return l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
}

KelvinVoigt kelvin_voigt_for_restitution(double k, double m, double e, bool no_pull) {
  // sqrt(k) sqrt(m), not sqrt(k m): k m underflowed for a light body on a soft spring (1e-200 kg
  // on 1e-195 N/m), and the dashpot tuned to e came out 0: the ball bounced at e = 1.
  return KelvinVoigt{k, 2.0 * damping_ratio_for_restitution(e) * std::sqrt(k) * std::sqrt(m), no_pull};
}

LinearLaw linear_law(const ContactLaw& law) {
  if (const auto* h = std::get_if<Hooke>(&law)) return {h->k, 0.0};
  if (const auto* kv = std::get_if<KelvinVoigt>(&law)) return {kv->k, kv->c};
  const auto& hc = std::get<HuntCrossley>(law);
  if (hc.n == 1.0 && hc.chi == 0.0) return {hc.k, 0.0};
  return {std::nan(""), std::nan("")};
}

double force(const ContactLaw& law, double d, double dd) {
  return std::visit([&](const auto& l) { return l.force(d, dd); }, law);
}
double dforce_ddelta(const ContactLaw& law, double d, double dd) {
  return std::visit([&](const auto& l) { return l.dforce_ddelta(d, dd); }, law);
}
double dforce_drate(const ContactLaw& law, double d, double dd) {
  return std::visit([&](const auto& l) { return l.dforce_drate(d, dd); }, law);
}
double switching(const ContactLaw& law, double d, double dd) {
  return std::visit([&](const auto& l) { return l.switching(d, dd); }, law);
}
bool releases_while_overlapping(const ContactLaw& law) {
  return std::visit([](const auto& l) { return l.releases_while_overlapping(); }, law);
}
double stored_energy(const ContactLaw& law, double d) {
  return std::visit([&](const auto& l) { return l.stored_energy(d); }, law);
}
double dissipated_power(const ContactLaw& law, double d, double dd) {
  return std::visit([&](const auto& l) { return l.dissipated_power(d, dd); }, law);
}
double stiffness(const ContactLaw& law) {
  return std::visit([](const auto& l) { return l.k; }, law);
}

double exponent(const ContactLaw& law) {
  const auto* hc = std::get_if<HuntCrossley>(&law);
  return hc ? hc->n : 1.0;
}

std::string describe(const ContactLaw& law) {
  struct Describe {
    std::string operator()(const Hooke& h) const { return fmt::format("hooke k={:g} N/m", h.k); }
    std::string operator()(const HuntCrossley& h) const {
      return fmt::format("hunt-crossley K={:g} N/m^{:g} n={:g} chi={:g} s/m", h.k, h.n, h.n, h.chi);
    }
    std::string operator()(const KelvinVoigt& kv) const {
      return fmt::format("kelvin-voigt{} k={:g} N/m c={:g} N s/m", kv.no_pull ? " (no pull)" : "", kv.k,
                         kv.c);
    }
  };
  return std::visit(Describe{}, law);
}

double hunt_crossley_restitution(double a) {
  require_in("hunt_crossley_restitution: chi V", a, kNonNegative);
  // Small a: the relation fixes 1 - e only through its a^3 terms, below the rounding of its a^2
  // ones (e's error ~ eps / a), so the series e = 1 - 2a/3 + 4a^2/9 - 44a^3/135 + O(a^4) instead:
  // both errors are ~2e-13 at a = 1e-3.
  if (a < 1e-3) return 1.0 + a * (-2.0 / 3.0 + a * (4.0 / 9.0 - a * 44.0 / 135.0));
  // In L = ln(1 - a e) the relation a e + ln(1 - a e) + a - ln(1 + a) = 0 reads
  // h(L) = c - (exp(L) - 1 - L) = 0 with c = a - ln(1 + a) > 0: h rises from -inf to h(0) = c,
  // one root in (-(2 + c), 0). Solved in L, not e: past a ~ 40 the root's 1 - a e is below
  // 1e-15 (about (1 + a) exp(-1 - a)), which e cannot resolve; e = -expm1(L) / a keeps it. (expm1:
  // at small a the root L ~ -a, and 1 - exp(L) would lose it to the rounding of 1.)
  const double c = a - std::log1p(a);
  auto h = [c](double L) { return c - (std::expm1(L) - L); };
  double lo = -(2.0 + c), hi = 0.0;
  for (int i = 0; i < 2200; ++i) {  // to adjacent doubles: at most ~1100 halvings
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (h(mid) < 0 ? lo : hi) = mid;
  }
  return -std::expm1(0.5 * (lo + hi)) / a;
}

double hunt_crossley_chi_v(double e) {
  require_in("hunt_crossley_chi_v: e", e, kUnitInterval);
  if (e >= 1.0) return 0.0;
  if (e <= 0.0) return std::numeric_limits<double>::infinity();
  // hunt_crossley_restitution falls from 1 at a = 0, and below 1 / a everywhere (1 - a e > 0), so
  // at a = 1 / e it is below e: the root lies in (0, 1 / e). Bisected to adjacent doubles; the
  // forward relation's own accuracy (~1e-13) then sets a's.
  double lo = 0.0, hi = 1.0 / e;
  for (int i = 0; i < 2200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (hunt_crossley_restitution(mid) > e ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double damping_factor(DampingRule rule, double e, double v) {
  switch (rule) {
    case DampingRule::HuntCrossley:
      return 3.0 * (1.0 - e) / (2.0 * v);
    case DampingRule::LankaraniNikravesh:
      return 3.0 * (1.0 - e * e) / (4.0 * v);
    case DampingRule::Flores:
      return 8.0 * (1.0 - e) / (5.0 * e * v);
    case DampingRule::Gonthier:
      return (1.0 - e * e) / (e * v);
    case DampingRule::Exact:
      return hunt_crossley_chi_v(e) / v;
  }
  return 0.0;
}

std::vector<std::string> damping_rule_names() {
  std::vector<std::string> names;
  for (const DampingRule rule : kDampingRules) names.emplace_back(to_string(rule));
  return names;
}

DampingRule parse_damping_rule(const std::string& name) {
  for (const DampingRule rule : kDampingRules)
    if (to_string(rule) == name) return rule;
  throw std::invalid_argument(
      fmt::format("--rule: value '{}' is not one of: {}", name, fmt::join(damping_rule_names(), ", ")));
}

std::string_view to_string(DampingRule rule) {
  switch (rule) {
    case DampingRule::HuntCrossley:
      return "hunt-crossley";
    case DampingRule::LankaraniNikravesh:
      return "lankarani-nikravesh";
    case DampingRule::Flores:
      return "flores";
    case DampingRule::Gonthier:
      return "gonthier";
    case DampingRule::Exact:
      return "exact";
  }
  return "?";
}

double effective_modulus(double E1, double nu1, double E2, double nu2) {
  const double c2 = std::isinf(E2) ? 0.0 : (1.0 - nu2 * nu2) / E2;
  return 1.0 / ((1.0 - nu1 * nu1) / E1 + c2);
}

double hertz_stiffness(double radius, double E_eff) { return 4.0 / 3.0 * E_eff * std::sqrt(radius); }

}  // namespace contact
