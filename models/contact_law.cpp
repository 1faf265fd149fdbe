#include "contact_law.hpp"

#include <fmt/format.h>

#include <numbers>

namespace contact {

double damping_ratio_for_restitution(double e) {
  if (e <= 0.0) return 1.0;
  const double l = std::log(e);
  return -l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
}

KelvinVoigt kelvin_voigt_for_restitution(double k, double m, double e, bool no_pull) {
  return KelvinVoigt{k, 2.0 * damping_ratio_for_restitution(e) * std::sqrt(k * m), no_pull};
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
double stored_energy(const ContactLaw& law, double d) {
  return std::visit([&](const auto& l) { return l.stored_energy(d); }, law);
}
double stiffness(const ContactLaw& law) {
  return std::visit([](const auto& l) { return l.k; }, law);
}

std::string describe(const ContactLaw& law) {
  struct Describe {
    std::string operator()(const Hooke& h) const { return fmt::format("hooke k={:g} N/m", h.k); }
    std::string operator()(const KelvinVoigt& kv) const {
      return fmt::format("kelvin-voigt{} k={:g} N/m c={:g} N s/m", kv.no_pull ? " (no pull)" : "",
                         kv.k, kv.c);
    }
  };
  return std::visit(Describe{}, law);
}

}  // namespace contact
