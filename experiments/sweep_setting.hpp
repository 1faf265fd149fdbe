#pragma once
// The one setting a sweep varies, set the same way in every experiment: a fixed step, or a
// relative tolerance with atol = rtol / 100 (the study's states are of order one in SI units:
// metres and metres per second).
#include "integrator.hpp"

namespace contact {

inline constexpr double kAtolPerRtol = 1e-2;

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

}  // namespace contact
