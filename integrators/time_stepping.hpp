#pragma once
// The loop every time-stepping method shares (sequential impulses, soft step, XPBD, Moreau–Jean,
// the implicit Euler spring): fixed steps of dt, each taken by the method's own step function,
// with what the run records done here once: contacts (begin when a contact carries an impulse
// or overlaps, end when it does neither), penetration, apexes in free flight, the energy ledger
// (the step books what its contact solve or dashpot removes; the rest is drift), samples, and
// a typed failure on a non-finite state.
#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/integrators/run_recorder.hpp"
#include "contact_ode/integrators/run_result.hpp"
#include "contact_ode/models/mechanical_system.hpp"

#include <functional>
#include <span>
#include <string>
#include <vector>

namespace contact {

// Contacts whose gap is within this of closing count as closed [m]: a resting column's positions
// carry rounding of 1e-17 m, which must not open its contacts for a step (the ball above would
// fall freely for that step and land with an impact).
inline constexpr double kContactMargin = 1e-9;

// Below this a contact's push is the rounding of its solver (Moreau-Jean's LCP is solved to
// 1e-12 of its velocity scale) [m/s].
inline constexpr double kPushNoise = 1e-9;

struct StepReport {
  // Energy the contact model removed during the step [J]: for impulses, Newton's loss
  // (impact_losses) for the approach speed at the step's start; for springs, the dashpot's work
  // and the elastic energy of laws that let go while the bodies overlap (SpringSwitches).
  double dissipated = 0;
  // How much each contact pushed during the step: the change of its gap rate its impulse made,
  // w lambda [m/s] (a spring method: 1 while its law acts). A contact is closed during a step in
  // which it pushes by more than kPushNoise, or overlaps by more than kContactMargin.
  std::vector<double> push;
};

// What Newton's law with restitution e removes from a contact of effective inverse mass w
// approaching at u < 0: (1 - e^2) u^2 / (2 w) [J]; 0 when it does not approach. Booked once per
// impact, at the step a contact closes, on the gap rate the step began with: Newton's law acts at
// the impact; what a closed contact does afterwards (the g dt each step adds and its impulse
// removes, a soft contact's sinking) is the method's own, and shows as its drift.
inline double newton_loss(double u, double e, double w) {
  return u < 0 ? 0.5 * (1 - e * e) * u * u / w : 0.0;
}

// Newton's loss of the contacts that closed this step (`fresh`), contact i having approached at
// u[i] under restitution e[i] and taken the impulse P[i] over the step. One alone (no other active
// contact's gap rate moves under its impulse): newton_loss, exactly. Contacts that share a body end
// the approach together, and newton_loss, a contact's loss alone, is not theirs (a plastic strike
// on a row of touching balls loses 2/3 of the energy for three and counted 1/2): impulses that
// leave each contact at -e u take -sum P_j (1 - e_j) u_j / 2 of kinetic energy (a resting
// neighbour, u = 0, adds none). P includes the support of the step's other forces, an error of
// g h / |u| in the loss. Costs one copy of the state in a step where a contact closes.
double impact_losses(const ContactGeometry& geo, const NormalImpulses& normal, const Vector& y,
                     const std::vector<bool>& active, const std::vector<bool>& fresh,
                     std::span<const double> u, std::span<const double> e, std::span<const double> P);

// Advances y by one step h; counts its work in stats; throws SolverFailure when it cannot.
using StepFunction =
    std::function<void(double t, double h, Vector& y, StepReport& report, SolverStats& stats)>;

// `springs`: whether the method's contacts are the scene's penalty springs (their elastic energy
// counts); impulse methods pass false, and an overlap they leave holds no energy. The run's work
// bound (steps times the method's MethodInfo::passes) solve() checks before it starts.
// `game`: a game loop's method, whose persistence and on_notifications give the run the game
// loops' notifications (collision_list.hpp), a contact detected in each step in which it is closed.
RunResult run_time_stepping(const Dynamics& model, const std::string& method, double dt,
                            const StepFunction& step, const SolveOptions& span, bool springs,
                            const Method* game = nullptr);

// Adds d to contact i's accumulated impulse `lambda`, clamped at >= 0 (a contact pushes, never
// pulls), and applies what changed to the velocities. Returns the change [N s].
double accumulate_impulse(const NormalImpulses& normal, std::size_t i, double d, double& lambda, Vector& y);

// The elastic energy of clamped laws that let go of an overlap, or take hold at one, over a step
// of a spring method. energy() counts a spring only while its law pushes (switching > 0): a clamped
// law that lets go while the bodies overlap releases its elastic energy (a physical loss), and one
// that takes hold at an overlap takes it back. Booked as the penalty method books it at its roots,
// but only for a switch inside the overlap (at both ends of the step): where the overlap itself
// crosses zero the elastic energy is continuous, and what changes is the scheme's error. Left
// out, the implicit Euler spring's ledger ended low by the 1.3 % of E0 a clamped law tuned to
// e = 0.8 releases, however small the step. (XPBD, which holds every law clamped, books what a
// contact that does not push loses of its counted spring, sub-step by sub-step: xpbd.cpp.)
class SpringSwitches {
 public:
  explicit SpringSwitches(std::size_t contacts) : engaged_(contacts), overlapping_(contacts) {}
  // Each law's state as the step begins.
  void before(const ContactGeometry& geo, ConstVectorRef y);
  // The energy released over the step (taken back: negative) [J], the laws' states at y.
  double released(const ContactGeometry& geo, ConstVectorRef y) const;

 private:
  std::vector<char> engaged_, overlapping_;
};

// The entry of a time-stepping method that resolves contacts by impulses with Newton's
// restitution (sequential impulses, soft step, Moreau–Jean): fixed step, needs normal impulses
// and an impulse map (for e); `settings` are the Method fields it reads (MethodInfo::settings).
MethodInfo impulse_stepping_method(
    std::string name, std::string description,
    std::function<RunResult(const Dynamics&, const Method&, const SolveOptions&)> run,
    std::vector<std::string> settings, std::function<int(const Method&)> passes = {});

// The smooth part of a step, every contact free (gravity and the scene's other forces). It keeps
// the scene's position mask, the all-free modes and a scratch rate, so that a step allocates
// nothing. Each call evaluates the right-hand side once and returns 1 (for the statistics).
class FreeMotion {
 public:
  explicit FreeMotion(const Dynamics& model);
  // v += h a(q, v), the positions left as they are.
  long add_velocity(double t, double h, Vector& y);
  // q += h Q(q) v with the velocities in y (the position rows of the right-hand side read only
  // the velocities), then the scene's invariants restored.
  long advance_positions(double t, double h, Vector& y);
  // dst's positions := src's, its velocities untouched.
  void copy_positions(const Vector& src, Vector& dst) const;
  const Mask& positions() const { return positions_; }

 private:
  const Dynamics& model_;
  Mask positions_;
  ContactModes free_;
  Vector rate_;
};

}  // namespace contact
