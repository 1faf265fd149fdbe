#pragma once
// exact-linear: the exact solution of an ODE whose right-hand side is affine in the state between
// two restarts, y' = A y + b (a penalty scene with linear contact laws, its switches located and
// restarted at), with quadrature entries (the energy ledger) quadratic forms of the rest. No
// tolerance: each step is the Taylor series of the exact solution, summed until its terms fall
// below rounding, and the step's dense output is that polynomial, on which roots are located.
//   At every restart it forms A from the Jacobian and checks what it relies on, refusing (a solver
// error naming the reason) a system that is not affine (a nonlinear law such as Hertz's), depends
// on time, or changes between restarts (switches not located); and it forms each quadrature's
// quadratic form by polarisation, m (m + 3) / 2 right-hand sides for m other entries (at most 64).
// A restart into a mode met before (the same A, and f as that segment predicts) reuses its forms.
//   Steps: a step of length h sums the terms (h A)^j f / (j + 1)!; it is limited to h rho <= 1,
// rho A's spectral radius (the segment's fastest frequency: a contact's omega), which keeps the
// series short and a root function from crossing zero twice unseen. A free flight, whose A is
// nilpotent, is one step to the next output or root, however long.
#include "contact_ode/integrators/integrator.hpp"

namespace contact {

std::unique_ptr<Integrator> make_exact_linear(const IntegratorOptions& options, OdeSystem system, double t0,
                                              ConstVectorRef y0);

}  // namespace contact
