#pragma once
// Named parameters with units and defaults, as registries (laws, scenes) describe them, and the
// values a caller gives by name.
#include <map>
#include <string>
#include <vector>

namespace contact {

struct ParameterInfo {
  std::string name;  // e.g. "h0"
  std::string unit;  // e.g. "m"; "" for dimensionless
  double default_value;
  std::string description;
};

using ParameterValues = std::map<std::string, double>;

// The value of every parameter: the given one or the default. Throws std::invalid_argument
// naming a given name that is not a parameter, and the accepted names.
ParameterValues resolve(const std::vector<ParameterInfo>& parameters, const ParameterValues& given,
                        const std::string& owner);

}  // namespace contact
