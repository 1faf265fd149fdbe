// engines — MuJoCo, Bullet, ODE and Siconos (integrators/engines), each at its defaults (what users get) and
// tuned to the scene's physics (what it can do), beside event-driven impulses, the penalty ODE, sequential
// impulses, the soft step and Moreau–Jean, on the scenes of engine_scenes() (problems.hpp: a drop, a head-on
// pair, cradles with and without gaps, a resting column), each scored against its exact rigid answer (the
// soft step's restitution threshold clear of the chains' strikes); first_apex_time_error_s: the bounce's
// timing (apexes are interpolated in free flight, so a step does not round it). Penalty laws: Kelvin–Voigt at
// --k tuned to the scene's e; fixed steps --dt; CPU time: median of --repeats solves (time_solves); omega_dt:
// the stiffest contact's sqrt(k w) dt (unstable explicit above 2). Then the drop at steps --dt x 4 ... / 4:
// apex error, observed order and CPU time per fixed-step method, the work-precision figure (engines and
// Moreau–Jean). Outputs in --out (default results/engines): engines, summary (scored error per scene, a row
// per method), convergence and orders (fitted over the three finest steps) as {csv,md,tex},
// work_precision.{png,pdf,gp}, meta.json. Exit codes: 0, 1, 2 bad input.
#include "contact_ode/analysis/cpu_time.hpp"
#include "contact_ode/analysis/fit.hpp"
#include "contact_ode/analysis/metrics.hpp"
#include "contact_ode/analysis/table.hpp"
#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/models/ball_drop.hpp"
#include "contact_ode/models/scene_registry.hpp"
#include "experiment.hpp"
#include "figure.hpp"
#include "problems.hpp"
#include "process.hpp"
#include "progress.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace contact;

namespace {

const std::vector<std::string> kReferences = {"event-exact", "penalty", "sequential-impulses", "soft-step",
                                              "moreau-jean"};

// "defaults" for an engine as users get it; "tuned" for its settings matched to the scene
// (mujoco-spring, bullet-tuned, ode-spring); ode-quick is ODE's other stepper, at its defaults.
std::string setting(const std::string& method) {
  if (method_info(method).family != "engine") return "project";
  return method.find('-') == std::string::npos || method == "ode-quick" ? "defaults" : "tuned";
}

// CPU time per solve less an engine's world construction, paid once per world (MuJoCo's at its
// default sizes: 7 times its 50 steps of the head-on pair), apart as setup_cpu_s. r: the last run.
CpuTiming time_solves(const Dynamics& scene, const Method& m, const SolveOptions& span, long repeats,
                      RunResult& r) {
  const auto run = [&] { return (r = solve(scene, m, span)).stats.setup_cpu_s; };
  return time_cpu_excluding(run, static_cast<int>(repeats), static_cast<int>(repeats), 0.0);
}

}  // namespace

int program(int argc, char** argv) {
  double dt = 1e-3, k = 1e5;
  long repeats = 5;
  Experiment app("engines",
                 "MuJoCo, Bullet, ODE and Siconos at their defaults and tuned, beside the project's methods.",
                 "results/engines");
  app.add("--dt", dt, "step of every fixed-step method and engine [s]", cli::positive());
  app.add("--k", k, "penalty stiffness of every contact [N/m]", cli::positive());
  app.add("--repeats", repeats, "solves per CPU-time median", cli::integer_in(1, 1000));
  return app.run(argc, argv, [&](OutputSet& files) {
    std::vector<std::string> methods = kReferences;
    for (const auto& m : engine_methods()) methods.push_back(m.name);
    Table table({"scene", "method", "setting", "omega_dt", "status", "contacts", "first_apex_time_error_s",
                 "scored_error", "scored_as", "first_restitution", "max_penetration_m", "energy_drift_rel",
                 "cpu_s_per_sim_s", "cpu_spread_rel", "setup_cpu_s"});
    Progress progress("engines", engine_scenes(k).size() * methods.size());
    for (const ScoredScene& s : engine_scenes(k)) {
      const auto scene = make_scene(s.scene, s.params, "kelvin-voigt");
      double w = 0;
      for (std::size_t i = 0; i < scene->contact_count(); ++i)  // the stiffest contact's w: omega_dt
        w = std::max(w, dynamic_cast<const NormalImpulses&>(*scene).inverse_mass(i, scene->initial_state()));
      for (const auto& name : methods) {
        progress.step(fmt::format("{}, {}", s.name, name));
        if (!method_info(name).can_run(*scene)) continue;
        Method method{.name = name, .dt = dt};
        if (s.scene == "ball-chain") method = clear_of_restitution_threshold(method, s.params.at("v0"));
        const SolveOptions span{.t_end = s.t_end, .sample_dt = s.t_end / 100};
        RunResult r;  // the timed solves' own result (every method here is deterministic)
        const CpuTiming cpu = time_solves(*scene, method, span, repeats, r);
        const bool ok = report(r, fmt::format("engines: {}, {}", s.name, name));
        const RunMetrics m = compute_metrics(r);
        const double nan = std::nan("");
        table.add_row({s.name, name, setting(name), std::sqrt(k * w) * dt, std::string(to_string(r.status)),
                       static_cast<long>(m.contacts),
                       r.apexes.empty() ? nan : std::abs(r.apexes.front().t - s.first_apex_time),
                       ok ? s.error(r, method_info(name).uses_contact_law) : nan, s.scored_as,
                       m.first_restitution, ok ? m.max_penetration : nan, ok ? m.max_energy_drift : nan,
                       cpu.median / s.t_end, (cpu.max - cpu.min) / cpu.median, cpu.left_out});
      }
    }
    files.add_table("engines", table);
    files.add_table("summary", pivot(table, "method", {"setting"}, "scene", "scored_error"));

    // The drop's work-precision: the largest first-apex error over five drop heights in [1, 1.1] m
    // (drawn once, seeded: the impact's phase in the step varies, so that no step is lucky), and
    // the CPU time per solve from 1 m (time_solves), against the step.
    Table conv({"method", "setting", "dt_s", "apex_error_m", "cpu_s", "setup_cpu_s"}),
        orders({"method", "setting", "observed_order"});
    Series series;
    std::mt19937 draw(2026);
    std::vector<std::unique_ptr<Dynamics>> drops;
    for (int j = 0; j < 5; ++j) {
      const double h0 = j ? 1 + 0.1 * std::generate_canonical<double, 53>(draw) : 1.0;
      drops.push_back(make_scene("ball-drop", {{"e", 0.8}, {"k", k}, {"h0", h0}}, "kelvin-voigt"));
    }
    for (const auto& name : methods) {
      if (!method_info(name).fixed_step) continue;
      std::vector<double> steps, errors;
      std::string rows;
      for (double h : {4 * dt, 2 * dt, dt, dt / 2, dt / 4}) {
        const Method method{.name = name, .dt = h};
        const SolveOptions span{.t_end = 1.2, .sample_dt = 0.1};
        RunResult first;  // the first drop's, timed
        const CpuTiming cpu = time_solves(*drops[0], method, span, repeats, first);
        double err = 0;
        for (std::size_t j = 0; j < drops.size(); ++j) {  // NaN as soon as one drop does not bounce
          const double e = first_apex_error(dynamic_cast<const BallDrop&>(*drops[j]).params(),
                                            j ? solve(*drops[j], method, span) : first);
          err = std::isnan(e) ? e : std::max(err, e);
          if (std::isnan(err)) break;
        }
        // A step at which some drop does not bounce (Bullet's defaults) is a row without an error.
        conv.add_row({name, setting(name), h, err, cpu.median, cpu.left_out});
        if (!std::isfinite(err)) continue;
        steps.push_back(h);
        errors.push_back(err);
        rows += fmt::format("{},{}\n", cpu.median, std::max(err, 1e-12));
      }
      orders.add_row({name, setting(name), fitted_order(steps, errors, 1e-12, 3)});
      // The figure: the engines and Moreau–Jean (eight series); the rest are in the tables.
      if (!rows.empty() && (setting(name) != "project" || name == "moreau-jean"))
        series.add(rows, fmt::format("using 1:2 with linespoints title '{}'", name));
    }
    files.add_table("convergence", conv);
    files.add_table("orders", orders);
    render({"work_precision", series.data(),
            loglog("CPU time per solve, no world construction [s]", "max |first apex - e^2 h_0| [m]") +
                "set key outside right font ',8'\nplot " + series.plot()},
           files);
    fmt::print("Engines beside the project's methods (dt = {:g} s, k = {:g} N/m)\n\n{}\n{}", dt, k,
               table.to_markdown(3), orders.to_markdown(3));
  });
}

int main(int argc, char** argv) { return contact::guarded_main("engines", argc, argv, program); }
