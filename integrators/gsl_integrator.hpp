#pragma once
// GSL odeiv2 behind the Integrator interface, an independent second opinion on SUNDIALS:
//   gsl-rk8pd   explicit embedded Runge–Kutta Prince–Dormand (8, 9)           order 8
//   gsl-rkf45   explicit embedded Runge–Kutta–Fehlberg (4, 5)                 order 5
//               (GSL advances with the fifth-order solution: measured, test_integrators)
//   gsl-msbdf   variable-order BDF (1-5), Newton with the Jacobian            variable
//   gsl-bsimp   implicit Bulirsch–Stoer (Bader–Deuflhard), with the Jacobian  variable
// Error control is GSL's standard one on y with the options' tolerances; a positive dt fixes
// the step instead. Outputs and roots inside a step come from re-stepping from its start with
// a separate stepper (one-step methods) or, for the multistep msbdf, from the cubic Hermite
// interpolant of the step's end values and slopes (error O(h^4) on the step).
#include "contact_ode/integrators/integrator.hpp"

namespace contact {

std::unique_ptr<Integrator> make_gsl(const IntegratorOptions& options, OdeSystem system, double t0,
                                     ConstVectorRef y0);

}  // namespace contact
