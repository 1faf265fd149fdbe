#pragma once
// The one setting a sweep varies, set the same way in every experiment: a fixed step, or a
// relative tolerance with atol = rtol / 100 (the study's states are of order one in SI units:
// metres and metres per second).
#include "contact_ode/integrators/integrator.hpp"
#include "contact_ode/integrators/method_registry.hpp"

#include <string>
#include <vector>

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

// `m` with its accuracy setting at `value`: dt for a fixed-step method, the tolerances otherwise.
inline Method with_setting(Method m, double value) {
  if (method_info(m.name).fixed_step)
    m.dt = value;
  else
    m.integrator = with_setting(m.integrator, false, value);
  return m;
}

// The methods the rigid-body experiments compare (rigid_scenes, energy_drift, rigid_impacts): the
// penalty ODE, the game loop with projection + impulse and with projection alone, and
// event-driven impulses in both sequential orders.
inline const std::vector<std::string> kRigidMethods = {
    "penalty", "game-symplectic", "game-symplectic-projection", "event-ode", "event-ode-reversed"};
// The game step and the tolerances the rigid experiments run at unless they sweep them.
inline Method rigid_method(const std::string& name) {
  Method m{.name = name, .dt = 1e-4};
  m.integrator.rtol = 1e-8;
  m.integrator.atol = 1e-10;
  return m;
}

}  // namespace contact
