#include "contact_ode/models/parameters.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace contact {

bool Range::contains(double v) const {
  return std::isfinite(v) && !is_subnormal(v) && (lo_open ? v > lo : v >= lo) &&
         (hi_open ? v < hi : v <= hi) && (!whole || v == std::floor(v));
}

bool is_subnormal(double v) { return v != 0 && std::abs(v) < std::numeric_limits<double>::min(); }

std::string outside(double v) {
  return is_subnormal(v)
             ? fmt::format("below the smallest normal double ({:g})", std::numeric_limits<double>::min())
             : "out of range";
}

std::string Range::to_string() const {
  return fmt::format("{}{}{:g}, {:g}{}", whole ? "whole numbers in " : "", lo_open ? '(' : '[', lo, hi,
                     hi_open ? ')' : ']');
}

void require_in(const std::string& what, double value, const Range& accepted) {
  if (!accepted.contains(value))
    throw std::invalid_argument(
        fmt::format("{} = {} is {}; accepted range {}", what, value, outside(value), accepted.to_string()));
}

ParameterValues resolve(const std::vector<ParameterInfo>& parameters, const ParameterValues& given,
                        const std::string& owner) {
  ParameterValues values;
  for (const auto& p : parameters) values[p.name] = p.default_value;
  for (const auto& [name, value] : given) {
    const auto p = std::find_if(parameters.begin(), parameters.end(),
                                [&name = name](const ParameterInfo& info) { return info.name == name; });
    if (p == parameters.end()) {
      std::vector<std::string> names;
      for (const auto& info : parameters) names.push_back(info.name);
      throw std::invalid_argument(
          fmt::format("{}: parameter '{}' is not one of: {}", owner, name, fmt::join(names, ", ")));
    }
    require_in(fmt::format("{}: parameter '{}'", owner, name), value, p->accepted);
    values[name] = value;
  }
  return values;
}

}  // namespace contact
