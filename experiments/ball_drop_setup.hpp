#pragma once
// The ball drop experiment's options and the pieces its two recipes share: the single comparison
// (ball_drop.cpp) and the stiffness sweep (ball_drop_sweep.cpp, --sweep).
#include "contact_ode/analysis/references.hpp"
#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/models/contact_law.hpp"
#include "experiment.hpp"
#include "output.hpp"

#include <functional>
#include <string>
#include <vector>

namespace contact {

struct BallDropOptions {
  std::string methods = "all";
  std::string law = "kelvin-voigt";
  double k = 1e5, e = 0.8, m = 1.0, g = 9.81, h0 = 1.0, v0 = 0.0;
  double dt = 1e-3, rtol = 1e-8, atol = 0.0, t_end = 3.0, sample_dt = 0.01;  // atol 0: scaled
  std::string jacobian = "analytic";
  std::string integrator = "cvode-bdf";
  std::string linear_solver = "auto";
  long max_steps = 100000;
  long max_records = RunLimits{}.max_records;
  double rest_speed = 1e-7;
  bool sweep = false;
  double k_min = 1e2, k_max = 1e8;
  long per_decade = 1;
};

// The absolute tolerance scaled to the drop: 1e-10 per metre of its height scale
// L = h0 + v0^2 / (2g) (the highest point; h0 without gravity), applied to heights [m] and speeds
// [m/s] alike. At L = 1 m it is the 1e-10 the study uses; a drop from 1e-9 m gets 1e-19, so that
// its bounces stay far above what the flight resolves.
double scaled_atol(const BallDropOptions& o);
// Throws std::invalid_argument naming --h0 and --v0 when the drop's height scale or impact speed
// is beyond the doubles (--v0 1e300): refused as "--atol: value 'inf'" or by a closed form
// ("linear_law_first_contact: V = inf"), options and functions the user never named.
void check_scales(const BallDropOptions& o);
ContactLaw law_for(const BallDropOptions& o, double k);
Method method_for(const BallDropOptions& o, const std::string& name);
// `progress`: SolveOptions::progress of the run (Progress::follow), or none.
RunResult run_ball(const BallDropOptions& o, const std::string& method, double k,
                   std::function<void(double)> progress = {});
// Every method that can run the ball drop (with the default law), and those that can run it with
// o's law (a power law has no linear spring for XPBD or an engine's spring setting to match) and
// linear solver (KLU: not penalty-dq, whose Jacobian is difference quotients).
std::vector<std::string> ball_methods();
std::vector<std::string> ball_methods(const BallDropOptions& o);
// The first contact in closed form where the law has one (references.hpp) and the ball reaches
// the floor, else NaN.
SpringContact closed_form_contact(const BallDropOptions& o, double k);
// The closed forms a reader compares the tables with, as text.
std::string ball_references(const BallDropOptions& o);

// The methods --method names (all: every method the options allow).
std::vector<std::string> chosen_methods(const BallDropOptions& o);

// Notes on stderr for options given that do not take effect: a method setting that none of the
// methods run reads (--integrator for siconos), --rtol on a fixed-step integrator (no
// error control; as co.solve() warns in Python), and the other mode's options (a sweep's k range
// without --sweep, --k in a sweep). Notes, not errors: --method all runs methods that do not read
// the tolerance. (--atol still sets the contact threshold and the rest height.)
void note_options_without_effect(const BallDropOptions& o, const Experiment& app,
                                 const IntegratorOptions& integrator);

void run_single(const BallDropOptions& o, OutputSet& out);
// Under mpirun the sweep's (k, method) runs are dealt over the ranks (Experiment::share).
void run_sweep(const BallDropOptions& o, Experiment& app, OutputSet& out);

}  // namespace contact
