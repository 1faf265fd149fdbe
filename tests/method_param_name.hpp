#pragma once
// A test parameterised by a method's name ("gsl-rk8pd") is named after it with '_' for '-':
// GoogleTest takes only letters, digits and underscores in a name.
#include <algorithm>
#include <string>

struct MethodParamName {
  template <class ParamInfo>
  std::string operator()(const ParamInfo& info) const {
    std::string name = info.param;
    std::replace(name.begin(), name.end(), '-', '_');
    return name;
  }
};
