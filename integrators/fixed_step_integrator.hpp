#pragma once
// The fixed-step schemes (fixed_step.hpp) behind the Integrator interface: steps on the grid
// t0 + n dt from the last (re)start, outputs and roots inside a step by re-stepping from its
// start with the shorter step (the scheme's own dense output).
#include "contact_ode/integrators/fixed_step.hpp"
#include "contact_ode/integrators/integrator.hpp"

namespace contact {

std::unique_ptr<Integrator> make_fixed_step(FixedStepScheme scheme, const IntegratorOptions& options,
                                            OdeSystem system, double t0, ConstVectorRef y0);

}  // namespace contact
