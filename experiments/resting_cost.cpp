// resting_cost — what a penalty contact at rest costs adaptive integrators, explicit and implicit, as
// the springs stiffen: contact_cost's impact has its spring's motion to follow, a rest has none.
// A column of --balls balls (0.1 kg, r = 5 cm, Kelvin–Voigt damped to e = 0.5) released touching and
// at rest on the floor rings down onto its springs' static sag (by 1 s its transient is below the
// codes' tolerance from k = 1e5 N/m up: the sag within 1.3e-6 of the closed form at rtol 1e-6; a
// softer column rings for longer, 2e-4 off at 1 s at k = 1e4) and then stays there to --t-end. An implicit
// code's steps are then set by its tolerance on a state that no longer moves; an explicit code's are held by
// its stability bound, h |lambda| of order one on the column's fastest mode (|lambda| up to 2 sqrt(k/m)), so
// its right-hand sides per simulated second grow as k^(1/2). For each of --integrators at rtol = --rtol (atol
// = rtol / 100) and k = --k-min ... --k-max (--per-decade): right-hand sides, steps and located roots per
// simulated second, CPU time per simulated second (median of 1 to 10 solves within 20 ms), and the top ball's
// sink against the closed form m g n (n + 1) / (2 k); the exponents of cost against k, fitted by least
// squares in log-log (GSL) over the whole range. Under mpirun the (integrator, k) cases are dealt
// over the ranks. Outputs in --out (default results/resting_cost): cost.{csv,md,tex},
// exponents.{csv,md,tex}, rhs.{png,pdf,gp}, meta.json. Exit codes: 0, 1 solver failure, 2 bad input.
#include "contact_ode/analysis/cpu_time.hpp"
#include "contact_ode/analysis/fit.hpp"
#include "contact_ode/analysis/table.hpp"
#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/models/scene_registry.hpp"
#include "experiment.hpp"
#include "figure.hpp"
#include "process.hpp"
#include "progress.hpp"
#include "sweep_setting.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>

using namespace contact;

namespace {
constexpr double kM = 0.1, kG = 9.81;  // the stack experiment's balls
}

int program(int argc, char** argv) {
  double k_min = 1e5, k_max = 1e8, rtol = 1e-6, t_end = 1.0;
  long per_decade = 1, balls = 4;
  std::string integrators = "cvode-bdf,cvode-adams,arkode-dirk,arkode-erk";
  Experiment app(
      "resting_cost",
      "Cost of a resting column of penalty contacts against k for explicit and implicit adaptive codes.",
      "results/resting_cost");
  app.add("--k-min", k_min, "smallest k [N/m]", cli::positive());
  app.add("--k-max", k_max, "largest k [N/m]", cli::positive());
  app.add("--per-decade", per_decade, "points per decade of k", cli::integer_in(1, 100));
  app.add("--rtol", rtol, "relative tolerance (atol = rtol / 100)", cli::real_in(1e-12, 1e-2, true, true));
  app.add("--balls", balls, "balls in the column", cli::integer_in(1, 1000));
  app.add("--t-end", t_end, "simulated time [s]", cli::real_in(1e-3, 100, true, true));
  app.add("--integrators", integrators, "adaptive integrators, comma-separated",
          cli::some_of(integrator_names()));
  return app.run(argc, argv, [&](OutputSet& files) {
    require_k_range(k_min, k_max);
    const auto chosen = adaptive_integrators(integrators);
    const std::vector<double> grid = log_grid(k_min, k_max, per_decade);
    const double n = static_cast<double>(balls);
    Progress progress("resting_cost", chosen.size() * grid.size());
    const auto results = app.share(chosen.size() * grid.size(), [&](std::size_t i) -> nlohmann::json {
      const std::string& name = chosen[i / grid.size()];
      const double k = grid[i % grid.size()];
      const std::string what = fmt::format("{} at k = {:g}", name, k);
      progress.step(what);
      const Method penalty = penalty_under(name, rtol);
      const auto column =
          make_scene("ball-stack", {{"n", n}, {"m", kM}, {"g", kG}, {"k", k}}, "kelvin-voigt");
      RunResult r;
      const CpuTiming cpu = time_cpu_within(
          [&] { r = solve(*column, penalty, {.t_end = t_end, .sample_dt = t_end}); }, 1, 10, 0.02);
      require(r, what);
      const auto& y = r.samples.back().y;
      return {{"steps", static_cast<double>(r.stats.steps) / t_end},
              {"rhs", static_cast<double>(r.stats.rhs_evals) / t_end},
              {"roots", static_cast<double>(r.stats.events) / t_end},
              {"cpu", cpu.median / t_end},
              {"sink", -y[y.size() - 2]},
              {"exact", kM * kG * n * (n + 1) / (2 * k)}};
    });
    if (!results) return;  // another MPI rank: its share is done
    Table cost({"integrator", "kind", "k_N_per_m", "steps_per_sim_s", "rhs_per_sim_s", "roots_per_sim_s",
                "cpu_s_per_sim_s", "top_sink_m", "closed_form_sink_m"});
    std::map<std::string, std::vector<ConvergencePoint>> series;
    std::map<std::string, std::vector<double>> ks, rhs, cpu;
    const auto kind = [](const std::string& name) {
      return integrator_info(name).implicit ? "implicit" : "explicit";
    };
    for (std::size_t i = 0; i < results->size(); ++i) {
      const std::string& name = chosen[i / grid.size()];
      const double k = grid[i % grid.size()];
      const auto& c = (*results)[i];
      const auto get = [&c](const char* key) { return c[key].get<double>(); };
      cost.add_row({name, std::string(kind(name)), k, get("steps"), get("rhs"), get("roots"), get("cpu"),
                    get("sink"), get("exact")});
      series[name].push_back({k, get("rhs")});
      ks[name].push_back(k);
      rhs[name].push_back(get("rhs"));
      cpu[name].push_back(get("cpu"));
    }
    Table exponents({"integrator", "kind", "rhs_exponent", "rhs_exponent_sd", "cpu_exponent"});
    exponents.set_latex_header({"integrator", "kind", "$\\partial\\log n_f/\\partial\\log k$", "sd",
                                "$\\partial\\log t_{\\mathrm{CPU}}/\\partial\\log k$"});
    for (const auto& name : chosen) {
      const double nan = std::nan("");
      const bool enough = ks[name].size() >= 2;
      const PowerFit f =
          enough ? fit_power_law(ks[name], rhs[name]) : PowerFit{.exponent = nan, .exponent_sd = nan};
      exponents.add_row({name, std::string(kind(name)), f.exponent, f.exponent_sd,
                         enough ? fit_power_law(ks[name], cpu[name]).exponent : nan});
    }
    files.add_table("cost", cost);
    files.add_table("exponents", exponents);
    render(convergence_figure("rhs", "k [N/m]", "right-hand sides per simulated second",
                              {series.begin(), series.end()}, {}),
           files);
    fmt::print(
        "A resting column of {} balls, cost against k (rtol {:g}, {:g} s)\n\n{}\nFitted exponents:\n\n{}",
        balls, rtol, t_end, cost.to_markdown(3), exponents.to_markdown(3));
  });
}

int main(int argc, char** argv) { return contact::guarded_main("resting_cost", argc, argv, program); }
