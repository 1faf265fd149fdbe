#include "energy_drift_runs.hpp"

#include "cli.hpp"
#include "contact_ode/models/ball_drop.hpp"
#include "contact_ode/models/rigid/rigid_scenes.hpp"
#include "sweep_setting.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace contact {

std::vector<DriftRun> drift_runs(const DriftSettings& s) {
  const double m = 1.0, g = 9.81, h0 = 1.0, t0 = std::sqrt(2 * h0 / g);
  std::vector<DriftRun> runs;
  auto ball = std::make_shared<BallDrop>(BallDropParams{m, g, h0, 0.0, 1.0, Hooke{s.k}});
  const double t_ball = 2.0 * static_cast<double>(s.bounces) * t0;  // the n-th rigid impact is at (2n - 1) t0
  const SolveOptions ball_span{.t_end = t_ball, .sample_dt = t_ball / 2000};
  auto ball_run = [&](const std::string& method, const std::string& setting, double value) {
    Method mt{.name = method, .integrator = {.max_steps = 10000000}};
    runs.push_back(
        {"ball", method, setting, value, ball, setting == "exact" ? mt : with_setting(mt, value), ball_span});
  };
  for (const std::string method :
       {"game-euler", "game-symplectic", "game-euler-spring", "game-symplectic-spring", "penalty",
        "event-ode", "game-implicit-spring", "sequential-impulses", "soft-step", "xpbd", "moreau-jean"}) {
    const bool fixed = method_info(method).fixed_step;
    for (double v : fixed ? s.dts : s.rtols) ball_run(method, fixed ? "dt" : "rtol", v);
  }
  ball_run("event-exact", "exact", 0.0);
  for (const auto& name : cli::chosen(s.scenes, rigid::rigid_scene_names())) {
    const rigid::SceneInfo& info = rigid::rigid_scene(name);
    auto scene = std::make_shared<rigid::RigidScene>(info.make({}));
    const SolveOptions span{.t_end = info.t_end, .sample_dt = info.t_end / 200};
    for (const auto& method : kRigidMethods) {
      const bool fixed = method_info(method).fixed_step;
      for (double v : fixed ? s.rigid_dts : s.rigid_rtols)
        runs.push_back(
            {name, method, fixed ? "dt" : "rtol", v, scene, with_setting(rigid_method(method), v), span});
    }
  }
  // The run furthest past its work bound (fixed_step_work over RunLimits::max_steps) and how far.
  const DriftRun* worst = nullptr;
  double over = 1;
  for (const DriftRun& run : runs)
    if (const double r =
            fixed_step_work(run.settings, run.span) / static_cast<double>(run.span.limits.max_steps);
        r > over)
      std::tie(worst, over) = std::pair{&run, r};
  if (worst) {
    const std::string why = *work_refusal(worst->settings, worst->span);
    const double most_bounces = std::floor(static_cast<double>(s.bounces) / over);
    if (worst->system != "ball")  // a scene's span is its own: only its step can change
      throw std::invalid_argument(
          fmt::format("--rigid-dts: value '{:g}' makes {} on {} take {}; accepted [{:.3g}, inf) there",
                      worst->value, worst->method, worst->system, why, worst->value * over));
    if (most_bounces >= 1)  // the ball's work scales with the span, so with --bounces
      throw std::invalid_argument(fmt::format(
          "--bounces: value '{}' makes {} at dt = {:g} s take {}; accepted [1, {:.0f}] at these --dts",
          s.bounces, worst->method, worst->value, why, most_bounces));
    throw std::invalid_argument(fmt::format(  // not one bounce fits: the step is what is wrong
        "--dts: value '{:g}' makes {} take {} for --bounces {}, and even one bounce is too many; accepted "
        "--dts >= {:g} for --bounces {}",
        worst->value, worst->method, why, s.bounces, cli::rounded_up(worst->value * over), s.bounces));
  }
  return runs;
}

}  // namespace contact
