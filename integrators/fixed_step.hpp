#pragma once
// Fixed-step one-step schemes, as games use them. Each advances y by dt in place and returns
// the number of right-hand-side evaluations it made.
//   explicit Euler        y+ = y + dt f(t, y)                                  (order 1)
//   semi-implicit Euler   v+ = v + dt a(q, v);  q+ = q + dt q'(q, v+)           (order 1,
//                         symplectic: the velocity is updated first and the position uses it)
#include "ode_system.hpp"

#include <string_view>

namespace contact {

enum class FixedStepScheme { ExplicitEuler, SemiImplicitEuler };

std::string_view to_string(FixedStepScheme s);

// `work` is scratch space of the system's size, kept by the caller so a step allocates nothing.
int fixed_step(FixedStepScheme scheme, const OdeSystem::Rhs& f, std::size_t position_size,
               double t, double dt, VectorRef y, Vector& work);

}  // namespace contact
