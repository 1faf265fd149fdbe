#include "ball_drop_setup.hpp"

#include "cli.hpp"

#include "contact_ode/models/ball_drop.hpp"
#include "contact_ode/models/law_registry.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace contact {

double scaled_atol(const BallDropOptions& o) {
  if (o.atol > 0) return o.atol;
  return 1e-10 * (o.h0 + (o.g > 0 ? o.v0 * o.v0 / (2 * o.g) : 0.0));
}

double impact_speed(const BallDropOptions& o) { return contact::impact_speed(o.h0, o.v0, o.g); }

void check_scales(const BallDropOptions& o) {
  // The energy per unit mass, v0^2 / 2 + g h0, must be a double: every run's energies are (the
  // impact speed, formed without its square, is finite further out).
  if (!std::isfinite(scaled_atol(o)) || !std::isfinite(o.v0 * o.v0 + 2 * o.g * o.h0))
    throw std::invalid_argument(
        fmt::format("--h0, --v0, --g: values '{}', '{}' and '{}' give a height scale h0 + v0^2 / (2 g) or a "
                    "squared impact speed v0^2 + 2 g h0 beyond the doubles; accepted: both finite",
                    o.h0, o.v0, o.g));
  // Every run would fail at t = 0 on the samples it may keep (a work limit per method, exit 1):
  // the two options ask for it, so they are refused as such.
  const long kept = RunLimits{}.max_samples;
  if (!(o.t_end / o.sample_dt < static_cast<double>(kept)))
    throw std::invalid_argument(fmt::format(
        "--t-end, --sample-dt: values '{}' and '{}' ask for {:.3g} output samples; at most {} are "
        "kept: accepted --sample-dt > --t-end / {} = {:.3g}",
        o.t_end, o.sample_dt, o.t_end / o.sample_dt, kept, kept, o.t_end / static_cast<double>(kept)));
}

ContactLaw law_for(const BallDropOptions& o, double k) {
  const double V = impact_speed(o);
  return make_law(o.law, {.k = k, .m = o.m, .e = o.e, .v = V > 0 ? V : 1.0});
}

Method method_for(const BallDropOptions& o, const std::string& name) {
  Method m{.name = name, .dt = o.dt, .rest_speed = o.rest_speed};
  m.integrator.method = o.integrator;
  m.integrator.rtol = o.rtol;
  m.integrator.atol = scaled_atol(o);
  m.integrator.max_steps = o.max_steps;
  m.integrator.jacobian = parse_jacobian(o.jacobian);
  m.integrator.linear_solver = parse_linear_solver(o.linear_solver);
  // Fixed-step integrators run at --dt; adaptive and exact ones choose their own steps.
  m.integrator.dt = needs_step(integrator_info(o.integrator)) ? o.dt : 0.0;
  return m;
}

RunResult run_ball(const BallDropOptions& o, const std::string& method, double k,
                   std::function<void(double)> progress) {
  const BallDrop model({o.m, o.g, o.h0, o.v0, o.e, law_for(o, k)});
  return solve(model, method_for(o, method),
               {.t_end = o.t_end,
                .sample_dt = o.sample_dt,
                .limits = {.max_records = o.max_records},
                .progress = std::move(progress)});
}

std::vector<std::string> ball_methods() { return methods_for(BallDrop({})); }

std::vector<std::string> ball_methods(const BallDropOptions& o) {
  std::vector<std::string> names = methods_for(BallDrop({o.m, o.g, o.h0, o.v0, o.e, law_for(o, o.k)}));
  // KLU needs the analytic Jacobian: a method that always forms difference quotients cannot use it.
  if (parse_linear_solver(o.linear_solver) == LinearSolverKind::Klu)
    std::erase_if(names, [](const std::string& name) { return method_info(name).dq_jacobian; });
  return names;
}

SpringContact closed_form_contact(const BallDropOptions& o, double k) {
  const double nan = std::nan("");
  if (!(o.g > 0 || o.v0 < 0)) return {nan, nan, nan};  // without gravity, not thrown down: no contact
  return linear_law_first_contact(o.law, o.m, k, o.e, impact_speed(o), o.g);
}

std::string ball_references(const BallDropOptions& o) {
  std::string s;
  if (o.g > 0) {
    const RigidBounces rigid(o.h0, o.v0, o.g, o.e);
    s += fmt::format(
        "rigid (Newton, e = {:g}): first impact {:.6g} s, first apex {} = {:.6g} m, Zeno time {:.6g} s\n",
        o.e, rigid.T1, o.v0 == 0 ? "e^2 h0" : "(e V)^2 / 2g", rigid.apex_height(1), rigid.zeno_time());
  }
  if (o.law == "hooke") s += "closed forms: Hooke spring with gravity (exact); restitution 1\n";
  if (o.law == "kelvin-voigt" || o.law == "kelvin-voigt-clamped")
    s += "closed forms: Kelvin–Voigt with gravity (exact); restitution e without gravity\n";
  return s;
}

std::vector<std::string> chosen_methods(const BallDropOptions& o) {
  return cli::chosen(o.methods, ball_methods(o));
}

void note_options_without_effect(const BallDropOptions& o, const Experiment& app,
                                 const IntegratorOptions& integrator) {
  // A method setting none of the methods run reads (--method siconos --integrator rk4 said nothing,
  // and with --rtol blamed the integrator, which siconos does not run).
  const auto methods = chosen_methods(o);
  std::vector<std::string> options{"--integrator", "--rtol",      "--atol",       "--dt", "--linear-solver",
                                   "--jacobian",   "--max-steps", "--rest-speed", "--law"};
  if (!o.sweep) options.push_back("--k");  // a sweep's is noted below
  note_unread_options("ball_drop", app, methods, options);
  const bool rtol_read =
      std::any_of(methods.begin(), methods.end(), [](const auto& m) { return reads_option(m, "--rtol"); });
  if (app.given("--rtol") && rtol_read && !reads_rtol(integrator))
    fmt::print(stderr,
               "ball_drop: note: --rtol has no effect on --integrator {} (fixed step: its accuracy is set by "
               "--dt)\n",
               o.integrator);
  // The other mode's options were silently ignored.
  for (const char* other : o.sweep ? std::vector<const char*>{"--k"}
                                   : std::vector<const char*>{"--k-min", "--k-max", "--per-decade"})
    if (app.given(other))
      fmt::print(stderr, "ball_drop: note: {} has no effect {}\n", other,
                 o.sweep ? "with --sweep (k runs from --k-min to --k-max)" : "without --sweep");
}

}  // namespace contact
