#include "contact_ode/integrators/method_registry.hpp"

#include "contact_ode/models/parameters.hpp"
#include "contact_ode/models/registry.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <tuple>

namespace contact {

const std::vector<MethodInfo>& method_registry() {
  static const std::vector<MethodInfo> all = [] {
    std::vector<MethodInfo> methods;
    for (auto family : {penalty_methods, game_methods, event_methods,  // one entry per family
                        implicit_spring_methods, sequential_impulses_methods, soft_step_methods, xpbd_methods,
                        moreau_jean_methods, engine_methods}) {
      auto entries = family();
      methods.insert(methods.end(), entries.begin(), entries.end());
    }
    return methods;
  }();
  return all;
}

std::vector<std::string> method_names() { return names_of(method_registry()); }

std::vector<std::string> methods_for(const Dynamics& scene) {
  std::vector<std::string> names;
  for (const auto& m : method_registry())
    if (m.can_run(scene)) names.push_back(m.name);
  return names;
}

const MethodInfo& method_info(const std::string& name) {
  return find_named(method_registry(), name, "--method");
}

namespace {

// A method's own checks end a run whose state leaves the doubles' range as non-finite-state; this
// holds for every method, whatever it checks: the exact bounces of a 1e308 kg ball (an impulse of
// 8e308 N s) and of one thrown up at 1e308 m/s (past 1.8e308 m after 1.8 s) reported success with
// a state of inf. The run ends at its first such sample, and what it recorded after that goes.
void end_at_first_non_finite_sample(RunResult& r) {
  const auto bad = std::ranges::find_if(r.samples, [](const Sample& s) { return !s.y.allFinite(); });
  if (bad == r.samples.end()) return;
  r.status = Status::NonFiniteState;
  r.t_reached = bad->t;
  r.message =
      fmt::format("the state is not finite at t = {:.9g} s (sample {} of {}): beyond the doubles' range",
                  bad->t, bad - r.samples.begin(), r.samples.size());
  r.samples.erase(bad, r.samples.end());
  std::erase_if(r.contacts, [&](const ContactRecord& c) { return c.t_begin >= r.t_reached; });
  std::erase_if(r.apexes, [&](const Apex& a) { return a.t >= r.t_reached; });
}

// The settings of the time-stepping and event-driven methods, each in its range (whatever method
// reads them, so that a wrong value never waits for the method that uses it).
void check_method_settings(const Method& m) {
  auto refuse = [](const char* name, double value, const std::string& range) {
    throw std::invalid_argument(
        fmt::format("--{}: value '{}' is {}; accepted range {}", name, value, outside(value), range));
  };
  // Each real setting through its Range, which also refuses a value below the smallest normal
  // double, as the command line does (a 1e-310 s step or tolerance ran into NaN, or a failure that
  // did not name it).
  auto need = [&](const char* name, double value, const Range& range, const char* note = "") {
    if (!range.contains(value)) refuse(name, value, range.to_string() + note);
  };
  // The steps and tolerances have their ranges checked where they are read; here only the rule.
  using Rule = std::tuple<const char*, double, const char*>;
  for (const auto& [name, value, range] :
       {Rule{"dt", m.dt, "(0, inf)"}, Rule{"dt", m.integrator.dt, "[0, inf) (0: the integrator's own)"},
        Rule{"rtol", m.integrator.rtol, "(0, 1)"}, Rule{"atol", m.integrator.atol, "(0, inf)"}})
    if (is_subnormal(value)) refuse(name, value, range);
  if (m.iterations < 1) refuse("iterations", m.iterations, "[1, inf)");
  if (m.substeps < 1) refuse("substeps", m.substeps, "[1, inf)");
  need("erp", m.erp, kUnitInterval);
  need("theta", m.theta, kUnitInterval);
  if (!std::isnan(m.restitution_threshold))
    need("restitution-threshold", m.restitution_threshold, kNonNegative, " or NaN (the method's default)");
  need("contact-hertz", m.contact_hertz, kNonNegative);
  need("contact-damping-ratio", m.contact_damping_ratio, kNonNegative);
  need("push-max", m.push_max, kPositive);
  // Event-driven guards: a rest speed <= 0 never stops a Zeno cascade (the exact flight then ran
  // into the record limit at the Zeno time, a work limit that did not name the cause).
  need("rest-speed", m.rest_speed, kPositive);
  need("rest-height", m.rest_height, kAnyFinite, " (< 0: the default)");
  need("min-event-spacing", m.min_event_spacing, kNonNegative);
  if (m.max_events < 1) refuse("max-events", static_cast<double>(m.max_events), "[1, inf)");
  if (m.persistence < 1) refuse("persistence", m.persistence, "[1, inf)");
}

// Whether the method runs one of the ODE integrators (its `integrator` setting): penalty, event-ode.
bool integrates(const MethodInfo& info) {
  return std::ranges::find(info.settings, "integrator") != info.settings.end();
}

// The samples a run keeps: one per sample_dt, or per step where the steps are fewer, and the first.
double output_samples(const MethodInfo& info, const Method& method, const SolveOptions& options) {
  double samples = options.t_end / options.sample_dt;
  if (info.fixed_step) samples = std::min(samples, steps_to_cover(options.t_end, method.dt));
  return std::min(samples + 1, static_cast<double>(options.limits.max_samples));
}

// A run holds its output samples (the whole state each) and its method's working memory
// (MethodInfo::working_doubles per state entry). A run that passes the limit is refused before it
// starts: a chain of 1e8 balls, or 1e5 balls sampled every 10 us for 0.1 s (16 GB), filled the
// machine, which ends in the kernel's OOM killer rather than an error.
void refuse_what_cannot_fit(const Dynamics& scene, const MethodInfo& info, const Method& method,
                            const SolveOptions& options) {
  const double bytes = memory_estimate(scene, method, options);
  if (bytes <= options.limits.max_memory_bytes) return;
  const double entries = static_cast<double>(scene.state_size());
  throw std::invalid_argument(fmt::format(
      "{} on {} needs about {:.4g} GB ({:.3g} output samples of its {:.3g} state values, and {:.0f} "
      "working doubles per value{}); a run may hold {:.3g} GB (half the memory this process may use): "
      "fewer bodies, a shorter t_end or a wider sample_dt",
      info.name, scene.name(), bytes / 1e9, output_samples(info, method, options), entries,
      info.working_doubles,
      info.dense_state_matrices > 0 ? fmt::format(" and {:.3g} of a dense {:.3g} x {:.3g} matrix",
                                                  info.dense_state_matrices, entries, entries)
                                    : "",
      options.limits.max_memory_bytes / 1e9));
}

int passes(const MethodInfo& info, const Method& method) { return info.passes ? info.passes(method) : 1; }

}  // namespace

double memory_estimate(const Dynamics& scene, const Method& method, const SolveOptions& options) {
  const MethodInfo& info = method_info(method.name);
  const double entries = static_cast<double>(scene.state_size());
  const double dense = info.dense_state_matrices * entries;  // a dense n x n matrix: n more per entry
  return 8 * entries * (info.working_doubles + dense + output_samples(info, method, options));
}

double fixed_step_work(const Method& method, const SolveOptions& options) {
  const MethodInfo& info = method_info(method.name);
  return info.fixed_step ? steps_to_cover(options.t_end, method.dt) * passes(info, method) : 0.0;
}

std::optional<std::string> work_refusal(const Method& method, const SolveOptions& options) {
  const MethodInfo& info = method_info(method.name);
  if (!info.fixed_step) return std::nullopt;
  return fixed_step_work_refusal(steps_to_cover(options.t_end, method.dt), passes(info, method),
                                 options.limits);
}

RunResult solve(const Dynamics& scene, const Method& method, const SolveOptions& options) {
  const MethodInfo& info = method_info(method.name);
  if (!info.can_run(scene))
    throw std::invalid_argument(
        fmt::format("method '{}' cannot run scene '{}': it needs {}", info.name, scene.name(), info.needs));
  // (A span of 1e-310 s, below the smallest normal double, gave CVODE's runs a NaN state.)
  if (!kPositive.contains(options.t_end))
    throw std::invalid_argument(fmt::format("--t-end: value '{}' is {}; accepted range (0, inf)",
                                            options.t_end, outside(options.t_end)));
  if (!kPositive.contains(options.sample_dt))
    throw std::invalid_argument(fmt::format("--sample-dt: value '{}' is {}; accepted range (0, inf)",
                                            options.sample_dt, outside(options.sample_dt)));
  if (!(options.limits.max_records >= 1 && options.limits.max_records <= kMaxRecords))
    throw std::invalid_argument(
        fmt::format("--max-records: value '{}' is out of range; accepted range [1, {}]",
                    options.limits.max_records, kMaxRecords));
  if (info.fixed_step && !(std::isfinite(method.dt) && method.dt > 0))
    throw std::invalid_argument(
        fmt::format("--dt: value '{}' is out of range; accepted range (0, inf)", method.dt));
  check_method_settings(method);
  // Before the energy check below builds the initial state: a run refused for its memory need not
  // allocate (and write) a state first. make_scene refuses a state that alone cannot be held.
  refuse_what_cannot_fit(scene, info, method, options);
  // exact-linear integrates y' = A y + b with the scene's Jacobian as A; a scene without one (the
  // rigid scenes) was a run that failed at t = 0 as 'solver-error', naming no setting.
  if (integrates(info) && method.integrator.method == "exact-linear" && !scene.has_jacobian())
    throw std::invalid_argument(fmt::format(
        "--integrator: value 'exact-linear' needs the scene's Jacobian (the A of y' = A y + b), and scene "
        "'{}' has none; accepted for it: the other integrators",
        scene.name()));
  // Every energy a run reports is a double: a scene whose initial energy is not (a drop from 1e308 m,
  // m g h0 overflowed) 'succeeded' with an infinite energy at every sample.
  if (const double e0 = scene.energy(scene.initial_state()); !std::isfinite(e0))
    throw std::invalid_argument(fmt::format(
        "scene '{}': its initial energy is {} J, beyond the doubles; accepted: parameters whose energy "
        "(as m g h0 + m v0^2 / 2 for a drop) is finite",
        scene.name(), e0));
  if (const auto why = work_refusal(method, options)) {  // a work limit at t = 0, its initial state kept
    RunRecorder refused(scene, info.name, options);
    try {
      refused.sample(0.0, scene.initial_state());
    } catch (const SolverFailure& f) {  // more samples than kept: that refusal, as every method's run gives
      return refused.fail(f, {});
    }
    return refused.fail(SolverFailure(Status::WorkLimit, 0.0, *why), {});
  }
  RunResult r = info.run(scene, method, options);
  r.method = info.name;
  if (r.ok()) end_at_first_non_finite_sample(r);
  return r;
}

}  // namespace contact
