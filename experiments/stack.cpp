// stack — resting contact: a column of --balls balls on the floor under gravity (ball-stack,
// 0.1 kg, r = 5 cm, e = 0.5), released touching and at rest, run for --t-end by every method that
// can run it, at dt = --dt for the fixed-step ones and their defaults otherwise; the penalty
// methods use the law --law at stiffness --k (damping tuned to e).
// Measured: the top ball's sink (penalty's exact static value m g n (n + 1) / (2k) beside it,
// 0 for impulses), the largest overlap, the jitter (RMS of all ball velocities over the second
// half of the run), the energy drift (the ledger's numerical part) and the cost per simulated
// second (right-hand sides; CPU time, the median of 1 to 5 solves, as many as fit in 5 ms, an
// engine's world construction left out: one solve's wall time, the column until it was CPU time,
// counted what the study's other job took from the core). A run that fails is a row with its
// status, and said on stderr: event-driven impulses cannot hold a column that rests from the start.
// Outputs in --out (default results/stack): stack.{csv,md,tex}, cost.{png,pdf,gp} (CPU time per
// simulated second against n), sink.{png,pdf,gp}, meta.json; under mpirun the (n, method) runs are
// dealt over the ranks. Exit codes: 0, 1, 2 bad input.
#include "contact_ode/analysis/cpu_time.hpp"
#include "contact_ode/analysis/metrics.hpp"
#include "contact_ode/analysis/table.hpp"
#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/models/law_registry.hpp"
#include "contact_ode/models/scene_registry.hpp"
#include "experiment.hpp"
#include "figure.hpp"
#include "process.hpp"
#include "progress.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>

using namespace contact;

namespace {

constexpr double kM = 0.1, kG = 9.81, kFloor = 1e-12;  // kFloor: zero drawn here on log axes
constexpr double kBudget = 0.005;                      // CPU s of timed solves a row (1 to 5 solves)

std::vector<std::string> stack_methods() { return methods_for(*make_scene("ball-stack")); }

// RMS of every ball's velocity over the samples in the second half of the run.
double jitter(const RunResult& r) {
  double sum = 0;
  long count = 0;
  for (const auto& s : r.samples)
    if (s.t >= 0.5 * r.samples.back().t)
      for (Eigen::Index j = 1; j < s.y.size(); j += 2, ++count) sum += s.y[j] * s.y[j];
  return count ? std::sqrt(sum / static_cast<double>(count)) : std::nan("");
}

}  // namespace

int program(int argc, char** argv) {
  std::vector<double> balls{1, 2, 4, 8, 16};
  double t_end = 2.0, dt = 1e-3, k = 1e5;
  std::string law = "kelvin-voigt", methods = "all";
  Experiment app("stack",
                 "Resting contact: a column of balls on the floor under every method that can run it.",
                 "results/stack");
  app.add_list("--balls", balls, "column heights, comma-separated", cli::integer_in(1, 1000));
  app.add("--t-end", t_end, "simulated time [s]", cli::positive());
  app.add("--dt", dt, "step of the fixed-step methods [s]", cli::positive());
  app.add("--k", k, "penalty stiffness [N/m]", cli::positive());
  app.add("--law", law, "penalty law (damping tuned to e = 0.5)", cli::one_of(law_names()));
  app.add("--methods", methods, "methods, comma-separated or 'all'", cli::some_of(stack_methods()));
  return app.run(argc, argv, [&](OutputSet& files) {
    // Some methods need a linear law (xpbd): 'all' is every method that can run the
    // column under --law; a named one that cannot is refused in terms of the options.
    const auto runnable = methods_for(*make_scene("ball-stack", {}, law));
    const auto chosen = cli::chosen(methods, runnable);
    for (const auto& name : chosen)
      if (std::find(runnable.begin(), runnable.end(), name) == runnable.end())
        throw std::invalid_argument(
            fmt::format("--methods: value '{}' cannot run with --law {}: it needs {}; "
                        "accepted with it: {}",
                        name, law, method_info(name).needs, fmt::join(runnable, ", ")));
    note_unread_options("stack", app, chosen, {"--dt", "--k", "--law"});
    Table table({"balls", "method", "status", "top_sink_m", "closed_form_sink_m", "max_penetration_m",
                 "jitter_mps", "energy_drift_rel", "rhs_evals", "rhs_per_sim_s", "cpu_s_per_sim_s",
                 "cpu_repeats"});
    std::map<std::string, std::string> cost, sink;  // method -> "n,value" lines
    const std::size_t per_n = chosen.size();
    Progress progress("stack", per_n * balls.size());
    const auto results = app.share(per_n * balls.size(), [&](std::size_t i) -> nlohmann::json {
      const double n = balls[i / per_n];
      const std::string& name = chosen[i % per_n];
      const auto column = make_scene("ball-stack", {{"n", n}, {"m", kM}, {"g", kG}, {"k", k}}, law);
      progress.step(fmt::format("{} balls, {}", n, name));
      RunResult r;  // the timed solves' own (every method here is deterministic)
      const auto run = [&] {
        r = solve(*column, {.name = name, .dt = dt},
                  {.t_end = t_end, .sample_dt = t_end / 200, .progress = progress.follow(t_end)});
        return r.stats.setup_cpu_s;
      };
      const CpuTiming cpu = time_cpu_excluding(run, 1, 5, kBudget);
      const bool ok = report(r, fmt::format("stack: {} balls, {}", n, name));
      const double nan = std::nan(""), top = ok ? -r.samples.back().y[r.samples.back().y.size() - 2] : nan;
      const double exact = method_info(name).uses_contact_law ? kM * kG * n * (n + 1) / (2 * k) : 0.0;
      const RunMetrics m = compute_metrics(r);
      return {{"ok", ok},
              {"row",
               row_to_json({n, name, std::string(to_string(r.status)), top, exact,
                            ok ? m.max_penetration : nan, ok ? jitter(r) : nan, ok ? m.max_energy_drift : nan,
                            r.stats.rhs_evals, static_cast<double>(r.stats.rhs_evals) / t_end,
                            cpu.median / t_end, static_cast<long>(cpu.repeats)})}};
    });
    if (!results) return;  // another MPI rank: its share is done
    for (std::size_t i = 0; i < results->size(); ++i) {
      const auto row = row_from_json((*results)[i].at("row"));  // top sink: column 3, CPU: 10
      table.add_row(row);
      if (!(*results)[i].at("ok").get<bool>()) continue;
      const std::string& name = chosen[i % per_n];
      const double n = balls[i / per_n];
      cost[name] += fmt::format("{},{}\n", n, std::max(std::get<double>(row[10]), 1e-7));
      sink[name] += fmt::format("{},{}\n", n, std::max(std::abs(std::get<double>(row[3])), kFloor));
    }
    files.add_table("stack", table);
    for (const auto& [figure, lines, ylabel] :
         {std::tuple{"cost", &cost, "CPU time per simulated second [s]"},
          std::tuple{"sink", &sink, "|sink of the top ball| [m] (none: 10^{-12})"}}) {
      Series series;
      for (const auto& [name, rows] : *lines)
        series.add(rows, fmt::format("using 1:2 with linespoints title '{}'", name));
      if (!series.empty())
        render({figure, series.data(),
                loglog("balls in the column", ylabel) + "set key outside right font ',8'\nplot " +
                    series.plot()},
               files);
    }
    fmt::print("Resting column (m = {:g} kg, {} law k = {:g} N/m, dt = {:g} s, {:g} s)\n\n{}", kM, law, k, dt,
               t_end, table.to_markdown(3));
  });
}

int main(int argc, char** argv) { return contact::guarded_main("stack", argc, argv, program); }
