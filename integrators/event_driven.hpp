#pragma once
// Event-driven impulse resolution: bodies fly freely; the time a contact's gap closes is located
// by root finding (approaching zeros only); Newton's law v+ = -e v- is applied there through the
// model's impulse map; the flight restarts.
//
// Zeno: with e < 1 a bouncing contact accumulates infinitely many impacts before a finite time
// (t_inf = t0 (1+e)/(1-e) for the ball drop). The run stops the cascade with three guards:
//   rest_speed         after an impact whose outgoing normal speed is below it, the contact is
//                      put at rest on its surface (Resting mode: normal motion frozen);
//   min_event_spacing  two impacts of one contact closer in time than this also mean rest;
//   max_events         a hard cap: exceeding it ends the run with Status::ZenoLimit.
// The rest guard costs at most 2 rest_speed / (g (1 - e)) of Zeno time for a ball under gravity.
// A numerical flight also rests a contact at a located impact that is not approaching: bounces
// lower than its absolute tolerance are below what it resolves.
//
// Two flights: any Integrator with root finding (any model), or the model's closed form (AnalyticFlight),
// the exact reference. With the closed form a resting contact holds the whole state, which is
// exact for one body on a static surface, the case closed forms cover here.
#include "integrator.hpp"
#include "mechanical_system.hpp"
#include "run_result.hpp"

namespace contact {

struct EventOptions {
  double t_end = 3.0;            // [s]
  double sample_dt = 0.01;       // output spacing [s]
  IntegratorOptions integrator;  // the numerical flight (CVODE BDF by default)
  double rest_speed = 1e-7;      // [m/s]
  double min_event_spacing = 0;  // [s]
  long max_events = 1000000;
  bool reverse_order = false;    // sequential rule: highest contact index first instead of lowest
};

// Flight by a numerical integrator.
RunResult run_event_driven(const MechanicalSystem& model, const EventOptions& options);
// Flight by the model's closed form.
RunResult run_event_driven(const MechanicalSystem& model, const AnalyticFlight& flight,
                           const EventOptions& options);

}  // namespace contact
