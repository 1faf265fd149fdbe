#pragma once
// What every method returns: samples at requested times, a contact log, apexes, statistics and
// how the run ended. Plain values; analysis/ turns them into metrics.
#include "contact_ode/integrators/solver_stats.hpp"
#include "contact_ode/integrators/status.hpp"
#include "contact_ode/models/linear_algebra.hpp"

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace contact {

struct Sample {
  double t;           // [s]
  Vector y;           // state, labelled by the model's state_labels()
  double energy;      // [J]
  double dissipated;  // energy removed by physical dissipation so far [J] (dashpots, impulses)
};

// One contact, from the moment the bodies start to interact to the moment they stop.
// Velocities are the signed gap rate along the normal (< 0 approaching), so the effective
// restitution is -v_out / v_in. A contact that began without approaching (bodies touching at rest,
// as a resting column starts) has none: NaN, not the infinity or 0/0 of that ratio.
struct ContactRecord {
  std::size_t contact = 0;       // which potential contact of the model
  double t_begin = 0.0;          // [s]
  double t_end = 0.0;            // [s]; NaN while still open at the end of the run
  double max_penetration = 0.0;  // largest overlap seen [m]
  double v_in = 0.0;             // gap rate when the contact began [m/s]
  double v_out = 0.0;            // gap rate when it ended [m/s]; NaN while open
  bool closed() const { return t_end == t_end; }
  double duration() const { return t_end - t_begin; }
  double restitution() const { return v_in < 0 ? -v_out / v_in : std::numeric_limits<double>::quiet_NaN(); }
};

// A local maximum of a contact's gap during free flight after the contact has begun at least once
// (the top of a bounce, so that apex n follows impact n; a rise before the first impact is none).
struct Apex {
  std::size_t contact = 0;
  double t = 0.0;           // [s]
  double gap = 0.0;         // [m]
  double energy = 0.0;      // [J]
  double dissipated = 0.0;  // [J], as in Sample
};

// A gameplay notification of the game loop, delivered in one batch after a physics step.
struct CollisionEvent {
  enum class Kind { Begin, End };
  Kind kind;
  std::size_t contact;  // which potential contact of the model
  long step;            // the step after which it was delivered
  double t;             // that step's end time [s]
};

// A run's records and how it ended. Its energy ledger: E0 = E(t) + dissipated(t) + drift(t). Penalty
// runs integrate the laws' dissipated power as an extra state; impulsive methods add the kinetic
// energy each impulse removes. What is left, the drift, is numerical: integration error, and for
// game methods the energy that projection adds or removes.
struct RunResult {
  std::string method;
  std::vector<std::string> state_labels;
  double energy0 = 0.0;
  std::vector<Sample> samples;
  std::vector<ContactRecord> contacts;
  std::vector<Apex> apexes;
  std::vector<CollisionEvent> notifications;  // game loop only
  SolverStats stats;
  Status status = Status::Success;
  double t_reached = 0.0;
  std::string message;  // the solver's own message when status != Success
  bool ok() const { return status == Status::Success; }
};

}  // namespace contact
