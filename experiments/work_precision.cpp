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
// Cost: right-hand-side evaluations (fixed-step and game methods: one per stage), wall time and
// CPU time of the solve. The SciPy peer (scipy_peer.hpp: solve_ivp BDF, Radau, LSODA, RK45 with
// restarts at the switches and the analytic Jacobian) runs the ball at the same tolerances.
// Settings: adaptive rtol = 1e-3 .. 1e-9 (atol = rtol / 100); fixed dt halved --halvings times
// from 1/16 of a contact's duration (w dt = pi/16: 2.0e-3 s for the ball, 4.4e-5 s for the chain).
// Outputs in --out (default results/work_precision): work_precision.{csv,md,tex},
// {ball,chain}_{rhs,time}.{png,pdf,gp}, meta.json. Exit codes: 0, 1 solver failure, 2 bad input.
#include "contact_ode/analysis/cpu_time.hpp"
#include "contact_ode/analysis/table.hpp"
#include "experiment.hpp"
#include "figure.hpp"
#include "problems.hpp"
#include "process.hpp"
#include "progress.hpp"
#include "scipy_peer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

using namespace contact;

namespace {

constexpr double kFloor = 1e-16;

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
  app.add("--integrators", integrators, "penalty integrators, comma-separated or 'all'",
          cli::some_of(integrator_names()));
  app.add("--problems", problems, "ball, chain or both, comma-separated",
          cli::one_of({"ball", "chain"}, true));
  return app.run(argc, argv, [&](OutputSet& files) {
    const auto chosen = cli::chosen(integrators, integrator_names());
    const auto problem_list = cli::split_list(problems);
    const std::vector<double> tols = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9};

    std::vector<Problem> problems_run;
    for (const auto& name : problem_list)
      problems_run.push_back(name == "ball" ? ball_problem(k, 1.5) : chain_problem(balls, chain_k));
    const std::vector<WorkJob> jobs = work_precision_jobs(problems_run, chosen, tols, halvings);

    Table table({"problem", "paradigm", "integrator", "setting", "value", "error", "rhs_evals", "wall_time_s",
                 "cpu_time_s"});
    std::map<std::string, std::map<std::string, std::string>>
        series;  // problem -> series label -> "cost,time,error" lines
    Progress progress("work_precision", jobs.size());
    for (const auto& job : jobs) {
      progress.step(fmt::format("{} {} {} {}={:g}", job.problem->name, job.paradigm, job.integrator,
                                job.setting, job.value));
      const double cpu0 = cpu_seconds();
      const RunResult r = require(solve(*job.problem->model, job.method,
                                        {.t_end = job.problem->t_end, .sample_dt = job.problem->t_end}),
                                  fmt::format("{} {} {} ({} = {:g})", job.problem->name, job.paradigm,
                                              job.integrator, job.setting, job.value));
      const double cpu = cpu_seconds() - cpu0;
      const bool rigid = job.paradigm == "game" || job.paradigm == "event";
      const double err = job.problem->error(r, rigid);
      table.add_row({job.problem->name, job.paradigm, job.integrator, job.setting, job.value, err,
                     r.stats.rhs_evals, r.stats.wall_time_s, cpu});
      series[job.problem->name][job.paradigm + " " + job.integrator] += fmt::format(
          "{},{},{}\n", std::max(r.stats.rhs_evals, 1L), std::max(cpu, 1e-7), std::max(err, kFloor));
    }
    const std::string missing = scipy_peer_missing();
    if (!missing.empty())
      fmt::print(stderr, "work_precision: the SciPy peer is skipped: missing {}\n", missing);
    for (const Problem& ball : problems_run)
      for (const auto& [p, err] : ball.name == "ball" && missing.empty() ? scipy_on_ball(ball, k, tols)
                                                                         : std::vector<ScoredScipyRun>{}) {
        table.add_row({"ball", "scipy", p.method, "rtol", p.rtol, err, p.nfev, std::nan(""), p.cpu_s});
        series["ball"]["scipy " + p.method] +=
            fmt::format("{},{},{}\n", p.nfev, p.cpu_s, std::max(err, kFloor));
      }
    files.add_table("work_precision", table);
    for (const auto& [problem, lines] : series)
      for (const auto& [cost, column, label] :
           {std::tuple{std::string("rhs"), 1, std::string("right-hand-side evaluations")},
            std::tuple{std::string("time"), 2, std::string("CPU time per solve [s]")}}) {
        Series figure;
        int i = 0;  // colours and point types cycle at different periods, so no two series look alike
        for (const auto& [name, rows] : lines) {
          figure.add(rows, fmt::format("using {}:3 with linespoints lc {} pt {} title '{}'", column,
                                       i % 8 + 1, i % 13 + 1, name));
          ++i;
        }
        render({problem + "_" + cost, figure.data(),
                loglog(label, "error") + "set key outside right font ',8'\nplot " + figure.plot()},
               files);
      }
    fmt::print("Work-precision: {} runs (ball k = {:g} N/m; chain of {} balls, k = {:g} N/m)\n\n{}",
               jobs.size(), k, balls, chain_k, table.to_markdown(3));
  });
}

int main(int argc, char** argv) { return contact::guarded_main("work_precision", argc, argv, program); }
