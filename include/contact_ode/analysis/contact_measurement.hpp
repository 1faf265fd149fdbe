#pragma once
// One isolated contact measured by simulation: a ball of mass m [kg] meets a rigid floor at
// speed V [m/s], no gravity, and the penalty ODE is integrated by CVODE BDF at a tight tolerance
// (rtol 1e-10 by default) with the contact's begin and end located by root finding. Used where no
// closed form exists: the restitution a law really achieves, the advisor's check of its answer.
#include "contact_ode/analysis/references.hpp"
#include "contact_ode/models/contact_law.hpp"

namespace contact {

// Duration [s], maximum penetration [m] and exit speed [m/s]; the restitution is exit / V.
// Throws std::runtime_error if the contact does not end within 1000 undamped-Hooke periods' worth
// of time or the solver fails.
SpringContact measure_isolated_contact(const ContactLaw& law, double m, double V, double rtol = 1e-10);

}  // namespace contact
