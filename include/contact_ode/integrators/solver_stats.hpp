#pragma once
// Work counters every method reports, so that methods can be compared on the same footing.
// Fields a method does not have stay 0. `+=` adds runs or restarted segments together
// (CVodeReInit resets CVODE's own counters, so a restarted run sums them here).
#include <string>

namespace contact {

struct SolverStats {
  long steps = 0;            // accepted steps (fixed-step: steps taken; closed form: flight legs)
  long failed_steps = 0;     // rejected steps: error-test plus nonlinear-convergence failures
  long rhs_evals = 0;        // right-hand-side evaluations, including those of a
                             // difference-quotient Jacobian, J v or band preconditioner
  long jac_evals = 0;        // Jacobian evaluations (analytic or difference quotient; GMRES:
                             // the analytic ones its J v products use, one a Newton iteration)
  long newton_iters = 0;     // nonlinear (Newton) iterations
  long linear_setups = 0;    // linear-solver setups (factorisations)
  long linear_iters = 0;     // iterations of an iterative linear solver (GMRES)
  long root_evals = 0;       // root (switching-function) evaluations
  long events = 0;           // roots located and acted on: contact switches, impacts, apexes
  long restarts = 0;         // re-initialisations after an event
  double wall_time_s = 0.0;  // wall-clock time of the run [s]
  // CPU time of building an engine's own world from the scene before its run [s]: paid once per
  // world, and in neither wall_time_s nor a rate per simulated second (MuJoCo compiles an XML
  // model: 0.4 to 1.3 ms in the study's run, its 50 steps of the head-on pair 0.12 ms). The project's
  // methods build no world: 0, their setup inside the run.
  double setup_cpu_s = 0.0;

  SolverStats& operator+=(const SolverStats& o) {
    steps += o.steps;
    failed_steps += o.failed_steps;
    rhs_evals += o.rhs_evals;
    jac_evals += o.jac_evals;
    newton_iters += o.newton_iters;
    linear_setups += o.linear_setups;
    linear_iters += o.linear_iters;
    root_evals += o.root_evals;
    events += o.events;
    restarts += o.restarts;
    wall_time_s += o.wall_time_s;
    setup_cpu_s += o.setup_cpu_s;
    return *this;
  }
};

}  // namespace contact
