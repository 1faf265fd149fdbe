// work_precision — error against cost for every integrator and all three paradigms, on the ball
// drop and on the N-ball chain.
// Ball: m = 1 kg from h0 = 1 m, e = 1, Hooke spring k = --k; error at t = 1.5 s (two contacts).
// Chain: --balls equal balls (0.1 kg, touching), striker at 1 m/s from 1 cm, Hooke springs
// k = --chain-k; error once the striker has arrived and three pair contact times per ball have
// passed (0.031 s for 10 balls at 1e6 N/m).
// Each paradigm is measured against the exact solution of its own model:
//   penalty (every integrator) and game-spring  -> the spring model: for the ball the closed form
//     (hooke_ball_state); for the chain CVODE BDF at rtol 1e-12, atol 1e-14, switches located;
//   game (projection + impulse) and event-driven -> the rigid model: for the ball the closed
//     form (rigid_ball_state); for the chain the sequential-impulse limit (the last ball leaves at
//     the striker's speed, the rest stand still).
// Error norm: ball max(|x - x*| / h0, |v - v*| / V); chain max_i |v_i - v_i*| / v0. Errors are
// floored at 1e-16 for the log plots (event-driven chain impulses are exact).
// Cost: right-hand-side evaluations (fixed-step and game methods: one per stage) and wall time.
// Settings: adaptive rtol = 1e-3 .. 1e-9 (atol = rtol / 100); fixed dt halved --halvings times
// from 1/16 of a contact's duration (w dt = pi/16: 2.0e-3 s for the ball, 4.4e-5 s for the chain).
// Outputs in --out (default results/work_precision): work_precision.{csv,md,tex},
// {ball,chain}_{rhs,time}.{png,pdf,gp}, meta.json. Exit codes: 0, 1 solver failure, 2 bad input.
#include "contact_ode/analysis/references.hpp"
#include "contact_ode/analysis/table.hpp"
#include "contact_ode/integrators/event_driven.hpp"
#include "contact_ode/integrators/game_step.hpp"
#include "contact_ode/integrators/penalty.hpp"
#include "contact_ode/models/ball_chain.hpp"
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
#include <functional>
#include <iostream>
#include <map>

using namespace contact;

namespace {

constexpr double kFloor = 1e-16;

struct Job {
  std::string problem, paradigm, integrator, setting;
  double value;
  std::function<RunResult()> run;
};

}  // namespace

int program(int argc, char** argv) {
  double k = 1e4, chain_k = 1e6;
  long balls = 10, halvings = 4;
  std::string integrators = "all", problems = "ball,chain";
  Experiment app(
      "work_precision",
      "Error against cost for every integrator and paradigm, on the ball drop and the N-ball chain.",
      "results/work_precision");
  app.add("--k", k, "ball spring stiffness [N/m]", cli::positive());
  app.add("--chain-k", chain_k, "chain spring stiffness [N/m]", cli::positive());
  app.add("--balls", balls, "balls in the chain", cli::integer_at_least(2));
  app.add("--halvings", halvings, "fixed steps: the largest halved this many times",
          cli::integer_at_least(0));
  auto names = integrator_names();
  names.insert(names.begin(), "all");
  app.add("--integrators", integrators, "penalty integrators, comma-separated or 'all'",
          cli::one_of(names, true));
  app.add("--problems", problems, "ball, chain or both, comma-separated",
          cli::one_of({"ball", "chain"}, true));
  return app.run(argc, argv, [&](OutputSet& files) {
    const auto chosen = integrators == "all" ? integrator_names() : cli::split_list(integrators);
    const auto problem_list = cli::split_list(problems);
    const std::vector<double> tols = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9};

    // The two problems: the model, the time of measurement, the fixed steps, and each model's error.
    const double g = 9.81, h0 = 1.0, V = std::sqrt(2 * g * h0), t_ball = 1.5;
    const auto ball = std::make_shared<BallDrop>(BallDropParams{1.0, g, h0, 0.0, 1.0, Hooke{k}});
    BallChainParams cp;
    cp.n = static_cast<std::size_t>(balls);
    cp.law = Hooke{chain_k};
    const auto chain = std::make_shared<BallChain>(cp);
    // Contact durations set the steps: the largest fixed step is 1/16 of a contact (w dt = pi/16),
    // and the chain is measured once the pulse has had three pair contacts per ball to cross it.
    const double ball_contact = hooke_contact(1.0, k, V, g).duration;
    const double chain_contact = hooke_contact(cp.m / 2, chain_k, cp.v0, 0.0).duration;
    const double t_chain = cp.approach / cp.v0 + 3.0 * static_cast<double>(cp.n) * chain_contact;
    auto steps = [&](double largest) {
      std::vector<double> dts;
      for (long j = 0; j <= halvings; ++j) dts.push_back(largest / std::pow(2.0, static_cast<double>(j)));
      return dts;
    };
    // Chain spring reference: CVODE BDF, tight, switches located.
    Vector chain_spring_ref;
    if (std::find(problem_list.begin(), problem_list.end(), "chain") != problem_list.end()) {
      Method reference{.name = "penalty"};
      reference.integrator.rtol = 1e-12;
      reference.integrator.atol = 1e-14;
      reference.integrator.max_steps = 10000000;
      const RunResult r =
          require(solve(*chain, reference, {.t_end = t_chain, .sample_dt = t_chain}), "chain reference");
      chain_spring_ref = r.samples.back().y;
    }
    auto error = [&](const std::string& problem, bool rigid, const RunResult& r) {
      const Vector& y = r.samples.back().y;
      if (problem == "ball") {
        const BallState ref =
            rigid ? rigid_ball_state(h0, 0.0, g, 1.0, t_ball) : hooke_ball_state(1.0, k, h0, 0.0, g, t_ball);
        return std::max(std::abs(y[0] - ref.x) / h0, std::abs(y[1] - ref.v) / V);
      }
      double err = 0;
      for (std::size_t b = 0; b < cp.n; ++b) {
        const auto i = static_cast<Eigen::Index>(2 * b + 1);
        const double ref = rigid ? (b + 1 == cp.n ? cp.v0 : 0.0) : chain_spring_ref[i];
        err = std::max(err, std::abs(y[i] - ref) / cp.v0);
      }
      return err;
    };

    std::vector<Job> jobs;
    for (const auto& problem : problem_list) {
      const MechanicalSystem& model =
          problem == "ball" ? static_cast<const MechanicalSystem&>(*ball) : *chain;
      const double t_end = problem == "ball" ? t_ball : t_chain;
      const SolveOptions span{.t_end = t_end, .sample_dt = t_end};
      const auto dts = steps((problem == "ball" ? ball_contact : chain_contact) / 16);
      auto integrator_options = [](const std::string& name, double value) {
        IntegratorOptions o;
        o.method = name;
        o.max_steps = 10000000;
        return with_setting(o, !integrator_info(name).adaptive, value);
      };
      for (const auto& name : chosen) {
        const bool adaptive = integrator_info(name).adaptive;
        for (double v : adaptive ? tols : dts)
          jobs.push_back({problem, "penalty", name, adaptive ? "rtol" : "dt", v,
                          [&model, span, o = integrator_options(name, v)] {
                            return solve(model, {.name = "penalty", .integrator = o}, span);
                          }});
      }
      for (const auto& [paradigm, method] :
           {std::pair{std::string("game"), std::string("game-symplectic")},
            std::pair{std::string("game-spring"), std::string("game-symplectic-spring")}})
        for (double dt : dts)
          jobs.push_back({problem, paradigm, "semi-implicit-euler", "dt", dt, [&model, span, dt, method] {
                            return solve(model, {.name = method, .dt = dt}, span);
                          }});
      for (const std::string name : {"cvode-bdf", "gsl-rk8pd"})
        for (double tol : tols)
          jobs.push_back(
              {problem, "event", name, "rtol", tol, [&model, span, o = integrator_options(name, tol)] {
                 return solve(model, {.name = "event-ode", .integrator = o}, span);
               }});
      if (problem == "ball")
        jobs.push_back({problem, "event", "exact-flight", "exact", 0.0,
                        [ball, span] { return solve(*ball, {.name = "event-exact"}, span); }});
    }

    Table table(
        {"problem", "paradigm", "integrator", "setting", "value", "error", "rhs_evals", "wall_time_s"});
    std::map<std::string, std::map<std::string, std::string>>
        series;  // problem -> series label -> "cost,time,error" lines
    Progress progress("work_precision", jobs.size());
    for (const auto& job : jobs) {
      progress.step(
          fmt::format("{} {} {} {}={:g}", job.problem, job.paradigm, job.integrator, job.setting, job.value));
      const RunResult r = require(job.run(), fmt::format("{} {} {} ({} = {:g})", job.problem, job.paradigm,
                                                         job.integrator, job.setting, job.value));
      const bool rigid = job.paradigm == "game" || job.paradigm == "event";
      const double err = error(job.problem, rigid, r);
      table.add_row({job.problem, job.paradigm, job.integrator, job.setting, job.value, err,
                     r.stats.rhs_evals, r.stats.wall_time_s});
      series[job.problem][job.paradigm + " " + job.integrator] +=
          fmt::format("{},{},{}\n", std::max(r.stats.rhs_evals, 1L), std::max(r.stats.wall_time_s, 1e-7),
                      std::max(err, kFloor));
    }

    files.add_table("work_precision", table);
    for (const auto& [problem, lines] : series)
      for (const auto& [cost, column, label] :
           {std::tuple{std::string("rhs"), 1, std::string("right-hand-side evaluations")},
            std::tuple{std::string("time"), 2, std::string("wall time [s]")}}) {
        Series figure;
        int i = 0;  // colours and point types cycle at different periods, so no two series look alike
        for (const auto& [name, rows] : lines) {
          figure.add(rows, fmt::format("using {}:3 with linespoints lc {} pt {} title '{}'", column,
                                       i % 8 + 1, i % 13 + 1, name));
          ++i;
        }
        render({problem + "_" + cost, figure.data(),
                fmt::format("set logscale xy\nset format x '10^{{%L}}'\nset format y '10^{{%L}}'\nset xlabel "
                            "'{}'\nset ylabel 'error'\n"
                            "set key outside right font ',8'\nset grid\nplot {}",
                            label, figure.plot())},
               files);
      }
    fmt::print("Work-precision: {} runs (ball k = {:g} N/m; chain of {} balls, k = {:g} N/m)\n\n{}",
               jobs.size(), k, balls, chain_k, table.to_markdown(3));
  });
}

int main(int argc, char** argv) { return contact::guarded_main("work_precision", argc, argv, program); }
