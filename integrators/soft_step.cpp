// Soft step (Box2D v3): `substeps` sub-steps per step, each: forces update the velocities, the
// accumulated impulses are applied again (warm start), one soft solve with bias pushes overlaps
// out at most at push_max, the positions move, and one relax solve without bias removes the
// velocity the bias added. After the sub-steps a restitution pass gives each contact that
// approached at least as fast as the threshold and carried an impulse the bounce -e u of its approach.
// The contact frequency is capped at a quarter of the sub-step rate, as Box2D does.
#include "contact_ode/integrators/soft_step.hpp"

#include "contact_ode/integrators/capabilities.hpp"
#include "contact_ode/integrators/method_registry.hpp"
#include "time_stepping.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace contact {

SoftConstraint soft_constraint(double hertz, double zeta, double h) {
  if (hertz == 0) return {0.0, 1.0, 0.0};  // rigid
  const double w = 2 * std::numbers::pi * hertz;
  const double a1 = 2 * zeta + h * w, a2 = h * w * a1, a3 = 1 / (1 + a2);
  return {w / a1, a2 * a3, a3};
}

double soft_impulse(const SoftConstraint& c, double w_n, double u, double s, double L, double push_max) {
  return -c.mass_scale / w_n * (u + std::max(c.bias_rate * s, -push_max)) - c.impulse_scale * L;
}

namespace {

RunResult run(const Dynamics& scene, const Method& m, const SolveOptions& span) {
  const ContactGeometry& geo = contact_geometry(scene);
  const NormalImpulses& normal = normal_impulses(scene, m.name);
  const ImpulseMap& law = impulse_map(scene, m.name);
  const std::size_t nc = scene.contact_count();
  const double threshold = std::isnan(m.restitution_threshold) ? 1.0 : m.restitution_threshold;
  std::vector<double> lambda(nc, 0.0), max_lambda(nc), approach(nc), total(nc), restitution(nc);
  std::vector<bool> active(nc), fresh(nc);
  FreeMotion motion(scene);
  auto step = [&](double t, double dt, Vector& y, StepReport& report, SolverStats& stats) {
    const int n = m.substeps;  // >= 1: solve() checks it
    const double h = dt / n;
    const SoftConstraint soft =
        soft_constraint(std::min(m.contact_hertz, 0.25 / h), m.contact_damping_ratio, h);
    const SoftConstraint rigid{0.0, 1.0, 0.0};
    for (std::size_t i = 0; i < nc; ++i) {
      // Speculative contact: overlapping, or closing the gap within this step.
      const double g = geo.gap(i, y), u = geo.gap_rate(i, y);
      const bool was = active[i];
      active[i] = g + dt * std::min(u, 0.0) <= kContactMargin;
      if (!active[i] || !was || !m.warm_start) lambda[i] = 0;
      fresh[i] = active[i] && !was;
      approach[i] = u;
      max_lambda[i] = 0;
      total[i] = 0;
      restitution[i] = 0;
    }
    // One velocity solve over the active contacts; with bias: soft push-out of overlaps; without:
    // rigid, only keeping contacts from approaching. Open gaps are allowed to close within h.
    auto solve = [&](bool use_bias) {
      for (std::size_t i = 0; i < nc; ++i) {
        if (!active[i]) continue;
        const double s = geo.gap(i, y), w = normal.inverse_mass(i, y), u = geo.gap_rate(i, y);
        double d;
        if (s > 0)
          d = -(u + s / h) / w;  // speculative: approach no faster than the gap closes in h
        else if (use_bias)       // soft push-out, no faster than push_max
          d = soft_impulse(soft, w, u, s, lambda[i], m.push_max);
        else
          d = soft_impulse(rigid, w, u, 0.0, lambda[i]);
        accumulate_impulse(normal, i, d, lambda[i], y);
        max_lambda[i] = std::max(max_lambda[i], lambda[i]);
      }
    };
    for (int k = 0; k < n; ++k) {
      stats.rhs_evals += motion.add_velocity(t + k * h, h, y);
      for (std::size_t i = 0; i < nc; ++i)
        if (active[i]) normal.apply_normal_impulse(i, lambda[i], y);  // warm start
      solve(true);
      stats.rhs_evals += motion.advance_positions(t + k * h, h, y);
      solve(false);
      stats.newton_iters += 2;
      for (std::size_t i = 0; i < nc; ++i) total[i] += lambda[i];  // the sub-step's impulse
    }
    // Restitution, and the ledger: Newton's loss for the approach the step began with, at e where
    // the pass bounces the contact and at 0 (inelastic) where it does not. What the soft push-out
    // adds or removes besides is the method's drift.
    for (std::size_t i = 0; i < nc; ++i) {
      report.push[i] = active[i] ? max_lambda[i] * normal.inverse_mass(i, y) : 0.0;
      fresh[i] = fresh[i] && max_lambda[i] > 0;  // a speculative contact that took no impulse did not close
      if (!active[i] || max_lambda[i] == 0) continue;
      // Box2D v3's b2ApplyRestitution skips a point whose approach is slower than the threshold
      // (relativeVelocity > -threshold): one that strikes at exactly it bounces.
      if (approach[i] > -threshold) continue;  // no bounce: inelastic
      restitution[i] = law.restitution(i);
      total[i] += accumulate_impulse(
          normal, i, -(geo.gap_rate(i, y) + restitution[i] * approach[i]) / normal.inverse_mass(i, y),
          lambda[i], y);
    }
    report.dissipated += impact_losses(geo, normal, y, active, fresh, approach, restitution, total);
  };
  return run_time_stepping(scene, m.name, m.dt, step, span, false);
}

}  // namespace

std::vector<MethodInfo> soft_step_methods() {
  return {impulse_stepping_method("soft-step",
                                  "Box2D v3's soft step: soft contact constraints (30 Hz, damping ratio 10), "
                                  "4 sub-steps, relax and restitution passes",
                                  run,
                                  {"dt", "substeps", "warm_start", "restitution_threshold", "contact_hertz",
                                   "contact_damping_ratio", "push_max"},
                                  [](const Method& m) { return m.substeps; })};
}

}  // namespace contact
