// rigid_impacts — conservation errors of every method on the 3D scenes, per step and tolerance.
// Scenes (models/rigid/rigid_scenes.hpp) whose bodies all have finite mass, so that the totals
// are conserved: snooker, planet, spinning-box, off-centre, cradle, wedge (rubber-steel is
// left out: the floor takes momentum). Methods (experiments/rigid_methods.hpp) at each game step
// in --dts and each CVODE tolerance in --rtols (atol = rtol / 100).
// Errors at the end of the run, against the start:
//   momentum          |sum p(T) - sum p(0)| / sqrt(2 M E0), M the total mass, E0 the initial
//                     kinetic energy (a scale that stays positive when the momenta cancel)
//   angular momentum  |sum L(T) - sum L(0)| / sum (|p_i(0)| max(|x_i(0)|, r) + |I_i w_i(0)|), about
//                     the origin, with lever arms of at least the ball radius r = 26 mm (so a
//                     head-on scene, whose L is zero, still has a scale)
//   energy            (E + dissipated - E0) / E0 (the ledger's numerical part)
// Outputs in --out (default results/rigid_impacts): conservation.{csv,md,tex},
// conservation.{png,pdf,gp} (largest error over the scenes against the step and the tolerance),
// meta.json; under mpirun the runs are dealt over the ranks. Exit: 0, 1 solver failure, 2 bad input.
#include "contact_ode/analysis/table.hpp"
#include "contact_ode/models/rigid/rigid_scenes.hpp"
#include "experiment.hpp"
#include "figure.hpp"
#include "process.hpp"
#include "progress.hpp"
#include "sweep_setting.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <map>

using namespace contact;
using namespace contact::rigid;

namespace {

constexpr double kFloor = 1e-17;  // errors drawn on a log axis

struct Totals {
  Vec3 p = Vec3::Zero(), L = Vec3::Zero();
};

struct Case {
  std::string scene, method;
  double value;
};

Totals totals(const std::vector<RigidBody>& bodies) {
  Totals t;
  for (const auto& b : bodies) {
    t.p += b.momentum();
    t.L += b.angular_momentum(Vec3::Zero());
  }
  return t;
}

}  // namespace

int program(int argc, char** argv) {
  std::vector<double> dts{1e-4, 1e-5, 1e-6}, rtols{1e-6, 1e-8, 1e-10};
  std::string scenes = "snooker,planet,spinning-box,off-centre,cradle,wedge";
  Experiment app("rigid_impacts",
                 "Momentum, angular momentum and energy errors of every method on the 3D scenes.",
                 "results/rigid_impacts");
  app.add_list("--dts", dts, "game steps [s], comma-separated", cli::positive());
  app.add_list("--rtols", rtols, "CVODE relative tolerances, comma-separated",
               cli::real_in(0, 1, true, true));
  auto names = rigid_scene_names();
  std::erase(names, "rubber-steel");
  app.add("--scene", scenes, "scenes, comma-separated (all finite masses)", cli::one_of(names, true));
  return app.run(argc, argv, [&](OutputSet& files) {
    const double lever = SceneParams{}.radius;
    const auto scene_list = cli::split_list(scenes);
    std::vector<Case> cases;
    for (const auto& name : scene_list)
      for (const auto& method : kRigidMethods)
        for (double v : method_info(method).fixed_step ? dts : rtols) cases.push_back({name, method, v});
    std::vector<PlannedRun> planned;  // a step too small for the work limit: refused before any run
    for (const auto& [s, m, v] : cases)
      planned.push_back({s + " " + m, with_setting(rigid_method(m), v), rigid_scene(s).t_end});
    refuse_dt_beyond_work_limit(planned, "--dts");
    Table table({"scene", "method", "setting", "value", "momentum_error_rel", "angular_momentum_error_rel",
                 "energy_error_rel", "contacts", "rhs_evals"});
    Progress progress("rigid_impacts", cases.size());
    const auto results = app.share(cases.size(), [&](std::size_t i) -> nlohmann::json {
      const auto& [name, method, v] = cases[i];
      const SceneInfo& info = rigid_scene(name);
      const RigidScene scene = info.make({});
      const Totals before = totals(scene.bodies());
      double mass = 0, L_scale = 0;
      for (const auto& b : scene.bodies()) {
        mass += b.inverse_mass > 0 ? 1 / b.inverse_mass : 0.0;
        L_scale += b.momentum().norm() * std::max(b.position.norm(), lever) +
                   (b.angular_momentum(b.position)).norm();
      }
      // The momentum that would carry the initial kinetic energy with the scene's total mass: a scale
      // that is not zero when the bodies' momenta cancel (the box spinning in place).
      const double p_scale = std::sqrt(2 * mass * scene.energy(scene.initial_state()));
      const bool fixed = method_info(method).fixed_step;
      progress.step(fmt::format("{} {} {:g}", name, method, v));
      const RunResult r = require(
          solve(scene, with_setting(rigid_method(method), v), {.t_end = info.t_end, .sample_dt = info.t_end}),
          fmt::format("{} {} ({} = {:g})", name, method, fixed ? "dt" : "rtol", v));
      const Totals after = totals(scene.bodies_at(r.samples.back().y));
      return row_to_json({name, method, std::string(fixed ? "dt" : "rtol"), v,
                          (after.p - before.p).norm() / p_scale, (after.L - before.L).norm() / L_scale,
                          (r.samples.back().energy + r.samples.back().dissipated - r.energy0) / r.energy0,
                          static_cast<long>(r.contacts.size()), r.stats.rhs_evals});
    });
    if (!results) return;  // another MPI rank: its share is done
    // method -> setting value -> largest error over the scenes (momentum, angular momentum, energy)
    std::map<std::string, std::map<double, std::array<double, 3>>> worst;
    for (std::size_t i = 0; i < cases.size(); ++i) {
      const auto row = row_from_json((*results)[i]);
      table.add_row(row);
      auto& w = worst[cases[i].method][cases[i].value];
      for (int q = 0; q < 3; ++q) w[q] = std::max(w[q], std::abs(std::get<double>(row[4 + q])));
    }
    // Three panels side by side: the game methods' errors against the step (bottom axis), the
    // others' against the tolerance (top axis): two axes, never one axis meaning both.
    std::string data, plot = "set multiplot layout 1,3\n";
    std::vector<std::string> blocks;
    for (const auto& [method, by_value] : worst) {
      for (const auto& [v, w] : by_value)
        data += fmt::format("{},{},{},{}\n", v, std::max(w[0], kFloor), std::max(w[1], kFloor),
                            std::max(w[2], kFloor));
      data += "\n\n";
      blocks.push_back(method);
    }
    const char* titles[] = {"momentum", "angular momentum", "energy"};
    for (int q = 0; q < 3; ++q) {
      plot += fmt::format(
          "set title '{}'\nset logscale xyx2\nset format x '10^{{%L}}'\nset format x2 '10^{{%L}}'\nset "
          "format y "
          "'10^{{%L}}'\nset xlabel 'dt [s] (game)'\nset x2label 'rtol (the others)'\nset x2tics\nset xtics "
          "nomirror\n"
          "set grid\nset yrange [1e-17:*]\n{}\nplot ",
          titles[q], q == 0 ? "set key top left font ',8'" : "unset key");
      for (std::size_t b = 0; b < blocks.size(); ++b)
        plot += fmt::format("{}'data.csv' index {} using 1:{} axes {} with linespoints {} title '{}'",
                            b ? ", " : "", b, q + 2, method_info(blocks[b]).fixed_step ? "x1y1" : "x2y1",
                            series_style(b), blocks[b]);
      plot += "\n";
    }
    plot += "unset multiplot";
    files.add_table("conservation", table);
    render({"conservation", data, "set size ratio 1\n" + plot}, files);
    fmt::print("Conservation errors on the 3D scenes\n\n{}", table.to_markdown(3));
  });
}

int main(int argc, char** argv) { return contact::guarded_main("rigid_impacts", argc, argv, program); }
