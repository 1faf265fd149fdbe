#pragma once
// SUNDIALS integrators behind the Integrator interface.
//   cvode-bdf, cvode-adams   CVODE, variable order (BDF 1-5, Adams 1-12), Newton iteration with
//                            the chosen linear solver, root finding
//   arkode-erk               ERKStep, explicit RK of order 4, adaptive or fixed step
//   arkode-dirk              ARKStep, diagonally implicit RK of order 4 (SDIRK)
//   arkode-imex              ARKStep, additive RK of order 4: OdeSystem::implicit_rhs implicit,
//                            the rest explicit
#include "contact_ode/integrators/integrator.hpp"

namespace contact {

std::unique_ptr<Integrator> make_cvode(const IntegratorOptions& options, OdeSystem system, double t0,
                                       ConstVectorRef y0);
std::unique_ptr<Integrator> make_arkode(const IntegratorOptions& options, OdeSystem system, double t0,
                                        ConstVectorRef y0);

}  // namespace contact
