#pragma once
// The rigid-body scenes resolved every way the study compares, by name. Shared by the
// rigid_scenes, energy_drift and rigid_impacts experiments so that all run exactly the same thing.
//   penalty          Kelvin–Voigt springs as an ODE under CVODE BDF (difference-quotient
//                    Jacobian), contact switches root-located
//   game             semi-implicit Euler at fixed dt with the tutorial's projection + impulse
//   game-projection  projection alone
//   event            free flight under CVODE, impulses at located contacts, lowest contact first
//   event-reversed   the same, highest contact first (the sequential rule's order-dependence)
#include "rigid_scene.hpp"
#include "run_result.hpp"

#include <string>
#include <vector>

namespace contact {

struct RigidRunSettings {
  double t_end = 0.05;     // [s]
  double sample_dt = 0.05; // [s]
  double dt = 1e-4;        // game step [s]
  double rtol = 1e-8;      // CVODE tolerances of penalty and event methods
  double atol = 1e-10;
};

std::vector<std::string> rigid_method_names();
// The game methods, whose setting is a fixed step; the others take a tolerance.
bool is_fixed_step(const std::string& rigid_method);
// `s` with the method's setting (game: dt; others: rtol, atol = rtol / 100) set to `value`.
RigidRunSettings with_setting(RigidRunSettings s, const std::string& rigid_method, double value);

// Runs the named method; throws std::invalid_argument for an unknown name.
RunResult run_rigid(const rigid::RigidScene& scene, const std::string& method, const RigidRunSettings& settings);

}  // namespace contact
