#pragma once
// Event-driven impulse resolution: bodies fly freely; the time a contact's gap closes is located
// by root finding (approaching zeros only); Newton's law v+ = -e v- is applied there through the
// model's impulse map; the flight restarts.
//
// Zeno: with e < 1 a bouncing contact accumulates infinitely many impacts before a finite time
// (t_inf = t0 (1+e)/(1-e) for the ball drop). The run stops the cascade with four guards:
//   rest_speed         after an impact whose outgoing normal speed is below it, the contact is
//                      put at rest on its surface (Resting mode: normal motion frozen);
//   rest_height        likewise when the bounce it starts would rise less than this: the height
//                      v_out^2 / (2 |a|), with a the gap's free-flight acceleration (-g for a
//                      ball), measured by a difference quotient of the gap rate along the flight;
//   min_event_spacing  two impacts of one contact closer in time than this also mean rest;
//   max_events         a hard cap: exceeding it ends the run with Status::ZenoLimit.
// Simultaneous contacts (a row of touching balls struck at one end) take their impulses one at a
// time, in sweeps over the contacts in index order (reverse_order: the highest first) until a sweep
// finds none approaching: Gauss–Seidel. A plastic row converges to its common velocity in ~n^3
// impulses; they count against max_events.
// The first three rest only a contact that the flight pushes together (its gap's acceleration < 0,
// as for the initial rest): two balls that leave an impact together fly on. A resting contact that
// an impulse drives together faster than rest_speed takes its impact and leaves rest (a ball
// landing on one at rest on the floor: the floor takes its share); one driven together slower than
// that stays at rest and is settled again (its support takes the impulse). Bodies that go on pressing into
// each other after an impact with no support holding them (a free cuboid turning under a ball at
// e = 0) are a sustained contact impulses do not model: a sample that finds an overlap beyond
// 100 atol ends the run with Status::Unresolved.
// A contact that starts closed (gap <= 0), still (|gap rate| <= rest_speed) and pushed together by
// the flight (the gap's acceleration < 0, with the contacts below it already held) starts at rest:
// a ball released on the floor, a resting column.
// A resting contact flies free again when an impulse drives it apart faster than rest_speed (a
// ball at rest struck from below its centre) or its gap opens past the flight's resolution, 100
// (atol + rtol |x|) (a ball that a curved support lets go of: the model holds a resting body as a
// support would); one its support holds (holds_at_rest) that the flight's error sinks half of
// that into the support is put back on its surface.
// The rest guards cost at most 2 v_rest / (g (1 - e)) of Zeno time for a ball under gravity,
// with v_rest the larger of rest_speed and sqrt(2 g rest_height).
// A numerical flight resolves a bounce only if it rises well above its absolute tolerance, so its
// rest height defaults to 100 atol. An impact it still locates while not approaching (a bounce it
// did not resolve) ends the run with Status::Unresolved: resting the contact there would silently
// drop the bounce's energy (a ball dropped from 1e-9 m with e = 1 and atol 1e-10 used to lose 99 %
// of its energy and report success).
//
// Two flights: any Integrator with root finding (any model), or the model's closed form (AnalyticFlight),
// the exact reference. With the closed form a resting contact holds the whole state, which is
// exact for one body on a static surface, the case closed forms cover here.
#include "contact_ode/integrators/integrator.hpp"
#include "contact_ode/integrators/run_recorder.hpp"
#include "contact_ode/integrators/run_result.hpp"
#include "contact_ode/models/mechanical_system.hpp"

namespace contact {

struct EventOptions {
  IntegratorOptions integrator;  // the numerical flight (CVODE BDF by default)
  double rest_speed = 1e-7;      // [m/s]
  double rest_height = -1;       // [m]; < 0: 100 * integrator.atol (numerical flight), 0 (exact)
  double min_event_spacing = 0;  // [s]
  long max_events = 1000000;
  bool reverse_order = false;  // sequential rule: highest contact index first instead of lowest
};

// Flight by a numerical integrator. Needs the scene's contact geometry and impulse map.
RunResult run_event_driven(const MechanicalSystem& model, const EventOptions& options,
                           const SolveOptions& span = {});
// Flight by the model's closed form.
RunResult run_event_driven(const MechanicalSystem& model, const AnalyticFlight& flight,
                           const EventOptions& options, const SolveOptions& span = {});

}  // namespace contact
