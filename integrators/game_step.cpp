#include "contact_ode/integrators/game_step.hpp"

#include "contact_ode/integrators/method_registry.hpp"

#include "collision_list.hpp"
#include "contact_ode/integrators/capabilities.hpp"
#include "contact_ode/integrators/run_recorder.hpp"
#include "normal_kept.hpp"
#include "time_stepping.hpp"

#include <fmt/format.h>

#include <cmath>

namespace contact {

std::string_view to_string(GameResolution r) {
  switch (r) {
    case GameResolution::ProjectionImpulse:
      return "projection+impulse";
    case GameResolution::Projection:
      return "projection";
    case GameResolution::Impulse:
      return "impulse";
    case GameResolution::Spring:
      return "spring";
  }
  return "?";
}

namespace {

// Fraction of the step at which a linear function going from a to b crosses zero.
double crossing(double a, double b) { return a == b ? 1.0 : a / (a - b); }

}  // namespace

RunResult run_game(const Dynamics& model, const GameOptions& opt, const SolveOptions& span) {
  const std::size_t nc = model.contact_count();
  const ContactGeometry& geo = contact_geometry(model);
  const bool spring = opt.resolution == GameResolution::Spring;
  const bool project =
      opt.resolution == GameResolution::ProjectionImpulse || opt.resolution == GameResolution::Projection;
  const bool impulse =
      opt.resolution == GameResolution::ProjectionImpulse || opt.resolution == GameResolution::Impulse;
  const std::string method = fmt::format("game {} {}", to_string(opt.scheme), to_string(opt.resolution));
  const ImpulseMap* map = spring ? nullptr : &impulse_map(model, method);
  RunRecorder rec(model, method, span);
  // Projection and impulses have no springs: the scene's spring energy at an overlap they leave
  // (a touching row resolved pair by pair in one step) was counted, 820 times the energy of a
  // chain at k = 1e9, whose springs these methods never use.
  if (!spring) rec.exclude_spring_energy();

  // Detection: the spring acts while its switching function is positive, impulses while the
  // bodies overlap. Both are "positive while in contact".
  auto detect = [&](std::size_t i, ConstVectorRef y) {
    return spring ? geo.switching(i, y) : -geo.gap(i, y);
  };
  ContactModes modes = model.all_modes(ContactMode::Free);
  const OdeSystem::Rhs f = [&](double t, ConstVectorRef y, VectorRef yd) { model.rhs(t, y, modes, yd); };

  Vector y = model.initial_state(), y_prev = y;
  FixedStepWork work(y.size());
  const Mask positions = model.position_mask();
  std::vector<double> d_prev(nc);
  for (std::size_t i = 0; i < nc; ++i) {
    d_prev[i] = detect(i, y);
    if (d_prev[i] > 0) rec.contact_begin(i, 0.0, geo.gap_rate(i, y));
  }

  CollisionList listed(nc, opt.persistence, opt.on_notifications);
  SpringSwitches switches(nc);
  SolverStats stats;
  double t = 0.0;
  try {
    rec.sample(0.0, y);
    // solve() checks the work too; run_game is called on its own as well.
    const double steps_needed = steps_to_cover(span.t_end, opt.dt);
    if (const auto why = fixed_step_work_refusal(steps_needed, 1, span.limits))
      throw SolverFailure(Status::WorkLimit, 0.0, *why);
    const auto n_steps = static_cast<long>(steps_needed);
    for (long n = 1; n <= n_steps; ++n) {
      throw_if_stop_requested(t);
      const double t0 = t;
      const double h = std::min(opt.dt, span.t_end - t0);  // the last step lands on t_end
      t = n == n_steps ? span.t_end : static_cast<double>(n) * opt.dt;
      y_prev = y;
      // 1. integrate
      if (spring) {
        geo.modes_from_state(nc, y, modes);
        switches.before(geo, y);
        // The dashpot's loss over the step, by the rectangle rule the Euler step itself uses.
        double power = 0;
        for (std::size_t i = 0; i < nc; ++i)
          if (modes[i] == ContactMode::Penalty) power += geo.dissipated_power(i, y);
        rec.add_dissipated(h * power);
      }
      stats.rhs_evals += fixed_step(opt.scheme, f, positions, t0, h, y, work);
      model.normalize(y);
      if (spring) rec.add_dissipated(switches.released(geo, y));
      stats.steps += 1;
      if (!y.allFinite())
        throw SolverFailure(Status::NonFiniteState, t,
                            fmt::format("state is not finite after step {} (dt = {:g} s)", n, h));
      for (std::size_t i = 0; i < nc; ++i) {
        // Apex: gap rate falls through zero during free flight (not in a step that detects the
        // contact: a resting ball's contact closes and reopens every frame), above kContactMargin
        // (the time-stepping methods' too): below it a top is a tall column's rounding, not a flight.
        const double r0 = geo.gap_rate(i, y_prev), r1 = geo.gap_rate(i, y);
        const double d = detect(i, y);
        if (r0 > 0 && r1 <= 0 && !rec.contact_open(i) && !(d > 0)) {
          const double s = crossing(r0, r1), top = geo.gap(i, y_prev) + 0.5 * r0 * s * h;
          if (top > kContactMargin) rec.apex(i, t0 + s * h, top, rec.energy(y_prev + s * (y - y_prev)));
        }
        // 2. detect, 3. resolve
        if (d > 0) {
          listed.detected(i);
          // Detected again in the frame right after its record ended: the same contact goes on.
          if (!rec.contact_open(i) && !rec.reopen_contact(i, t0))
            rec.contact_begin(i, t0 + crossing(d_prev[i], d) * h, geo.gap_rate(i, y));
          rec.observe_penetration(i, -geo.gap(i, y));
          if (spring) require_normal_kept(geo, i, t, y, std::max(-geo.gap_rate(i, y), 0.0) * h, opt.dt);
          if (project) map->project(i, y);
          if (const double u = geo.gap_rate(i, y); impulse && u < 0) {
            // What the impulse takes, -J (u- + u+) / 2 (ImpulseMap): the scene's whole energy
            // before and after each contact's impulse made a frame of a tall column O(N^2).
            const double J = map->apply_impulse(i, map->restitution(i), y);
            rec.add_dissipated(-0.5 * J * (u + geo.gap_rate(i, y)));
            stats.events += 1;
          }
        }
        // 4. notify, decided on the resolved state: a contact ends once the bodies no longer
        // overlap (touching after a projection counts as not overlapping) and do not approach.
        // Projection alone leaves them approaching, so its contact stays open while it pushes.
        const double d_after = detect(i, y);
        if (rec.contact_open(i) && d_after <= 0 && geo.gap_rate(i, y) >= 0) {
          const double end = d > 0 ? t : t0 + crossing(d_prev[i], d_after) * h;
          rec.contact_end(i, end, geo.gap_rate(i, y));
        }
        d_prev[i] = d_after;
      }
      // 4. notify: one batch, after the whole physics step.
      listed.end_step(n, t, rec);
      if (t >= rec.next_sample_time() * (1 - 1e-12)) rec.sample(t, y);
    }
  } catch (const SolverFailure& failure) {
    return rec.fail(failure, stats);
  }
  return rec.finish(stats, t);
}

}  // namespace contact

namespace contact {

std::vector<MethodInfo> game_methods() {
  auto entry = [](std::string name, std::string description, FixedStepScheme scheme,
                  GameResolution resolution) {
    const bool spring = resolution == GameResolution::Spring;
    return MethodInfo{
        .name = std::move(name),
        .description = std::move(description),
        .family = "game",
        .fixed_step = true,
        .uses_contact_law = spring,
        .needs = spring ? "dynamics and contact geometry" : "dynamics, contact geometry and an impulse map",
        .can_run = [spring](const Dynamics& scene) { return spring || has_impulse_map(scene); },
        .run =
            [scheme, resolution](const Dynamics& scene, const Method& m, const SolveOptions& span) {
              return run_game(scene,
                              {.dt = m.dt,
                               .scheme = scheme,
                               .resolution = resolution,
                               .persistence = m.persistence,
                               .on_notifications = m.on_notifications},
                              span);
            },
        .settings = {"dt"}};
  };
  using S = FixedStepScheme;
  using R = GameResolution;
  return {entry("game-euler", "explicit Euler at fixed dt, projection + impulse", S::ExplicitEuler,
                R::ProjectionImpulse),
          entry("game-symplectic", "semi-implicit Euler at fixed dt, projection + impulse",
                S::SemiImplicitEuler, R::ProjectionImpulse),
          entry("game-symplectic-projection", "semi-implicit Euler at fixed dt, projection alone",
                S::SemiImplicitEuler, R::Projection),
          entry("game-euler-spring", "explicit Euler at fixed dt, penalty spring force", S::ExplicitEuler,
                R::Spring),
          entry("game-symplectic-spring", "semi-implicit Euler at fixed dt, penalty spring force",
                S::SemiImplicitEuler, R::Spring)};
}

}  // namespace contact
