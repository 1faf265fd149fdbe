#pragma once
// Ctrl-C in the Python module: a solve in progress ends within a step, and Python gets the signal.
#include "contact_ode/integrators/status.hpp"

#include <pybind11/pybind11.h>

#include <csignal>

namespace contact::python {

namespace py = pybind11;

// Ctrl-C during a solve. Python's own SIGINT handler only marks the signal, and the interpreter
// looks at the mark when solve() returns: a 1000-ball chain went on for its whole solve. While a
// solve runs on Python's main thread (where Python takes its signals) SIGINT requests the
// library's stop instead, which ends the run within a step; afterwards Python's handler is back
// and the signal is handed to it, so that Python raises KeyboardInterrupt (or runs the handler the
// caller set). A SIGINT that Python ignores (SIG_IGN) or leaves to the system is not intercepted.
class InterruptibleSolve {
 public:
  InterruptibleSolve() {
    const auto threading = py::module_::import("threading");
    if (!threading.attr("current_thread")().is(threading.attr("main_thread")())) return;
    struct sigaction ours {};
    ours.sa_handler = [](int) { request_stop(); };
    sigemptyset(&ours.sa_mask);
    if (sigaction(SIGINT, &ours, &python_) != 0) return;
    installed_ = true;
    if (python_.sa_handler == SIG_IGN || python_.sa_handler == SIG_DFL) release();
  }
  InterruptibleSolve(const InterruptibleSolve&) = delete;
  InterruptibleSolve& operator=(const InterruptibleSolve&) = delete;
  ~InterruptibleSolve() { release(); }

  // Python's handler back; a SIGINT taken meanwhile is handed to it. Throws what it raises.
  void hand_over() {
    if (release() && PyErr_CheckSignals() != 0) throw py::error_already_set();
  }

 private:
  // Python's handler back, and a SIGINT taken meanwhile marked for it (also where solve() threw);
  // whether one was.
  bool release() {
    if (!installed_) return false;
    sigaction(SIGINT, &python_, nullptr);
    installed_ = false;
    const bool taken = stop_requested();
    clear_stop_request();
    return taken && PyErr_SetInterruptEx(SIGINT) == 0;
  }
  struct sigaction python_ {};
  bool installed_ = false;
};

}  // namespace contact::python
