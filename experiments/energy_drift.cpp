// energy_drift — how much energy each method invents or destroys over long runs: the ball drop with e = 1
// (Hooke k = --k for penalty methods, m = 1 kg, h0 = 1 m) for --bounces rigid bounces, and every rigid scene
// (its dashpots and impulses booked by the ledger), each method at every --dts (fixed-step) or --rtols.
// Energy error: (E + dissipated - E0) / |E0| at every sample (> 0: invented). Drift rate: its least-squares
// slope in t (GSL); verdict "gains"/"loses" when the final error exceeds 1e-10, else "conserves". Outputs in
// --out (default results/energy_drift): drift.{csv,md,tex}, ball_energy_{game,other} and rigid_energy
// .{png,pdf,gp}, meta.json; under mpirun the runs go over the ranks. Exit: 0, 1 solver failure, 2 bad input.
#include "contact_ode/analysis/metrics.hpp"
#include "contact_ode/analysis/table.hpp"
#include "contact_ode/models/rigid/rigid_scenes.hpp"
#include "energy_drift_runs.hpp"
#include "experiment.hpp"
#include "figure.hpp"
#include "process.hpp"
#include "progress.hpp"
#include "sweep_setting.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>

using namespace contact;

namespace {
constexpr double kLogFloor = 1e-17;  // zero errors are drawn here on the log axes
}  // namespace

int program(int argc, char** argv) {
  DriftSettings s;
  Experiment app("energy_drift",
                 "Energy drift of every method over long undamped ball drops and the rigid-body scenes.",
                 "results/energy_drift");
  app.add("--k", s.k, "penalty stiffness of the ball [N/m]", cli::positive());
  app.add("--bounces", s.bounces, "bounces of the rigid ball solution to run", cli::integer_in(1, 10000));
  app.add_list("--dts", s.dts, "ball game steps [s], comma-separated", cli::positive());
  app.add_list("--rtols", s.rtols, "ball relative tolerances, comma-separated",
               cli::real_in(0, 1, true, true));
  app.add_list("--rigid-dts", s.rigid_dts, "rigid-scene game steps [s]", cli::positive());
  app.add_list("--rigid-rtols", s.rigid_rtols, "rigid-scene relative tolerances",
               cli::real_in(0, 1, true, true));
  app.add("--scene", s.scenes, "rigid scenes, comma-separated, 'all' or 'none'",
          cli::some_of(rigid::rigid_scene_names(), true));
  return app.run(argc, argv, [&](OutputSet& files) {
    const std::vector<DriftRun> jobs = drift_runs(s);
    Table table({"system", "method", "setting", "value", "contacts", "final_energy_error_rel",
                 "max_abs_energy_error_rel", "drift_rate_per_s", "drift_rate_sd", "verdict", "rhs_evals"});
    std::map<std::string, Series> ball_figures;     // "game" loops and "other" methods: <= 10 series each
    std::map<std::string, std::string> rigid_rows;  // method -> "index,scene,max error" lines
    Progress progress("energy_drift", jobs.size());
    const auto results = app.share(jobs.size(), [&](std::size_t i) -> nlohmann::json {
      const DriftRun& job = jobs[i];
      const std::string what = fmt::format("{} {} {} = {:g}", job.system, job.method, job.setting, job.value);
      progress.step(what);
      const RunResult r = require(solve(*job.scene, job.settings, job.span), what);
      const EnergyGain d = energy_gain(r);
      std::string curve;  // |energy error| against t, the ball figure's line
      for (std::size_t j = 0; j < d.t.size(); ++j)
        curve += fmt::format("{},{}\n", d.t[j], std::max(std::abs(d.gain[j]), kLogFloor));
      return {{"row", row_to_json({job.system, job.method, job.setting, job.value,
                                   static_cast<long>(r.contacts.size()), d.final_gain,
                                   compute_metrics(r).max_energy_drift, d.rate, d.rate_sd, d.verdict(),
                                   r.stats.rhs_evals})},
              {"curve", curve}};
    });
    if (!results) return;  // another MPI rank: its share is done
    for (std::size_t i = 0; i < jobs.size(); ++i) {
      const DriftRun& job = jobs[i];
      const auto row = row_from_json((*results)[i].at("row"));  // max error: column 6, verdict: 9
      table.add_row(row);
      // The ball figure shows each method at its first setting (the coarsest by default).
      if (job.system == "ball" &&
          (job.setting == "exact" || job.value == (job.setting == "dt" ? s.dts : s.rtols).front())) {
        const auto setting = job.setting == "exact" ? "" : fmt::format(" {}={:g}", job.setting, job.value);
        Series& figure = ball_figures[job.method.starts_with("game") ? "game" : "other"];
        figure.add((*results)[i].at("curve").get<std::string>(),
                   fmt::format("using 1:2 with lines {} lw 2 title '{}{} ({})'", line_colour(figure.count()),
                               job.method, setting, std::get<std::string>(row[9])));
      }
      // The rigid figure shows each method at the coarsest step or the tightest tolerance.
      if (std::string& rows = rigid_rows[job.method];
          job.system != "ball" &&
          job.value == (job.setting == "dt" ? s.rigid_dts.front() : s.rigid_rtols.back()))
        rows += fmt::format("{},{},{}\n", std::count(rows.begin(), rows.end(), '\n'), job.system,
                            std::max(std::get<double>(row[6]), kLogFloor));
    }
    Series rigid_figure;  // scenes are categories: points, no lines between them
    for (const auto& [method, rows] : rigid_rows)
      if (!rows.empty())
        rigid_figure.add(rows, fmt::format("using 1:3:xtic(2) with points {} title '{}'",
                                           series_style(rigid_figure.count()), method));
    files.add_table("drift", table);
    const std::string below = fmt::format("set key outside below\nset yrange [{:g}:*]\n", kLogFloor);
    for (const auto& [group, figure] : ball_figures)
      render(
          {"ball_energy_" + group, figure.data(),
           logy("|E + dissipated - E_0| / E_0") + "set xlabel 't [s]'\n" + below + "plot " + figure.plot()},
          files);
    const std::string rigid_label =
        fmt::format("max |energy error| (dt = {:g}, rtol = {:g})", s.rigid_dts.front(), s.rigid_rtols.back());
    if (!rigid_figure.empty())
      render({"rigid_energy", rigid_figure.data(),
              logy(rigid_label) + "set xtics rotate by -30\nset offsets 0.3, 0.3, 0, 0\n" + below + "plot " +
                  rigid_figure.plot()},
             files);
    fmt::print("Energy drift (ball: e = 1, k = {:g} N/m, {} bounces; rigid scenes)\n\n{}", s.k, s.bounces,
               table.to_markdown());
  });
}

int main(int argc, char** argv) { return contact::guarded_main("energy_drift", argc, argv, program); }
