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
#include "contact_ode/analysis/references.hpp"
#include "contact_ode/analysis/table.hpp"
#include "contact_ode/integrators/penalty.hpp"
#include "contact_ode/models/ball_drop.hpp"
#include "experiment.hpp"
#include "figure.hpp"
#include "output.hpp"
#include "process.hpp"
#include "progress.hpp"
#include "sweep_setting.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <iostream>

using namespace contact;

namespace {

constexpr double kRoundOff = 1e-10;  // below: root-location (100 ulps of t) and dense-output error
constexpr std::size_t kFitRows = 5;

struct Point {
  double step;  // dt or rtol
  double error;
  long rhs_evals;
};

double fitted(const std::vector<Point>& points) {
  std::vector<double> h, err;
  for (const auto& p : points) {
    h.push_back(p.step);
    err.push_back(p.error);
  }
  return fitted_order(h, err, kRoundOff, kFitRows);
}

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
  auto names = integrator_names();
  names.insert(names.begin(), "all");
  app.add("--integrators", integrators, "integrators, comma-separated or 'all'", cli::one_of(names, true));
  return app.run(argc, argv, [&](OutputSet& files) {
    if (dt_max >= t_final) {
      throw std::invalid_argument(
          fmt::format("--dt-max: value '{:g}' is not below --t-final = {:g}; accepted range (0, t-final)",
                      dt_max, t_final));
    }
    const double m = 1.0, g = 9.81, h0 = 1.0, V = std::sqrt(2 * g * h0);
    const BallDrop model({m, g, h0, 0.0, 1.0, Hooke{k}});
    const BallState exact = hooke_ball_state(m, k, h0, 0.0, g, t_final);

    struct Job {
      std::string integrator;
      bool located, fixed;
      double step;
    };
    std::vector<Job> jobs;
    const auto chosen = integrators == "all" ? integrator_names() : cli::split_list(integrators);
    std::vector<double> tols;
    for (double tol = 1e-3; tol >= tol_min * (1 - 1e-9); tol /= 10) tols.push_back(tol);
    for (const auto& name : chosen) {
      const IntegratorInfo& info = integrator_info(name);
      for (bool located : {false, true}) {
        if (info.fixed_step_capable)
          for (long j = 0; j <= halvings; ++j)
            jobs.push_back({name, located, true, dt_max / std::pow(2.0, static_cast<double>(j))});
        if (info.adaptive)
          for (double tol : tols) jobs.push_back({name, located, false, tol});
      }
    }

    Table fixed({"integrator", "events", "dt_s", "error", "observed_order", "rhs_evals"});
    Table adaptive({"integrator", "events", "rtol", "error", "observed_order", "rhs_evals"});
    std::map<std::pair<std::string, bool>, std::vector<Point>> fixed_points, adaptive_points;
    Progress progress("convergence_dt", jobs.size());
    for (const auto& job : jobs) {
      progress.step(
          fmt::format("{} {} {:g}", job.integrator, job.located ? "located" : "unlocated", job.step));
      PenaltyOptions o;
      o.locate_switches = job.located;
      o.integrator.method = job.integrator;
      o.integrator.max_steps = 10000000;
      o.integrator = with_setting(o.integrator, job.fixed, job.step);
      const RunResult r =
          require(run_penalty(model, o, {.t_end = t_final, .sample_dt = t_final}),
                  fmt::format("{} ({} {:g})", job.integrator, job.fixed ? "dt" : "rtol", job.step));
      const auto& y = r.samples.back().y;
      const double err = std::max(std::abs(y[0] - exact.x) / h0, std::abs(y[1] - exact.v) / V);
      auto& points = (job.fixed ? fixed_points : adaptive_points)[{job.integrator, job.located}];
      const double order = points.empty()
                               ? std::nan("")
                               : observed_order(points.back().step, points.back().error, job.step, err);
      points.push_back({job.step, err, r.stats.rhs_evals});
      (job.fixed ? fixed : adaptive)
          .add_row({job.integrator, std::string(job.located ? "located" : "unlocated"), job.step, err, order,
                    r.stats.rhs_evals});
    }

    Table orders({"integrator", "theoretical_order", "fixed_order_unlocated", "fixed_order_located",
                  "tol_exponent_unlocated", "tol_exponent_located", "rhs_evals_tightest_unlocated",
                  "rhs_evals_tightest_located"});
    auto order_of = [](const auto& map, const std::string& name, bool located) {
      const auto it = map.find({name, located});
      return it == map.end() ? std::nan("") : fitted(it->second);
    };
    auto tightest_cost = [&](const std::string& name, bool located) {
      const auto it = adaptive_points.find({name, located});
      return it == adaptive_points.end() ? 0L : it->second.back().rhs_evals;
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
          fmt::format("set logscale xy\nset format x '10^{{%L}}'\nset format y '10^{{%L}}'\nset xlabel '{}'\n"
                      "set ylabel 'error at t_{{final}}'\nset key outside right font ',8'\nset grid\nplot {}",
                      xlabel, series.plot())};
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
