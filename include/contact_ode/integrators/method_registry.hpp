#pragma once
// Every method by name, and the one entry point: solve(scene, method, options) -> RunResult.
//
//   scene    a models/ system (Dynamics, with contact geometry and an impulse map where the
//            method needs them);
//   method   a name from method_registry() and the settings a method reads (a fixed step, an
//            ODE integrator, event guards), each method using those that apply to it;
//   options  what every run shares: time span, output spacing, work limits (SolveOptions).
//
// A method family is defined beside its paradigm (penalty.cpp, game_step.cpp, event_driven.cpp)
// as a function returning its entries; method_registry.cpp lists the families, one line each.
// Experiments, tests, benchmarks and the Python module enumerate methods from here only.
#include "contact_ode/integrators/integrator.hpp"
#include "contact_ode/integrators/run_recorder.hpp"
#include "contact_ode/integrators/run_result.hpp"
#include "contact_ode/models/mechanical_system.hpp"

#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace contact {

struct Method {
  std::string name = "penalty";  // a name from method_registry()
  double dt = 1e-3;              // fixed step of the time-stepping methods [s]
  IntegratorOptions integrator;  // the penalty ODE and the event-driven flight (CVODE BDF by default)
  double rest_speed = 1e-7;      // event-driven guards (event_driven.hpp) [m/s]
  double rest_height = -1;       // [m]; < 0: 100 atol for a numerical flight, 0 for the exact one
  double min_event_spacing = 0;  // [s]
  long max_events = 1'000'000;
  int persistence = 1;  // game notifications: frames a pair stays listed
  // Time-stepping solvers (sequential impulses, soft step, XPBD, Moreau–Jean):
  int iterations = 10;     // sequential impulses: Gauss–Seidel sweeps per step (Bullet's default)
  int substeps = 4;        // soft step and XPBD: sub-steps per step (Box2D v3's default)
  bool warm_start = true;  // sequential impulses and soft step: start from the last step's impulses
  double erp = 0.2;        // sequential impulses: the share of an overlap pushed out per step (Bullet, ODE)
  // Sequential impulses: push out by pseudo-velocities, off the real ones (Bullet's split
  // impulses); false: Baumgarte's bias in the velocities, which feeds bounces and shakes stacks.
  bool split_impulse = true;
  // Below this approach speed a contact does not bounce, from it up it does [m/s]; NaN: the
  // method's own default (sequential impulses 0.2 m/s as Bullet, soft step 1 m/s as Box2D v3).
  double restitution_threshold = std::numeric_limits<double>::quiet_NaN();
  double contact_hertz = 30;          // soft step: contact stiffness as a frequency [Hz] (Box2D v3)
  double contact_damping_ratio = 10;  // soft step: its damping ratio (Box2D v3)
  double push_max = 3;                // soft step: fastest push-out of an overlap [m/s] (Box2D v3)
  double theta = 0.5;                 // Moreau–Jean: the theta of its position update (Siconos)
  std::function<void(const std::vector<CollisionEvent>&)> on_notifications;  // game loop, per step
};

struct MethodInfo {
  std::string name;
  std::string description;
  std::string family;     // "penalty", "game", "event-driven": the paradigm
  bool fixed_step;        // its accuracy setting is Method::dt (otherwise the integrator's tolerances)
  bool uses_contact_law;  // whether the scene's penalty law (stiffness, damping) affects it
  std::string needs;      // the capabilities it asks of a scene, in words
  std::function<bool(const Dynamics&)> can_run;
  std::function<RunResult(const Dynamics&, const Method&, const SolveOptions&)> run;
  // The settings it reads, by their Python keywords (Method's fields: "dt" is Method::dt where
  // fixed_step, its integrator's fixed step otherwise); co.solve() warns of any other it is given.
  std::vector<std::string> settings;
  // Forms its integrator's Jacobian by difference quotients whatever Method::integrator says
  // (penalty-dq): it cannot run with a sparse linear solver (KLU needs the analytic Jacobian).
  bool dq_jacobian = false;
  // The sub-steps or solver sweeps each of its fixed steps makes (sequential impulses' iterations,
  // soft step's and XPBD's sub-steps); empty: one. The run's work bound counts steps times these.
  std::function<int(const Method&)> passes;
  // Memory that grows as the square of the state, in dense state-sized matrices: Siconos' LSODAR
  // integrates every state with a dense Jacobian (1); an ODE world's step grows as 0.0039 of one
  // (measured on chains of 5e4 to 4e5 balls: 523 to 3237 doubles per entry, 2.9 to 21 GB).
  double dense_state_matrices = 0;
  // The memory a run holds per state entry besides its samples, in doubles: about 4/3 of the most
  // measured (peak resident memory over state entries, chains and stacks of 5e4 to 1e7 balls); 6/5
  // for the fixed-step loops, measured at 11 to 16.6.
  double working_doubles = 20;
};

// working_doubles of the methods that run an ODE integrator: 24 (rk4) to 94 (a stack under CVODE),
// with KLU's factors and ARKODE's IMEX stages near the top. (16 was taken as a lower bound: a
// 1e7-ball chain under penalty holds 8 GB where that said 2.6, so a run past the limit started.)
inline constexpr double kIntegratorWorkingDoubles = 128;

// The settings of a method that runs an ODE integrator (IntegratorOptions): a fixed step ("dt")
// for an integrator that takes one, tolerances otherwise.
inline const std::vector<std::string> kIntegratorSettings = {
    "integrator", "rtol", "atol", "max_steps", "dt", "linear_solver", "jacobian"};

const std::vector<MethodInfo>& method_registry();
std::vector<std::string> method_names();
// The methods that can run `scene`, in registry order.
std::vector<std::string> methods_for(const Dynamics& scene);
// Throws std::invalid_argument naming the accepted methods.
const MethodInfo& method_info(const std::string& name);

// The memory [bytes] a run of `method` on `scene` over options' span holds at its peak, from above:
// its output samples and working_doubles per state entry. solve() refuses a run past
// options.limits.max_memory_bytes before it starts.
double memory_estimate(const Dynamics& scene, const Method& method, const SolveOptions& options);

// Runs `method` on `scene` over options' span. Throws std::invalid_argument for an unknown
// method, a scene the method cannot run (naming what it lacks) or a setting out of range (the
// time step, span and the time-stepping settings here; the integrator's when it is built); a
// solver failure is a RunResult with its status, the time reached and the solver's message.
RunResult solve(const Dynamics& scene, const Method& method, const SolveOptions& options = {});

// The steps times sub-steps or solver sweeps (MethodInfo::passes) a fixed-step method takes over
// options' span: what RunLimits::max_steps bounds (2^31 sweeps a step, or 1 ns steps over an hour,
// could only fail, after hours). 0 for a method whose steps its error control decides.
double fixed_step_work(const Method& method, const SolveOptions& options);
// Why solve() would end `method` over `options`' span in a work limit at t = 0, if it would. A
// sweep asks it of every run before the first starts, so that its last run is not refused after
// minutes of the others.
std::optional<std::string> work_refusal(const Method& method, const SolveOptions& options);

// The families, each defined beside its paradigm.
std::vector<MethodInfo> penalty_methods();
std::vector<MethodInfo> game_methods();
std::vector<MethodInfo> event_methods();
std::vector<MethodInfo> sequential_impulses_methods();
std::vector<MethodInfo> soft_step_methods();
std::vector<MethodInfo> xpbd_methods();
std::vector<MethodInfo> moreau_jean_methods();
std::vector<MethodInfo> implicit_spring_methods();
// The external engines this build links (integrators/engines), and those it was configured
// without ("" when none is missing).
std::vector<MethodInfo> engine_methods();
std::string engines_missing();

}  // namespace contact
