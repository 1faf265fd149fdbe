#pragma once
// The loop shared by every CVODE-based paradigm: integrate through the recorder's output times,
// stop at each root, let the paradigm act on it (log it, switch a contact mode, apply an
// impulse), restart CVODE when the paradigm changed the state or the right-hand side, and end
// the run with the solver's status on failure.
#include "cvode_solver.hpp"
#include "run_recorder.hpp"

#include <functional>

namespace contact {

struct CvodeDrive {
  // Called at every root with the state there (editable) and CVODE's root info. Returns whether
  // CVODE must restart from (t, y).
  std::function<bool(double t, Vector& y, const std::vector<int>& roots_found)> on_roots;
  // Called just before each sample is recorded (optional).
  std::function<void(ConstVectorRef y)> before_sample;
  std::vector<int> root_directions;  // empty: both directions
};

RunResult drive_cvode(OdeSystem system, ConstVectorRef y0, const CvodeOptions& options,
                      RunRecorder& recorder, const CvodeDrive& drive);

}  // namespace contact
