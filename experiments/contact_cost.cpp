// contact_cost — what a penalty contact costs adaptive integrators, explicit and implicit, as the
// spring stiffens: is a resolved contact stiff?
// The ball drop (m = 1 kg, g = 9.81 m/s^2, h0 = 1 m) on a Hooke spring k = --k-min ... --k-max
// (--per-decade points per decade), switches root-located, to t = 1.6 s or, for soft springs, the
// longer time the first contact and the first apex take (first_bounce_window), under each of
// --integrators at rtol = --rtol (atol = rtol / 100). Per run: right-hand sides and steps per
// contact, CPU time per contact (median of 3 to 10 solves within 20 ms), and the first apex's error
// against the closed form (no energy is lost: the apex is h0). A contact lasting pi sqrt(m/k) is
// resolved by every error-controlled code in a number of steps set by the tolerance, not by k: its
// stiffness (the spring's w) is the time scale being followed, so an explicit code is stable at the
// steps its accuracy asks for anyway. The exponents of cost
// against k, fitted by least squares in log-log (GSL) over the whole range, say how flat.
// Under mpirun the (integrator, k) cases are dealt over the ranks.
// Outputs in --out (default results/contact_cost): cost.{csv,md,tex}, exponents.{csv,md,tex},
// rhs.{png,pdf,gp}, cpu.{png,pdf,gp}, meta.json. Exit codes: 0, 1 solver failure, 2 bad input.
#include "contact_ode/analysis/cpu_time.hpp"
#include "contact_ode/analysis/fit.hpp"
#include "contact_ode/analysis/table.hpp"
#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/models/ball_drop.hpp"
#include "experiment.hpp"
#include "figure.hpp"
#include "problems.hpp"
#include "process.hpp"
#include "progress.hpp"
#include "sweep_setting.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

using namespace contact;

int program(int argc, char** argv) {
  double k_min = 1e2, k_max = 1e10, rtol = 1e-8;
  long per_decade = 2;
  std::string integrators = "cvode-bdf,cvode-adams,arkode-dirk,arkode-erk,gsl-rkf45,gsl-rk8pd";
  Experiment app("contact_cost",
                 "Cost per penalty contact against k for explicit and implicit adaptive codes.",
                 "results/contact_cost");
  app.add("--k-min", k_min, "smallest k [N/m]", cli::positive());
  app.add("--k-max", k_max, "largest k [N/m]", cli::positive());
  app.add("--per-decade", per_decade, "points per decade of k", cli::integer_in(1, 100));
  app.add("--rtol", rtol, "relative tolerance (atol = rtol / 100)", cli::real_in(1e-12, 1e-2, true, true));
  app.add("--integrators", integrators, "adaptive integrators, comma-separated",
          cli::some_of(integrator_names()));
  return app.run(argc, argv, [&](OutputSet& files) {
    require_k_range(k_min, k_max);
    const auto chosen = adaptive_integrators(integrators);
    const std::vector<double> grid = log_grid(k_min, k_max, per_decade);
    const double h0 = 1.0;
    Progress progress("contact_cost", chosen.size() * grid.size());
    const auto results = app.share(chosen.size() * grid.size(), [&](std::size_t i) -> nlohmann::json {
      const std::string& name = chosen[i / grid.size()];
      const double k = grid[i % grid.size()];
      const std::string what = fmt::format("{} at k = {:g}", name, k);
      progress.step(what);
      const Method penalty = penalty_under(name, rtol);
      const BallDropParams p{1.0, 9.81, h0, 0.0, 1.0, Hooke{k}};
      const BallDrop model(p);
      const double t_end = first_bounce_window(p, 1.6);
      RunResult r;
      const CpuTiming cpu = time_cpu_within(
          [&] { r = solve(model, penalty, {.t_end = t_end, .sample_dt = t_end}); }, 3, 10, 0.02);
      require(r, what);
      // An undamped spring never holds the ball, but an integrator's error can: at rtol 5.6e-3 and
      // k = 0.002 N/m (a contact of 138 s, 5 km deep) arkode-erk and gsl-rk8pd lost enough energy
      // to leave the ball below the spring's sag for good, and there is no apex to measure.
      first_bounce(r, p, what, "; tighten --rtol");
      const double contacts = static_cast<double>(r.contacts.size());
      return {{"steps", static_cast<double>(r.stats.steps) / contacts},
              {"rhs", static_cast<double>(r.stats.rhs_evals) / contacts},
              {"cpu", cpu.median / contacts},
              {"apex_error", std::abs(r.apexes.front().gap - h0)}};
    });
    if (!results) return;  // another MPI rank: its share is done
    Table cost({"integrator", "kind", "k_N_per_m", "steps_per_contact", "rhs_per_contact",
                "cpu_s_per_contact", "first_apex_error_m"});
    std::map<std::string, std::vector<ConvergencePoint>> rhs_series, cpu_series;
    std::map<std::string, std::vector<double>> ks, rhs, cpu;
    for (std::size_t i = 0; i < results->size(); ++i) {
      const std::string& name = chosen[i / grid.size()];
      const double k = grid[i % grid.size()];
      const auto& c = (*results)[i];
      const auto get = [&c](const char* key) { return c[key].get<double>(); };
      const std::string kind = integrator_info(name).implicit ? "implicit" : "explicit";
      cost.add_row({name, kind, k, get("steps"), get("rhs"), get("cpu"), get("apex_error")});
      rhs_series[name].push_back({k, get("rhs")});
      cpu_series[name].push_back({k, get("cpu")});
      ks[name].push_back(k);
      rhs[name].push_back(get("rhs"));
      cpu[name].push_back(get("cpu"));
    }
    Table exponents(
        {"integrator", "kind", "rhs_exponent", "rhs_exponent_sd", "cpu_exponent", "rhs_min", "rhs_max"});
    exponents.set_latex_header({"integrator", "kind", "$\\partial\\log n_f/\\partial\\log k$", "sd",
                                "$\\partial\\log t_{\\mathrm{CPU}}/\\partial\\log k$", "min $n_f$",
                                "max $n_f$"});
    for (const auto& name : chosen) {
      const bool enough = ks[name].size() >= 2;
      const double nan = std::nan("");
      const PowerFit r =
          enough ? fit_power_law(ks[name], rhs[name]) : PowerFit{.exponent = nan, .exponent_sd = nan};
      const double c = enough ? fit_power_law(ks[name], cpu[name]).exponent : nan;
      const auto [lo, hi] = std::minmax_element(rhs[name].begin(), rhs[name].end());
      exponents.add_row({name, std::string(integrator_info(name).implicit ? "implicit" : "explicit"),
                         r.exponent, r.exponent_sd, c, *lo, *hi});
    }
    files.add_table("cost", cost);
    files.add_table("exponents", exponents);
    const auto figure = [](const std::string& file, const std::string& ylabel, const auto& series) {
      return convergence_figure(file, "k [N/m]", ylabel, {series.begin(), series.end()}, {});
    };
    render(figure("rhs", "right-hand sides per contact", rhs_series), files);
    render(figure("cpu", "CPU time per contact [s]", cpu_series), files);
    fmt::print("Cost per contact against k (rtol {:g})\n\n{}\nFitted exponents:\n\n{}", rtol,
               cost.to_markdown(3), exponents.to_markdown(3));
  });
}

int main(int argc, char** argv) { return contact::guarded_main("contact_cost", argc, argv, program); }
