#pragma once
// How a run ended, and the typed error that carries a solver failure out of an integrator.
#include <atomic>
#include <stdexcept>
#include <string>

namespace contact {

enum class Status {
  Success,             // reached the final time
  MaxSteps,            // the solver's step budget ran out (CV_TOO_MUCH_WORK)
  ConvergenceFailure,  // Newton iteration failed repeatedly (CV_CONV_FAILURE)
  ErrorTestFailure,    // error test failed repeatedly or the step fell below the minimum
  NonFiniteState,      // the state or right-hand side became NaN or infinite
  Diverged,            // the state or energy grew past RunLimits::max_state_growth or max_energy_gain
  ZenoLimit,           // event-driven: more impacts than allowed before reaching rest
  Unresolved,          // an impact below what the flight's tolerance resolves (event-driven), or a
                       // penalty contact too short or shallow for its located switch
  NoProgress,          // the solver kept returning at the same time without advancing
  WorkLimit,           // the run's bound on steps, samples or records (RunLimits) was reached
  Interrupted,         // a stop was requested (request_stop: a stop signal)
  SolverError,         // any other solver error
};

const char* to_string(Status s);

// A request to end every run in the process, made by a program's stop signal handler (a
// lock-free atomic store: safe there). The integrators look at it at every step or right-hand side
// and end the run as Status::Interrupted, so that a single long solve stops within a step.
// Inline: it is looked at once per step of loops that take 100 ns per step.
namespace detail {
extern std::atomic<bool> stop_flag;
[[noreturn]] void throw_stopped(double t);
}  // namespace detail
inline void request_stop() noexcept { detail::stop_flag.store(true, std::memory_order_relaxed); }
inline bool stop_requested() noexcept { return detail::stop_flag.load(std::memory_order_relaxed); }
// For a process that outlives the interrupted run and goes on (the Python module, after it has
// handed the interrupt to Python); a program's interrupt is its end.
inline void clear_stop_request() noexcept { detail::stop_flag.store(false, std::memory_order_relaxed); }
// Throws SolverFailure(Status::Interrupted, t, ...) when a stop was requested.
inline void throw_if_stop_requested(double t) {
  if (stop_requested()) [[unlikely]]
    detail::throw_stopped(t);
}

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

// The failure of a run ended by a stop request at time t, whichever integrator ran it.
SolverFailure stopped_failure(double t);

}  // namespace contact
