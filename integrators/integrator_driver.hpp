#pragma once
// The loop shared by the penalty and event-driven paradigms, for any Integrator: integrate
// through the recorder's output times, stop at each root, let the paradigm act on it (log it,
// switch a contact mode, apply an impulse), restart the integrator when the paradigm changed the
// state or the right-hand side, and end the run with the solver's status on failure.
#include "contact_ode/integrators/integrator.hpp"
#include "contact_ode/integrators/run_recorder.hpp"
#include "contact_ode/models/mechanical_system.hpp"

#include <algorithm>
#include <functional>

namespace contact {

struct EventHandling {
  // Called at every root with the state there (editable) and the root info. Returns whether the
  // integrator must restart from (t, y).
  std::function<bool(double t, Vector& y, const std::vector<int>& roots_found)> on_roots;
  // Records a sample (optional; default: the recorder's sample(t, y)).
  std::function<void(double t, ConstVectorRef y)> sample;
  std::vector<int> root_directions;  // empty: both directions
};

// The contact threshold: a contact begins when its switching function (or, event-driven, its
// overlap) passes this length and ends when it falls this far below zero. Root functions are
// offset by it towards the side of the mode a contact is held in, so that none is ever exactly
// zero where an integrator (re)starts: CVODE deactivates a root function that is exactly zero at
// its initial time and reactivates it without reporting a root when it turns non-zero, which let
// touching bodies pass through each other unnoticed.
// It is a thousandth of the absolute tolerance: an overlap below the tolerance is not resolved by
// the integrator anyway, so a contact always means a real overlap, and the force missed while
// waiting for it (k times the threshold) is a thousandth of the error the tolerance allows. An
// offset far below every resolved length (1e-150 m, formerly) opened contacts on rounding noise
// (overlaps of 1e-26 ... 1e-150 m along a touching chain) and let CVODE's sign test
// glo * ghi < 0 underflow to zero, so that roots went unreported and the run stalled.
inline double contact_threshold(const IntegratorOptions& options) { return 1e-3 * options.atol; }

// Event-driven impacts need no such threshold: they fire only on approach, and the projection
// then moves the bodies by the overlap at the root, which must stay far below every resolved
// length for impulses to keep angular momentum to rounding. The gap's root function is offset by
// this much so that touching bodies (gap exactly 0 after a projection) count as apart: 1e-150 m,
// or a millionth of atol where that is smaller (a drop of 1e-155 m, atol scaled to it, overlapped
// by 1e-150 m before its impact fired, 1e5 times its height: 'unresolved').
inline double touch_offset(const IntegratorOptions& options) { return std::min(1e-150, 1e-6 * options.atol); }

RunResult drive(OdeSystem system, ConstVectorRef y0, const IntegratorOptions& options, RunRecorder& recorder,
                const EventHandling& events);

// The ODE of `model` with every contact in the modes `modes_at(y)` gives: right-hand side,
// Jacobian and its band, and the IMEX split (contact forces implicit, free motion explicit).
// No root functions; the paradigm adds its own.
using ModesAt = std::function<const ContactModes&(ConstVectorRef y)>;
OdeSystem mechanical_ode(const Dynamics& model, ModesAt modes_at);

// The same ODE with one more state, W' = power(y): the energy a physical loss has removed. W
// enters nothing else, so its Jacobian row is left empty (Newton's iteration for W converges as
// soon as y's does) and the band is unchanged; in an IMEX split it is explicit.
OdeSystem with_ledger(OdeSystem base, std::function<double(ConstVectorRef y)> power);

}  // namespace contact
