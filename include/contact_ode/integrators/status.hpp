#pragma once
// How a run ended, and the typed error that carries a solver failure out of an integrator.
#include <stdexcept>
#include <string>

namespace contact {

enum class Status {
  Success,             // reached the final time
  MaxSteps,            // the solver's step budget ran out (CV_TOO_MUCH_WORK)
  ConvergenceFailure,  // Newton iteration failed repeatedly (CV_CONV_FAILURE)
  ErrorTestFailure,    // error test failed repeatedly or the step fell below the minimum
  NonFiniteState,      // the state or right-hand side became NaN or infinite
  ZenoLimit,           // event-driven: more impacts than allowed before reaching rest
  Unresolved,          // event-driven: an impact below what the flight's tolerance resolves
  NoProgress,          // the solver kept returning at the same time without advancing
  WorkLimit,           // the run's bound on steps, samples or records (RunLimits) was reached
  SolverError,         // any other solver error
};

const char* to_string(Status s);

// Thrown by integrators when they cannot go on; carries where they stopped and why.
class SolverFailure : public std::runtime_error {
 public:
  SolverFailure(Status status, double t_reached, std::string message);
  Status status() const { return status_; }
  double t_reached() const { return t_reached_; }
  const std::string& solver_message() const { return message_; }

 private:
  Status status_;
  double t_reached_;
  std::string message_;
};

}  // namespace contact
