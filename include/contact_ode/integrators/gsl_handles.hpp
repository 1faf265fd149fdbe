#pragma once
// Owners for every GSL object the project creates, and the switch that turns GSL's default
// error handler (which aborts the process) into plain return codes.
#include <gsl/gsl_odeiv2.h>
#include <gsl/gsl_roots.h>

#include <memory>

namespace contact::gsl {

struct RootSolverFree {
  void operator()(gsl_root_fsolver* s) const { gsl_root_fsolver_free(s); }
};
struct DriverFree {
  void operator()(gsl_odeiv2_driver* d) const { gsl_odeiv2_driver_free(d); }
};
struct StepFree {
  void operator()(gsl_odeiv2_step* s) const { gsl_odeiv2_step_free(s); }
};

using RootSolver = std::unique_ptr<gsl_root_fsolver, RootSolverFree>;
using Driver = std::unique_ptr<gsl_odeiv2_driver, DriverFree>;
using Step = std::unique_ptr<gsl_odeiv2_step, StepFree>;

// Idempotent and thread-safe; every user of GSL calls it before its first GSL call.
void report_errors_by_return_code();

}  // namespace contact::gsl
