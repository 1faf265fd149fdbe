#pragma once
// The ball drop resolved every way the study compares, by name. Shared by the ball_drop
// experiment, the tests and the benchmarks so that all three run exactly the same thing.
#include "ball_drop.hpp"
#include "integrator.hpp"
#include "run_recorder.hpp"
#include "run_result.hpp"

#include <string>
#include <vector>

namespace contact {

struct MethodInfo {
  std::string name;
  std::string description;
  bool uses_stiffness;  // whether k (the contact law) affects it
};

// penalty, penalty-dq, game-euler, game-symplectic, game-euler-spring, game-symplectic-spring,
// event-ode, event-exact.
const std::vector<MethodInfo>& ball_drop_methods();
std::vector<std::string> ball_drop_method_names();

// Contact laws by name: hooke, kelvin-voigt, kelvin-voigt-clamped. The Kelvin–Voigt damping is
// tuned to restitution e for mass m (contact_law.hpp); Hooke ignores e (it is undamped).
std::vector<std::string> law_names();
ContactLaw make_law(const std::string& name, double k, double m, double e);

struct BallDropSettings {
  BallDropParams model;
  double t_end = 3.0;       // [s]
  double sample_dt = 0.01;  // [s]
  double dt = 1e-3;         // fixed step of the game methods [s]
  IntegratorOptions integrator;  // penalty, penalty-dq and event-ode (CVODE BDF by default)
  double rest_speed = 1e-7; // event-driven rest threshold [m/s]
  long max_events = 1000000;
  RunLimits limits;
};

// Runs the named method; throws std::invalid_argument for an unknown name.
RunResult run_ball_drop(const std::string& method, const BallDropSettings& settings);

}  // namespace contact
