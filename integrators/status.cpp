#include "contact_ode/integrators/status.hpp"

#include <fmt/format.h>

#include <atomic>

namespace contact {

const char* to_string(Status s) {
  switch (s) {
    case Status::Success:
      return "success";
    case Status::MaxSteps:
      return "max-steps";
    case Status::ConvergenceFailure:
      return "convergence-failure";
    case Status::ErrorTestFailure:
      return "error-test-failure";
    case Status::NonFiniteState:
      return "non-finite-state";
    case Status::Diverged:
      return "diverged";
    case Status::ZenoLimit:
      return "zeno-limit";
    case Status::Unresolved:
      return "unresolved";
    case Status::NoProgress:
      return "no-progress";
    case Status::WorkLimit:
      return "work-limit";
    case Status::Interrupted:
      return "interrupted";
    case Status::SolverError:
      return "solver-error";
  }
  return "unknown";
}

namespace detail {
std::atomic<bool> stop_flag{false};
static_assert(std::atomic<bool>::is_always_lock_free, "request_stop must be safe in a signal handler");
void throw_stopped(double t) { throw stopped_failure(t); }
}  // namespace detail

SolverFailure::SolverFailure(Status status, double t_reached, std::string message)
    : std::runtime_error(fmt::format("{} at t = {:.17g} s: {}", to_string(status), t_reached, message)),
      status_(status),
      t_reached_(t_reached),
      message_(std::move(message)) {}

SolverFailure stopped_failure(double t) {
  return SolverFailure(Status::Interrupted, t, "a stop was requested (SIGINT, SIGTERM or SIGHUP)");
}

}  // namespace contact
