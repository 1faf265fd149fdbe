#include "contact_ode/models/parameters.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace contact {

ParameterValues resolve(const std::vector<ParameterInfo>& parameters, const ParameterValues& given,
                        const std::string& owner) {
  ParameterValues values;
  for (const auto& p : parameters) values[p.name] = p.default_value;
  for (const auto& [name, value] : given) {
    if (!values.contains(name)) {
      std::vector<std::string> names;
      for (const auto& p : parameters) names.push_back(p.name);
      throw std::invalid_argument(
          fmt::format("{}: parameter '{}' is not one of: {}", owner, name, fmt::join(names, ", ")));
    }
    values[name] = value;
  }
  return values;
}

}  // namespace contact
