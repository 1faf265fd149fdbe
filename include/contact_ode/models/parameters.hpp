#pragma once
// Named parameters with units, defaults and accepted ranges, as registries (laws, scenes) describe
// them, and the values a caller gives by name.
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace contact {

// The values a parameter accepts: finite, between lo and hi (an open end excludes its bound), and
// whole numbers only where `whole` (a count). Never a value below the smallest normal double
// (1e-310 kg, 1e-310 s): the command line refuses one, and where it reached a solver it ended in
// NaN or a failure that did not name it.
struct Range {
  double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
  bool lo_open = true, hi_open = true, whole = false;
  bool contains(double v) const;
  std::string to_string() const;  // "(0, inf)", "[0, 1]", "whole numbers in [2, 1e+09)"
};
inline constexpr Range kAnyFinite{};
inline constexpr Range kPositive{.lo = 0};
inline constexpr Range kNonNegative{.lo = 0, .lo_open = false};
inline constexpr Range kUnitInterval{.lo = 0, .hi = 1, .lo_open = false, .hi_open = false};

// A value below the smallest normal double, 0 apart (Range refuses one).
bool is_subnormal(double v);
// Why a value is outside a range: "out of range", or "below the smallest normal double (2.22507e-308)".
std::string outside(double v);

// Throws std::invalid_argument "<what> = <value> is <outside(value)>; accepted range <range>"
// unless `accepted` contains the value.
void require_in(const std::string& what, double value, const Range& accepted);

struct ParameterInfo {
  std::string name;  // e.g. "h0"
  std::string unit;  // e.g. "m"; "" for dimensionless
  double default_value;
  std::string description;
  Range accepted = kAnyFinite;
};

using ParameterValues = std::map<std::string, double>;

// The value of every parameter: the given one or the default. Throws std::invalid_argument
// naming a given name that is not a parameter (and the accepted names), or a value outside its
// parameter's range (and the range).
ParameterValues resolve(const std::vector<ParameterInfo>& parameters, const ParameterValues& given,
                        const std::string& owner);

}  // namespace contact
