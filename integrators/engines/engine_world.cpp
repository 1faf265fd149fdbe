#include "engine_world.hpp"

#include "../time_stepping.hpp"
#include "contact_ode/integrators/capabilities.hpp"

#include <fmt/format.h>

#include <cmath>
#include <ctime>
#include <stdexcept>

namespace contact {

std::pair<int, int> EngineScene::bodies(std::size_t c) const {
  const int i = static_cast<int>(c);
  return layout.floor ? std::pair{i - 1, i} : std::pair{i, i + 1};
}

int EngineScene::contact_between(int a, int b) const {
  if (a > b) std::swap(a, b);
  const int c = layout.floor ? b : a;
  if (b != a + 1 || c < 0 || c >= static_cast<int>(restitution.size())) return -1;
  return c;
}

namespace {

// This thread's CPU clock [s]: what the world's construction itself took, whatever other threads
// (a Python user's other solves) do meanwhile. In the study's one-thread processes it is the
// process clock its timings read.
double thread_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

const SphereLine* sphere_line_of(const Dynamics& s) { return dynamic_cast<const SphereLine*>(&s); }

bool can_run_engine(const Dynamics& s) {
  return sphere_line_of(s) && has_impulse_map(s) && has_normal_impulses(s);
}

// A spring setting gives the engine the scene's linear law: every contact must have one.
bool can_run_engine_spring(const Dynamics& s) { return can_run_engine(s) && has_linear_laws(s); }

EngineScene engine_scene(const Dynamics& scene, double dt) {
  const auto* line = sphere_line_of(scene);
  if (!line) throw std::invalid_argument(fmt::format("scene '{}' is not spheres on a line", scene.name()));
  const NormalImpulses& normal = normal_impulses(scene, "engine");
  const ImpulseMap& impulses = impulse_map(scene, "engine");
  EngineScene es{.layout = line->sphere_line(),
                 .centre = {},
                 .velocity = {},
                 .restitution = {},
                 .law = {},
                 .inverse_mass = {},
                 .dt = dt};
  const Vector y = scene.initial_state();
  for (std::size_t b = 0; b < es.layout.mass.size(); ++b) {
    es.centre.push_back(es.layout.rest_centre[b] + y[static_cast<Eigen::Index>(2 * b)]);
    es.velocity.push_back(y[static_cast<Eigen::Index>(2 * b + 1)]);
  }
  for (std::size_t c = 0; c < scene.contact_count(); ++c) {
    es.restitution.push_back(impulses.restitution(c));
    es.law.push_back(normal.linear_law(c));
    es.inverse_mass.push_back(normal.inverse_mass(c, y));
  }
  return es;
}

}  // namespace

MethodInfo engine_method(std::string name, std::string description, bool springs, double working_doubles,
                         EngineFactory make) {
  auto run = [springs, make = std::move(make)](const Dynamics& scene, const Method& m,
                                               const SolveOptions& span) {
    const EngineScene es = engine_scene(scene, m.dt);  // solve() has checked can_run
    // An engine that refuses the scene (MuJoCo's mass below its mjMINVAL, ODE's mass check) fails
    // the run at its first step, as a solver error with the engine's message, like any other of
    // its failures: not an exception out of solve().
    std::unique_ptr<EngineWorld> world;
    std::string refused;
    const double setup_start = thread_cpu_s();
    try {
      world = make(es);
    } catch (const EngineError& failure) {
      refused = failure.what();
    }
    const double setup = thread_cpu_s() - setup_start;
    const ContactGeometry& geo = contact_geometry(scene);
    const NormalImpulses& normal = normal_impulses(scene, "engine");
    const std::size_t nc = scene.contact_count();
    std::vector<double> centre, velocity, impulse(nc, 0.0), approach(nc, 0.0);
    std::vector<bool> pushed(nc, false), closed(nc, false), fresh(nc, false);
    Vector start, at = scene.initial_state();  // at: the state at an impact
    auto to_state = [&](const std::vector<double>& c, const std::vector<double>& v, Vector& y) {
      for (std::size_t b = 0; b < c.size(); ++b) {
        y[static_cast<Eigen::Index>(2 * b)] = c[b] - es.layout.rest_centre[b];
        y[static_cast<Eigen::Index>(2 * b + 1)] = v[b];
      }
    };
    // An event-driven engine's impacts, each booked as it happens, exactly: its Newton's law is an
    // LCP, whose complementarity leaves every contact that takes an impulse J at -e u, u its rate just
    // before, so the impact takes -J (u- + u+) / 2 = -J (1 - e) u / 2 from each. That is Newton's
    // loss for an approach (u < 0) and a gain for a contact the LCP pushes while it parts, where a
    // neighbour's impulse would close it (u > 0): booking approaches alone (impact_losses) left a
    // gapped 8-ball chain at e = 0.1 8e-4 of E0 off.
    double impacts_loss = 0;
    const bool event_driven =
        world && world->report_impacts([&](const std::vector<double>& c, const std::vector<double>& v,
                                           const std::vector<double>& J) {
          to_state(c, v, at);
          for (std::size_t i = 0; i < nc; ++i)
            if (es.inverse_mass[i] * J[i] > kPushNoise)
              impacts_loss -= 0.5 * J[i] * (1 - es.restitution[i]) * geo.gap_rate(i, at);
        });
    auto step = [&](double t, double h, Vector& y, StepReport& report, SolverStats& stats) {
      if (!world) throw SolverFailure(Status::SolverError, t, refused);
      start = y;
      impacts_loss = 0;
      try {
        world->step(h);
      } catch (const EngineError& failure) {
        throw SolverFailure(Status::SolverError, t, failure.what());
      }
      world->read(centre, velocity);
      world->impulses(impulse);
      to_state(centre, velocity, y);
      report.dissipated += impacts_loss;
      bool any_fresh = false;
      for (std::size_t i = 0; i < nc; ++i) {
        report.push[i] = es.inverse_mass[i] * impulse[i];
        const bool pushes = report.push[i] > kPushNoise;
        if (springs && geo.gap(i, y) < 0) {
          // The scene's dashpot at the step's rate (the rectangle rule): its loss, not the engine's.
          const double rate = geo.gap_rate(i, y);
          report.dissipated += h * es.law[i].c * rate * rate;
        }
        fresh[i] = !springs && !event_driven && pushes && !pushed[i];
        any_fresh = any_fresh || fresh[i];
        closed[i] = pushes;
        pushed[i] = pushes;
      }
      stats.rhs_evals += 1;  // one engine step
      if (!any_fresh) return;
      // A time-stepping engine's impacts, booked as the project's own time-stepping methods book
      // theirs: Newton's loss at the gap rate the step began with, and the engine's impulses where
      // contacts that share a body close together. Not at the speed an impulse J implies, J w /
      // (1 + e): an engine's impulse also pushes out what its step let sink (ODE's ERP took the
      // impulse of a plastic landing at 4.4 m/s to 5.3 N s, booking 14.1 J of a 9.81 J drop). A
      // column resting from the start books nothing for the first push that holds it: its gap
      // rates are 0 (at the implied speed it drifted, Siconos' 8-ball column by 1.8e-4 of E0).
      for (std::size_t i = 0; i < nc; ++i) approach[i] = geo.gap_rate(i, start);
      report.dissipated +=
          impact_losses(geo, normal, start, closed, fresh, approach, es.restitution, impulse);
    };
    RunResult r = run_time_stepping(scene, m.name, m.dt, step, span, springs);
    r.stats.setup_cpu_s = setup;
    return r;
  };
  return {
      .name = std::move(name),
      .description = std::move(description),
      .family = "engine",
      .fixed_step = true,
      .uses_contact_law = springs,
      .needs =
          springs
              ? "spheres on a line (SphereLine), an impulse map and normal impulses, with linear penalty laws"
              : "spheres on a line (SphereLine), an impulse map and normal impulses",
      .can_run = springs ? can_run_engine_spring : can_run_engine,
      .run = std::move(run),
      .settings = {"dt"},
      .working_doubles = working_doubles};
}

std::vector<MethodInfo> engine_methods() {
  std::vector<MethodInfo> all;
  auto add = [&all](std::vector<MethodInfo> entries) {
    all.insert(all.end(), entries.begin(), entries.end());
  };
  // Each engine is optional at configure time (integrators/engines/engines.cmake).
#ifdef CONTACT_ODE_WITH_MUJOCO
  add(mujoco_methods());
#endif
#ifdef CONTACT_ODE_WITH_BULLET
  add(bullet_methods());
#endif
#ifdef CONTACT_ODE_WITH_ODE
  add(ode_engine_methods());
#endif
#ifdef CONTACT_ODE_WITH_SICONOS
  add(siconos_methods());
#endif
  (void)add;
  return all;
}

std::string engines_missing() { return CONTACT_ODE_ENGINES_MISSING; }

}  // namespace contact
