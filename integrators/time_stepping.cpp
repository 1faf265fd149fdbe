#include "time_stepping.hpp"

#include "collision_list.hpp"
#include "normal_kept.hpp"

#include "contact_ode/integrators/capabilities.hpp"
#include "contact_ode/integrators/status.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace contact {

FreeMotion::FreeMotion(const Dynamics& model)
    : model_(model),
      positions_(model.position_mask()),
      free_(model.all_modes(ContactMode::Free)),
      rate_(static_cast<Eigen::Index>(model.state_size())) {}

long FreeMotion::add_velocity(double t, double h, Vector& y) {
  model_.rhs(t, y, free_, rate_);
  for (Eigen::Index j = 0; j < y.size(); ++j)
    if (!positions_[j]) y[j] += h * rate_[j];
  return 1;
}

long FreeMotion::advance_positions(double t, double h, Vector& y) {
  model_.rhs(t, y, free_, rate_);
  for (Eigen::Index j = 0; j < y.size(); ++j)
    if (positions_[j]) y[j] += h * rate_[j];
  model_.normalize(y);
  return 1;
}

void FreeMotion::copy_positions(const Vector& src, Vector& dst) const {
  for (Eigen::Index j = 0; j < dst.size(); ++j)
    if (positions_[j]) dst[j] = src[j];
}

double impact_losses(const ContactGeometry& geo, const NormalImpulses& normal, const Vector& y,
                     const std::vector<bool>& active, const std::vector<bool>& fresh,
                     std::span<const double> u, std::span<const double> e, std::span<const double> P) {
  double loss = 0;
  Vector probe;
  std::vector<std::size_t> closed;
  for (std::size_t i = 0; i < fresh.size(); ++i) {
    if (!fresh[i] || !(u[i] < 0)) continue;
    const double w = normal.inverse_mass(i, y);
    if (closed.empty()) {  // once a step, and only in one where a contact approached as it closed
      probe = y;
      for (std::size_t j = 0; j < active.size(); ++j)
        if (active[j]) closed.push_back(j);
    }
    // An impulse that moves contact i's rate by 1 m/s moves a contact that shares one of its bodies
    // by as much, in general; one on other bodies by nothing but the probe's rounding.
    normal.apply_normal_impulse(i, 1.0 / w, probe);
    const bool shared = std::ranges::any_of(closed, [&](std::size_t j) {
      return j != i && std::abs(geo.gap_rate(j, probe) - geo.gap_rate(j, y)) > 1e-9;
    });
    normal.apply_normal_impulse(i, -1.0 / w, probe);
    loss += shared ? -0.5 * P[i] * (1 - e[i]) * u[i] : newton_loss(u[i], e[i], w);
  }
  return loss;
}

double accumulate_impulse(const NormalImpulses& normal, std::size_t i, double d, double& lambda, Vector& y) {
  const double updated = std::max(lambda + d, 0.0), change = updated - lambda;
  normal.apply_normal_impulse(i, change, y);
  lambda = updated;
  return change;
}

void SpringSwitches::before(const ContactGeometry& geo, ConstVectorRef y) {
  for (std::size_t i = 0; i < engaged_.size(); ++i) {
    engaged_[i] = geo.switching(i, y) > 0;
    overlapping_[i] = geo.gap(i, y) < 0;
  }
}

double SpringSwitches::released(const ContactGeometry& geo, ConstVectorRef y) const {
  double energy = 0;
  for (std::size_t i = 0; i < engaged_.size(); ++i) {
    const bool was = engaged_[i] != 0, now = geo.switching(i, y) > 0;
    if (was != now && overlapping_[i] && geo.gap(i, y) < 0)
      energy += (was ? 1.0 : -1.0) * geo.elastic_energy(i, y);
  }
  return energy;
}

MethodInfo impulse_stepping_method(
    std::string name, std::string description,
    std::function<RunResult(const Dynamics&, const Method&, const SolveOptions&)> run,
    std::vector<std::string> settings, std::function<int(const Method&)> passes) {
  return {.name = std::move(name),
          .description = std::move(description),
          .family = "time-stepping",
          .fixed_step = true,
          .uses_contact_law = false,
          .needs = "dynamics, contact geometry, an impulse map and normal impulses",
          .can_run = [](const Dynamics& s) { return has_impulse_map(s) && has_normal_impulses(s); },
          .run = std::move(run),
          .settings = std::move(settings),
          .passes = std::move(passes)};
}

RunResult run_time_stepping(const Dynamics& model, const std::string& method, double dt,
                            const StepFunction& step, const SolveOptions& span, bool springs,
                            const Method* game) {
  const std::size_t nc = model.contact_count();
  const ContactGeometry& geo = contact_geometry(model);
  RunRecorder rec(model, method, span);
  if (!springs) rec.exclude_spring_energy();
  std::optional<CollisionList> listed;
  if (game) listed.emplace(nc, game->persistence, game->on_notifications);
  Vector y = model.initial_state(), y_prev = y;
  StepReport report{0.0, std::vector<double>(nc, 0.0)};
  SolverStats stats;
  double t = 0.0;
  try {
    rec.sample(0.0, y);
    for (std::size_t i = 0; i < nc; ++i)
      if (geo.gap(i, y) < -kContactMargin) rec.contact_begin(i, 0.0, geo.gap_rate(i, y));
    const auto n_steps = static_cast<long>(steps_to_cover(span.t_end, dt));  // solve() checked the work
    for (long n = 1; n <= n_steps; ++n) {
      throw_if_stop_requested(t);
      const double t0 = t, h = std::min(dt, span.t_end - t0);
      t = n == n_steps ? span.t_end : static_cast<double>(n) * dt;
      y_prev = y;
      report.dissipated = 0;
      std::fill(report.push.begin(), report.push.end(), 0.0);
      step(t0, h, y, report, stats);
      stats.steps += 1;
      if (!y.allFinite())
        throw SolverFailure(Status::NonFiniteState, t,
                            fmt::format("state is not finite after step {} (dt = {:g} s)", n, h));
      rec.add_dissipated(report.dissipated);
      for (std::size_t i = 0; i < nc; ++i) {
        const bool touching = report.push[i] > kPushNoise || geo.gap(i, y) < -kContactMargin;
        const double r0 = geo.gap_rate(i, y_prev), r1 = geo.gap_rate(i, y);
        // The record ends first: a flight whose top falls in the step its contact ends in (a short
        // hop, or an event-driven engine's impact late in the step before) lost that top, and the
        // next apex was reported as the first (Siconos, 1 um drop at a 0.2 ms step).
        if (!touching && rec.contact_open(i)) rec.contact_end(i, t0, r1);
        // A flight's top, where the gap rate turns: only above the margin within which the step
        // holds a contact closed (a column's top balls lift by 1e-22 m and settle back).
        if (!touching && !rec.contact_open(i) && r0 > 0 && r1 <= 0) {
          const double s = r0 / (r0 - r1), top = geo.gap(i, y_prev) + 0.5 * r0 * s * h;
          if (top > kContactMargin) rec.apex(i, t0 + s * h, top, rec.energy(y_prev + s * (y - y_prev)));
        }
        if (touching && !rec.contact_open(i)) rec.contact_begin(i, t0, r0);
        if (touching) rec.observe_penetration(i, -geo.gap(i, y));
        if (touching && springs) require_normal_kept(geo, i, t, y, std::max(-r1, 0.0) * h, dt);
        if (touching && listed) listed->detected(i);
      }
      if (listed) listed->end_step(n, t, rec);
      if (t >= rec.next_sample_time() * (1 - 1e-12)) rec.sample(t, y);
    }
  } catch (const SolverFailure& failure) {
    return rec.fail(failure, stats);
  }
  return rec.finish(stats, t);
}

}  // namespace contact
