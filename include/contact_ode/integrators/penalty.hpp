#pragma once
// Penalty resolution: contacts are springs (the model's contact law), and the whole system is
// one stiff ODE integrated by any Integrator (CVODE BDF by default).
//
// Each contact has two root functions: its switching function (the law pushes while > 0) and
// its gap rate. With `locate_switches`, the run holds every contact in a fixed mode (free or
// penalty) between roots, stops exactly where a switching function crosses zero, flips that
// contact's mode and restarts the integrator: no step straddles the kink of the force, and the
// right-hand side the integrator sees is smooth on every segment. Without it the mode is read from the
// state at each call (the kink is stepped over) and the roots are only logged, which is what
// convergence studies compare against. Gap-rate roots give the apexes (free flight) and the
// maximum penetration (in contact) exactly.
#include "contact_ode/integrators/integrator.hpp"
#include "contact_ode/integrators/run_recorder.hpp"
#include "contact_ode/integrators/run_result.hpp"
#include "contact_ode/models/mechanical_system.hpp"

namespace contact {

struct PenaltyOptions {
  IntegratorOptions integrator;
  bool locate_switches = true;
};

// Any scene: its contact geometry, if it has one, gives the springs (none: a plain ODE).
RunResult run_penalty(const Dynamics& model, const PenaltyOptions& options, const SolveOptions& span = {});

}  // namespace contact
