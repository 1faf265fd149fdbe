// rigid_scenes — the tutorial's 3D scenes (models/rigid/rigid_scenes.hpp: snooker, planet, spinning-box,
// off-centre, rubber-steel, cradle, wedge) resolved by every method of integrators/method_registry.hpp
// that runs them: penalty (a Kelvin–Voigt spring under CVODE BDF, switches root-located), the game's
// semi-implicit Euler with projection + impulse (or projection alone, where the cue ball keeps pushing),
// event-driven impulses at located contacts (lowest contact first, or highest: the rule's order
// dependence) and the engines' time-stepping methods, at --dt. Outputs in --out (default
// results/rigid_scenes): runs.{csv,md,tex} (a row per scene and method), observables.csv (scene, method,
// quantity, value), penetration.{png,pdf,gp}, meta.json; under mpirun the runs are dealt over the ranks.
// Exit codes: 0 success, 1 solver failure, 2 bad input (option, value, accepted range).
#include "contact_ode/models/rigid/rigid_scenes.hpp"
#include "contact_ode/analysis/metrics.hpp"
#include "contact_ode/analysis/rigid_observables.hpp"
#include "contact_ode/analysis/table.hpp"
#include "contact_ode/models/scene_registry.hpp"
#include "experiment.hpp"
#include "figure.hpp"
#include "output.hpp"
#include "process.hpp"
#include "progress.hpp"
#include "sweep_setting.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <map>

using namespace contact;
using namespace contact::rigid;

// The scene the options describe; a refusal of its sizes or masses names their options.
static RigidScene scene_from_options(const std::string& name, const SceneParams& p) {
  try {
    return rigid_scene(name).make(p);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(fmt::format("--m, --radius, --half-extents: {}", e.what()));
  }
}

int program(int argc, char** argv) {
  std::string scenes = "all",
              methods =
                  "penalty,game-symplectic,game-symplectic-projection,event-ode,event-ode-reversed,"
                  "game-implicit-spring,sequential-impulses,soft-step,xpbd,moreau-jean";
  SceneParams p;
  double dt = 1e-4, rtol = 1e-8, atol = 1e-10;
  std::vector<double> half{p.half_extents.x(), p.half_extents.y(), p.half_extents.z()}, quat{1, 0, 0, 0};
  Experiment app(
      "rigid_scenes",
      "The tutorial's 3D scenes resolved by penalty springs, game integration and event-driven impulses.",
      "results/rigid_scenes");
  app.add("--scene", scenes, "scenes, comma-separated or 'all'", cli::some_of(rigid_scene_names()));
  app.add("--method", methods, "methods, comma-separated",
          cli::one_of(methods_for(rigid_scene("snooker").make(p)), true));
  app.add("--m", p.m, "mass of each ball [kg] (planet: the cue ball's)", cli::positive());
  app.add("--radius", p.radius, "radius of each ball [m] (planet: the cue ball's)", cli::positive());
  app.add("--elasticity", p.elasticity,
          "elasticity of the cue ball, striker or lone sphere (cradle: every ball's; rubber-steel: the "
          "floor's; the other bodies' 1); restitution = product of the pair's",
          cli::real_in(0, 1, false, false));
  app.add("--half-extents", half, 3, "the cuboid's half extents [m]", cli::positive());
  app.add("--quaternion", quat, 4, "the cuboid's orientation w x y z (normalised; must be non-zero)",
          cli::finite());
  app.add("--k", p.k, "penalty stiffness [N/m]", cli::positive());
  app.add("--dt", dt, "game step [s]", cli::positive());
  app.add("--rtol", rtol, "CVODE relative tolerance", cli::real_in(0, 1, true, true));
  app.add("--atol", atol, "CVODE absolute tolerance", cli::positive());
  return app.run(argc, argv, [&](OutputSet& files) {
    // Normalised with scaling (stableNormalized): the plain norm of (1e200, ...) overflows to inf and
    // of (1e-200, ...) underflows to 0, though both are fine orientations.
    const Eigen::Vector4d q = Eigen::Vector4d(quat[0], quat[1], quat[2], quat[3]);
    if (q.cwiseAbs().maxCoeff() == 0) {
      throw std::invalid_argument(
          "--quaternion: value '0 0 0 0' has zero norm; accepted: any finite non-zero quaternion");
    }
    p.half_extents = Vec3(half[0], half[1], half[2]);
    const Eigen::Vector4d unit = q.stableNormalized();
    p.orientation = Quat(unit[0], unit[1], unit[2], unit[3]);

    Table runs({"scene", "method", "status", "contacts", "max_penetration_m", "energy_drift_rel", "rhs_evals",
                "wall_time_s"});
    Table observables({"scene", "method", "quantity", "value"});
    const auto scene_list = cli::chosen(scenes, rigid_scene_names());
    for (const auto& name : scene_list) {  // before any run: a ball inside the cuboid is bad input
      require_bodies_apart(scene_from_options(name, p),
                           fmt::format("--radius {:g}, --half-extents {:g}, --quaternion {:g}", p.radius,
                                       fmt::join(half, " "), fmt::join(quat, " ")));
    }
    const auto method_list = cli::split_list(methods);
    std::vector<PlannedRun> planned;
    for (const auto& name : scene_list)
      for (const auto& method : method_list) {
        // (Braced inside the push, GCC 12 warned it uninitialised.)
        Method each{.name = method, .dt = dt, .integrator = {.rtol = rtol, .atol = atol}};
        planned.push_back({fmt::format("{} on {}", method, name), each, rigid_scene(name).t_end});
      }
    refuse_dt_beyond_work_limit(planned);
    Progress progress("rigid_scenes", scene_list.size() * method_list.size());
    const std::size_t per_scene = method_list.size();
    const auto results = app.share(scene_list.size() * per_scene, [&](std::size_t i) -> nlohmann::json {
      const std::string &name = scene_list[i / per_scene], &method = method_list[i % per_scene];
      const SceneInfo& info = rigid_scene(name);
      const RigidScene scene = info.make(p);
      progress.step(name + " " + method);
      const RunResult r = solve(scene, planned[i].method, {.t_end = info.t_end, .sample_dt = info.t_end});
      if (!report(r, fmt::format("rigid_scenes: {} {}", name, method))) return nullptr;
      const RunMetrics m = compute_metrics(r);
      nlohmann::json quantities = nlohmann::json::array();
      for (const auto& [quantity, value] : observe(name, scene, r)) quantities.push_back({quantity, value});
      return {{"row",
               row_to_json({name, method, std::string(to_string(r.status)), static_cast<long>(m.contacts),
                            m.max_penetration, m.max_energy_drift, r.stats.rhs_evals, r.stats.wall_time_s})},
              {"observables", quantities}};
    });
    if (!results) return;  // another MPI rank: its share is done
    int failures = 0;
    std::map<std::string, std::string> penetration;  // method -> "scene index,scene,max penetration" lines
    for (std::size_t i = 0; i < results->size(); ++i) {
      const auto& result = (*results)[i];
      if (result.is_null()) {
        ++failures;
        continue;
      }
      const std::string &name = scene_list[i / per_scene], &method = method_list[i % per_scene];
      const auto row = row_from_json(result.at("row"));  // max penetration: column 4
      penetration[method] +=
          fmt::format("{},{},{}\n", i / per_scene, name, std::max(std::get<double>(row[4]), 1e-12));
      runs.add_row(row);
      for (const auto& obs : result.at("observables"))
        observables.add_row({name, method, obs[0].get<std::string>(), obs[1].get<double>()});
    }
    fmt::print("Rigid scenes (k = {:g} N/m, game dt = {:g} s, rtol = {:g})\n\n{}\n{}", p.k, dt, rtol,
               runs.to_markdown(), observables.to_markdown());
    if (failures > 0) throw std::runtime_error(fmt::format("{} run(s) failed", failures));
    files.add_table("runs", runs);
    files.add("observables.csv", observables.to_csv());
    Series series;
    int point_type = 4;
    for (const auto& [method, rows] : penetration)
      series.add(rows,
                 fmt::format("using 1:3:xtic(2) with points pt {} ps 1.5 title '{}'", point_type++, method));
    render({"penetration", series.data(),
            "set logscale y\nset format y '10^{%L}'\nset ylabel 'largest penetration [m] (none: "
            "10^{-12})'\nset xtics rotate by -30\n"
            "set offsets 0.3, 0.3, 0, 0\nset key outside below\nset grid\nplot " +
                series.plot()},
           files);
  });
}

int main(int argc, char** argv) { return contact::guarded_main("rigid_scenes", argc, argv, program); }
