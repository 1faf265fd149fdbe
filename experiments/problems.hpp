#pragma once
// The test problems of the convergence and work-precision studies: a scene, the time its error is
// measured at, the duration of one contact (which sets the fixed steps), and the error of a run's
// final state, scaled to 1 for an error the size of the motion, against either the spring
// solution (penalty methods) or the rigid limit (impulses).
#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/integrators/run_result.hpp"
#include "contact_ode/models/ball_drop.hpp"
#include "contact_ode/models/mechanical_system.hpp"
#include "contact_ode/models/parameters.hpp"

#include <nlohmann/json.hpp>

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace contact {

struct Problem {
  std::string name;
  std::shared_ptr<const MechanicalSystem> model;
  double t_end;             // the error is measured at this time [s]
  double contact_duration;  // of one contact [s]
  // The options that set the contact and their values, as a refusal names them: "--k: value '1' makes".
  std::string set_by;
  std::function<double(const RunResult& r, bool rigid)> error;
};

// 1 kg dropped from h0 onto a Hooke spring k, to t_end. References in closed form (hooke_ball_state,
// rigid_ball_state with e = 1); error max(|x - x*| / h0, |v - v*| / V), V the impact speed.
Problem ball_problem(double k, double t_end, double h0 = 1.0);

// One setting's error over several problems of one kind (drops from several heights): the largest
// and the RMS error (each problem's own `error`, against its spring model), and the mean
// right-hand-side evaluations and CPU time per solve. A run that fails ends the setting: its
// status ("ok" else the run's, e.g. "convergence-failure") and what the solver said, the errors
// NaN (a failed run has no final state to score), the cost of the runs until then.
// JSON as {"max", "rms", "rhs", "cpu_s", "status", "failure"}.
struct ErrorSpread {
  double max = 0, rms = 0, rhs = 0, cpu_s = 0;
  std::string status = "ok", failure;  // failure: "<status> at t = ... s: <solver's message>"
  bool ok() const { return status == "ok"; }
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ErrorSpread, max, rms, rhs, cpu_s, status, failure)
// As report(RunResult) for a setting: "<what>: <failure>" on stderr if it failed; whether it ran.
bool report(const ErrorSpread& r, const std::string& what);
ErrorSpread error_over(const std::vector<Problem>& problems,
                       const std::function<RunResult(const Problem&)>& solve_one);
// at_step(step) for each of `steps`, coarsest first, stopping after the first that succeeds with a
// maximum error below `floor` (0: never stops): a finer step would measure rounding, not the
// method, and the finest of a halving ladder costs as much as all the others together.
std::vector<ErrorSpread> errors_down_to(const std::vector<double>& steps, double floor,
                                        const std::function<ErrorSpread(double)>& at_step);

// ball_problem from `count` heights in [1, 1.25) m, quasi-random (the golden-ratio sequence): the
// contacts of the drops fall at phases spread evenly over any fixed step, so that a convergence
// study of a step that straddles a kink sees every phase rather than one.
std::vector<Problem> ball_problems_over_heights(double k, double t_end, std::size_t count);

// A row of `balls` steel balls (ball_chain.hpp) on Hooke springs k, the striker at 1 m/s, measured
// once the pulse has had three pair contacts per ball to cross it. Spring reference: CVODE BDF at
// rtol 1e-12 with the switches located (computed here; a failure throws); rigid reference: the
// last ball leaves at v0 and the others rest. Error: the largest velocity error over v0.
Problem chain_problem(long balls, double k);

// One run of the work-precision study: a problem, a paradigm and its integrator at one setting.
struct WorkJob {
  const Problem* problem;
  std::string paradigm, integrator, setting;
  double value;
  Method method;
};
// Every run of the study on `problems`: the penalty paradigm under each of `integrators` (the
// adaptive ones at `tols`, the fixed-step ones at 1/16 of a contact halved `halvings` times), the
// game loops (impulses and springs, semi-implicit Euler) at those steps, event-driven impulses
// with CVODE BDF and GSL RK8PD at `tols`, and the exact flight on the ball.
std::vector<WorkJob> work_precision_jobs(const std::vector<Problem>& problems,
                                         const std::vector<std::string>& integrators,
                                         const std::vector<double>& tols, long halvings);

// The figure panels a work-precision series belongs to, at most eight series each: "explicit"
// (penalty under the explicit and fixed-step integrators), "implicit" (under the implicit and
// multistep ones), "paradigms" (game loops, event-driven impulses, penalty under CVODE BDF) and
// "peers" (SciPy, paradigm "scipy", beside CVODE BDF and Adams and GSL RKF45).
std::vector<std::string> work_panels(const std::string& paradigm, const std::string& integrator);

// What a work-precision panel of `problem` ("ball" or "chain") plots against CPU time. The
// paradigms panel: each run's physical error, against the rigid body. The others compare codes
// that integrate one model, the penalty spring, whose physical errors are all its modelling error
// (0.21 for the ball at k = 1e4, at every tolerance), a flat line that says nothing of the codes:
// they plot the model error, against the spring's own solution.
struct PanelAxis {
  bool physical;
  std::string label;
};
PanelAxis work_panel_axis(const std::string& problem, const std::string& panel);

// A ball drop's first apex against the rigid one, |apex - e^2 h0| for a ball dropped at rest
// (RigidBounces in general) [m]; NaN when the run failed or did not bounce.
double first_apex_error(const BallDropParams& p, const RunResult& r);

// The simulated time a ball needs for its first contact and first apex: the flight to the floor
// (the rigid T1), 1.25 times the contact's duration as Hooke's exact form gives it with the damped
// frequency, (pi + 2 atan(g / (w V))) / w_d, w_d = w sqrt(1 - zeta^2), and a rise no longer than
// V / g, plus 0.05 s; never less than `at_least` (nor, for a nonlinear or overdamped law, more). A soft
// spring holds the ball long: a fixed 1.6 s ended before the first bounce below k = 33 N/m.
double first_bounce_window(const BallDropParams& p, double at_least);
// Whether a ball-drop run under a linear law ended with the spring holding the ball for good: in
// contact at its end, with too little energy of oscillation about the static sag s = m g / k,
// E = m v^2 / 2 + k (delta - s)^2 / 2, to come back to the surface (E < k s^2 / 2) or, under a law
// that lets go while overlapping, to bring its force k delta + c delta' = k s + k u + c u' to zero
// (sqrt(2 E (k + c^2 / m)) < k s, u = delta - s). In contact dE/dt = -c u'^2: once true, true for good.
bool held_for_good(const RunResult& r, const BallDropParams& p);
// A linear law's damped period 2 pi / w_d, w_d = sqrt(k / m - (c / 2 m)^2) [s]: NaN when
// overdamped or nonlinear. A contact that lets go at all does so within one (its later
// excursions toward the surface are smaller).
double damped_period(const BallDropParams& p);
// How a ball-drop run's first bounce went: "bounced" (its first contact closed and its first apex
// reached) or, under a damped law, "held" (held_for_good, no bounce at all). Anything else throws
// std::runtime_error saying by when and how deep the spring sags (m g / k), or, under an undamped
// law (which returns every ball), that the integrator's error held it, followed by `remedy`.
std::string first_bounce(const RunResult& r, const BallDropParams& p, const std::string& what,
                         std::string_view remedy = "");

// The scenes the engines are compared on (experiments/engines.cpp), each scored against its
// exact rigid answer:
//   drop       ball-drop, 1 kg from 1 m, e = 0.8: the first apex against e^2 h0;
//   head-on    two 0.1 kg balls at 1 m/s, e = 0.8: final velocities against (1 -+ e) v0 / 2;
//   cradle-1mm five balls 1 mm apart, e = 1: against the last ball alone leaving at v0;
//   cradle-0   five touching balls, e = 1: against the same sequential answer (a real cradle's);
//   stack      four balls resting on the floor: the top ball's sink against 0 (impulses) or
//              the penalty column's static sink m g n (n + 1) / (2k) (springs).
struct ScoredScene {
  std::string name, scene, scored_as;
  ParameterValues params;  // for make_scene, "k" added by the caller
  double t_end;            // [s]
  double first_apex_time;  // when the first bounce peaks, exactly [s] (NaN: no bounce to peak)
  // The error of a successful run; `springs`: the method models the penalty law.
  std::function<double(const RunResult& r, bool springs)> error;
};
std::vector<ScoredScene> engine_scenes(double k);

// Box2D's soft step bounces an impact from its restitution threshold up, 1 m/s by default, and the
// chains here strike at exactly that speed: there rounding decides (a velocity passed on down a
// row arrives at 1 - 1.1e-16 m/s and stays plastic, so a gapped cradle's last ball left at 0.5
// m/s at some gaps and at 1 m/s at others). `m` with the soft step's threshold at half the strike
// speed `v0`, clear of its strikes; any other method as given.
Method clear_of_restitution_threshold(Method m, double v0);

}  // namespace contact
