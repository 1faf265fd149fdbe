#pragma once
// One isolated contact measured by simulation: a ball of mass m [kg] meets a rigid floor at
// speed V [m/s], no gravity, and the penalty ODE is integrated by CVODE BDF at a tight tolerance
// (rtol 1e-10 by default) with the contact's begin and end located by root finding. Used where no
// closed form exists: the restitution a law really achieves, the advisor's check of its answer.
#include "contact_ode/analysis/references.hpp"
#include "contact_ode/models/contact_law.hpp"

#include <stdexcept>

namespace contact {

// A contact that has not ended within 100 times the undamped contact's duration (a dashpot near
// critical damping, a Hunt–Crossley rule's damping at low restitution).
struct ContactDidNotEnd : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Duration [s], maximum penetration [m] and exit speed [m/s]; the restitution is exit / V.
// Throws ContactDidNotEnd, or std::runtime_error if the solver fails.
SpringContact measure_isolated_contact(const ContactLaw& law, double m, double V, double rtol = 1e-10);

}  // namespace contact
