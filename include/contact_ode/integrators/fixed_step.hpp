#pragma once
// Fixed-step one-step schemes. Each advances y by h in place and returns the number of
// right-hand-side evaluations it made. With q the entries `positions` marks and v the others
// (q' depending on v only):
//   explicit Euler        y+ = y + h f(t, y)                                          order 1
//   semi-implicit Euler   v+ = v + h a(q, v);  q+ = q + h q'(q, v+)                     order 1
//                         (symplectic: the velocity first, the position with it)
//   velocity Verlet       v' = v + h/2 a(q, v);  q+ = q + h q'(q, v');  v+ = v' + h/2 a(q+, v')
//                         order 2 for position-dependent forces (first order in a damping term)
//   RK4                   the classical four-stage Runge–Kutta method                  order 4
// Each full right-hand-side call is counted, also where a scheme uses only half of it.
#include "contact_ode/integrators/ode_system.hpp"

#include <string_view>

namespace contact {

enum class FixedStepScheme { ExplicitEuler, SemiImplicitEuler, VelocityVerlet, Rk4 };

std::string_view to_string(FixedStepScheme s);

// Scratch space, kept by the caller so that a step allocates nothing.
struct FixedStepWork {
  Vector k1, k2, k3, k4, tmp;
  explicit FixedStepWork(Eigen::Index n = 0) : k1(n), k2(n), k3(n), k4(n), tmp(n) {}
};

int fixed_step(FixedStepScheme scheme, const OdeSystem::Rhs& f, const Mask& positions, double t, double h,
               VectorRef y, FixedStepWork& work);

}  // namespace contact
