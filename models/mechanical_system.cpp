#include "contact_ode/models/mechanical_system.hpp"

#include <fmt/format.h>

#include <variant>

namespace contact {

Mask interleaved_positions(std::size_t n) {
  Mask m(static_cast<Eigen::Index>(2 * n));
  for (Eigen::Index k = 0; k < m.size(); ++k) m[k] = k % 2 == 0;
  return m;
}

std::vector<std::string> interleaved_labels(std::size_t n) {
  std::vector<std::string> labels;
  for (std::size_t b = 0; b < n; ++b) {
    labels.push_back(fmt::format("u{}_m", b));
    labels.push_back(fmt::format("v{}_mps", b));
  }
  return labels;
}

void OneLawSystem::switching_and_rates(ConstVectorRef y, std::span<double> s, std::span<double> r) const {
  gaps_and_rates(y, s, r);
  std::visit(
      [&](const auto& law) {
        for (std::size_t i = 0; i < s.size(); ++i) s[i] = law.switching(-s[i], -r[i]);
      },
      law_);
}

}  // namespace contact
