// convergence_dt — observed orders of every integrator on the penalty ball drop, with and without
// the contact switches located.
// Problem: m = 1 kg dropped from h0 = 1 m onto a Hooke spring (k = --k), g = 9.81 m/s^2, to
// t = --t-final (1.5 s: two contacts, four force kinks). The reference is the closed-form
// solution (analysis/references.hpp, hooke_ball_state). Error norm: the scaled maximum norm
// max(|x - x*| / h0, |v - v*| / V) at t-final, V = sqrt(2 g h0) the impact speed.
// Fixed-step runs (every integrator that can run at a fixed step): dt = --dt-max / 2^j,
// j = 0..--halvings. Adaptive runs (every error-controlled integrator): rtol = 10^-3 .. --tol-min,
// one per decade, atol = rtol / 100.
// "unlocated": the modes follow the state inside each step, so steps straddle the kink of
// F = k max(-x, 0) (a jump in dF/dx): a method of order p > 2 drops to order 2.
// "located": each switch is a root; the integrator stops and restarts there, and recovers p.
// Observed order between rows: log(err_prev / err) / log(dt_prev / dt) (or of tolerances). The
// fitted order is the least-squares log-log slope (GSL) over the five finest rows with
// err > 1e-10 (the asymptotic range, above the floor set by locating roots to 100 ulps
// of t and by dense output).
// Outputs in --out (default results/convergence_dt): fixed_step.{csv,md,tex},
// adaptive.{csv,md,tex}, orders.{csv,md,tex}, fixed_step_errors.{png,pdf,gp},
// adaptive_errors.{png,pdf,gp},
// meta.json. Exit codes: 0, 1 solver failure, 2 bad input.
#include "contact_ode/analysis/fit.hpp"
#include "contact_ode/analysis/table.hpp"
#include "contact_ode/integrators/penalty.hpp"
#include "experiment.hpp"
#include "figure.hpp"
#include "problems.hpp"
#include "process.hpp"
#include "progress.hpp"
#include "sweep_setting.hpp"

#include <fmt/format.h>

#include <cmath>

using namespace contact;

namespace {

constexpr double kRoundOff = 1e-10;  // below: root-location (100 ulps of t) and dense-output error
constexpr std::size_t kFitRows = 5;

}  // namespace

int program(int argc, char** argv) {
  double k = 1e4, t_final = 1.5, dt_max = 2e-3, tol_min = 1e-10;
  long halvings = 6;
  std::string integrators = "all";
  Experiment app("convergence_dt",
                 "Observed orders of every integrator on the penalty ball drop, with and without located "
                 "contact switches.",
                 "results/convergence_dt");
  app.add("--k", k, "spring stiffness [N/m]", cli::positive());
  app.add("--t-final", t_final, "time at which the error is measured [s]", cli::positive());
  app.add("--dt-max", dt_max, "largest fixed step [s]", cli::positive());
  app.add("--halvings", halvings, "fixed steps: dt-max halved this many times", cli::integer_at_least(1));
  app.add("--tol-min", tol_min, "tightest tolerance (adaptive runs go from 1e-3 down to it)",
          cli::real_in(1e-14, 1e-4, false, false));
  app.add("--integrators", integrators, "integrators, comma-separated or 'all'",
          cli::some_of(integrator_names()));
  return app.run(argc, argv, [&](OutputSet& files) {
    if (dt_max >= t_final) {
      throw std::invalid_argument(
          fmt::format("--dt-max: value '{:g}' is not below --t-final = {:g}; accepted range (0, t-final)",
                      dt_max, t_final));
    }
    const Problem ball = ball_problem(k, t_final);

    const auto chosen = cli::chosen(integrators, integrator_names());
    std::vector<double> dts, tols;
    for (long j = 0; j <= halvings; ++j) dts.push_back(dt_max / std::pow(2.0, static_cast<double>(j)));
    for (double tol = 1e-3; tol >= tol_min * (1 - 1e-9); tol /= 10) tols.push_back(tol);
    std::size_t runs = 0;
    for (const auto& name : chosen)
      runs += 2 * ((integrator_info(name).fixed_step_capable ? dts.size() : 0) +
                   (integrator_info(name).adaptive ? tols.size() : 0));

    Table fixed({"integrator", "events", "dt_s", "error", "observed_order", "rhs_evals"});
    Table adaptive({"integrator", "events", "rtol", "error", "observed_order", "rhs_evals"});
    std::map<std::pair<std::string, bool>, std::vector<ConvergencePoint>> fixed_points, adaptive_points;
    Progress progress("convergence_dt", runs);
    auto run = [&](const std::string& name, bool located, bool is_fixed, double step) {
      const char* events = located ? "located" : "unlocated";
      progress.step(fmt::format("{} {} {:g}", name, events, step));
      PenaltyOptions o{.locate_switches = located};
      o.integrator.method = name;
      o.integrator.max_steps = 10000000;
      o.integrator = with_setting(o.integrator, is_fixed, step);
      const RunResult r = require(run_penalty(*ball.model, o, {.t_end = t_final, .sample_dt = t_final}),
                                  fmt::format("{} ({} {:g})", name, is_fixed ? "dt" : "rtol", step));
      const double err = ball.error(r, false);
      auto& points = (is_fixed ? fixed_points : adaptive_points)[{name, located}];
      const double order =
          points.empty() ? std::nan("") : observed_order(points.back().step, points.back().error, step, err);
      points.push_back({step, err, r.stats.rhs_evals});
      (is_fixed ? fixed : adaptive).add_row({name, std::string(events), step, err, order, r.stats.rhs_evals});
    };
    for (const auto& name : chosen)
      for (bool located : {false, true}) {
        if (integrator_info(name).fixed_step_capable)
          for (double dt : dts) run(name, located, true, dt);
        if (integrator_info(name).adaptive)
          for (double tol : tols) run(name, located, false, tol);
      }

    Table orders({"integrator", "theoretical_order", "fixed_order_unlocated", "fixed_order_located",
                  "tol_exponent_unlocated", "tol_exponent_located", "rhs_evals_tightest_unlocated",
                  "rhs_evals_tightest_located"});
    auto order_of = [](const auto& map, const std::string& name, bool located) {
      const auto it = map.find({name, located});
      return it == map.end() ? std::nan("") : fitted_order(it->second, kRoundOff, kFitRows);
    };
    auto tightest_cost = [&](const std::string& name, bool located) {
      const auto it = adaptive_points.find({name, located});
      return it == adaptive_points.end() ? 0L : it->second.back().cost;
    };
    for (const auto& name : chosen)
      orders.add_row({name, static_cast<long>(integrator_info(name).order),
                      order_of(fixed_points, name, false), order_of(fixed_points, name, true),
                      order_of(adaptive_points, name, false), order_of(adaptive_points, name, true),
                      tightest_cost(name, false), tightest_cost(name, true)});

    // One figure per sweep: located solid, unlocated dashed, one colour per integrator.
    auto figure = [](const std::string& name, const std::string& xlabel, const auto& points) {
      Series series;
      int colour = 0;
      for (const auto& [key, pts] : points) {
        std::string rows;
        for (const auto& p : pts) rows += fmt::format("{},{}\n", p.step, p.error);
        // Keys come in (name, unlocated), (name, located) pairs: one colour per integrator.
        colour += key.second ? 0 : 1;
        series.add(rows, fmt::format("using 1:2 with linespoints lc {} dt {} title '{}{}'", colour,
                                     key.second ? 1 : 2, key.first, key.second ? " (located)" : ""));
      }
      return Figure{
          name, series.data(),
          loglog(xlabel, "error at t_{final}") + "set key outside right font ',8'\nplot " + series.plot()};
    };
    files.add_table("fixed_step", fixed);
    files.add_table("adaptive", adaptive);
    files.add_table("orders", orders);
    if (!fixed_points.empty()) render(figure("fixed_step_errors", "dt [s]", fixed_points), files);
    if (!adaptive_points.empty()) render(figure("adaptive_errors", "rtol", adaptive_points), files);
    fmt::print("Observed orders on the penalty ball drop (k = {:g} N/m, error at t = {:g} s)\n\n{}", k,
               t_final, orders.to_markdown(3));
  });
}

int main(int argc, char** argv) { return contact::guarded_main("convergence_dt", argc, argv, program); }
