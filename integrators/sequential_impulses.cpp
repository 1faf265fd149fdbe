// Sequential impulses: the projected Gauss–Seidel contact solver of Bullet, ODE and PhysX. Each
// step: gravity and the other forces update the velocities; every overlapping contact gets a
// target gap rate (-e times its approach speed from the restitution threshold up, else 0) plus a
// Baumgarte push-out erp * overlap / dt; `iterations` Gauss–Seidel sweeps then solve for the
// normal impulses, each accumulated impulse clamped at >= 0 (contacts push, never pull), the
// first sweep started from the last step's impulses (warm starting); the positions then move
// with the new velocities (semi-implicit Euler). With split_impulse the push-out is solved
// apart, as pseudo-velocities that move the positions and are then forgotten (Bullet's split
// impulses): the overlap is corrected without the energy Baumgarte's bias feeds the bounce.
// With one contact, no warm start and erp = 0 a single sweep is the exact impulse of Newton's
// law: v+ = -e v- (tests/test_time_stepping.cpp).
#include "contact_ode/integrators/capabilities.hpp"
#include "contact_ode/integrators/method_registry.hpp"
#include "time_stepping.hpp"

#include <algorithm>
#include <cmath>

namespace contact {

namespace {

RunResult run(const Dynamics& scene, const Method& m, const SolveOptions& span) {
  const ContactGeometry& geo = contact_geometry(scene);
  const NormalImpulses& normal = normal_impulses(scene, m.name);
  const ImpulseMap& law = impulse_map(scene, m.name);
  const std::size_t nc = scene.contact_count();
  // Without a threshold a resting contact bounces on gravity's g dt of every step.
  const double threshold = std::isnan(m.restitution_threshold) ? 0.2 : m.restitution_threshold;
  std::vector<double> lambda(nc, 0.0), target(nc), bias(nc), push(nc), pseudo(nc), start(nc), restitution(nc);
  std::vector<bool> active(nc), fresh(nc);
  FreeMotion motion(scene);
  Vector ghost = Vector::Zero(static_cast<Eigen::Index>(scene.state_size()));
  auto step = [&](double t, double h, Vector& y, StepReport& report, SolverStats& stats) {
    for (std::size_t i = 0; i < nc; ++i) start[i] = geo.gap_rate(i, y);
    stats.rhs_evals += motion.add_velocity(t, h, y);
    // Targets from the velocities before any impulse: a warm start of the contact below must not
    // count as an approach of the one above.
    for (std::size_t i = 0; i < nc; ++i) {
      const bool was = active[i];
      active[i] = geo.gap(i, y) <= kContactMargin;
      fresh[i] = active[i] && !was;
      if (!active[i] || !was || !m.warm_start) lambda[i] = 0;
      if (!active[i]) continue;
      const double approach = geo.gap_rate(i, y);
      // Bullet's restitutionCurve: no bounce below the threshold, |u| < threshold; at it, one.
      restitution[i] = approach <= -threshold ? law.restitution(i) : 0.0;
      target[i] = -restitution[i] * approach;
      const double correction = m.erp / h * std::max(-geo.gap(i, y), 0.0);
      bias[i] = m.split_impulse ? 0.0 : correction;
      push[i] = m.split_impulse ? correction : 0.0;
    }
    for (std::size_t i = 0; i < nc; ++i)
      if (active[i]) normal.apply_normal_impulse(i, lambda[i], y);  // warm start
    for (int sweep = 0; sweep < m.iterations; ++sweep)
      for (std::size_t i = 0; i < nc; ++i) {
        if (!active[i]) continue;
        accumulate_impulse(normal, i, (target[i] + bias[i] - geo.gap_rate(i, y)) / normal.inverse_mass(i, y),
                           lambda[i], y);
      }
    stats.newton_iters += m.iterations;  // the solver's sweeps
    // A fresh contact's accumulated impulse is all this step's (it had no warm start).
    report.dissipated += impact_losses(geo, normal, y, active, fresh, start, restitution, lambda);
    for (std::size_t i = 0; i < nc; ++i)
      report.push[i] = active[i] ? lambda[i] * normal.inverse_mass(i, y) : 0.0;
    stats.rhs_evals += motion.advance_positions(t, h, y);
    if (m.split_impulse) {
      // The push-out as pseudo-velocities: solved on a copy with zero velocities, which then
      // moves the positions by h times what it gained.
      ghost.setZero();
      motion.copy_positions(y, ghost);
      std::fill(pseudo.begin(), pseudo.end(), 0.0);
      for (int sweep = 0; sweep < m.iterations; ++sweep)
        for (std::size_t i = 0; i < nc; ++i) {
          if (!active[i]) continue;
          accumulate_impulse(normal, i, (push[i] - geo.gap_rate(i, ghost)) / normal.inverse_mass(i, ghost),
                             pseudo[i], ghost);
        }
      stats.rhs_evals += motion.advance_positions(t, h, ghost);
      motion.copy_positions(ghost, y);
    }
  };
  return run_time_stepping(scene, m.name, m.dt, step, span, false);
}

}  // namespace

std::vector<MethodInfo> sequential_impulses_methods() {
  return {impulse_stepping_method(
      "sequential-impulses",
      "projected Gauss-Seidel impulses, 10 sweeps, warm starting, split-impulse "
      "push-out (Bullet, ODE, PhysX)",
      run, {"dt", "iterations", "warm_start", "erp", "split_impulse", "restitution_threshold"},
      [](const Method& m) { return m.iterations; })};
}

}  // namespace contact
