// work_precision — error against cost for every integrator and all three paradigms, on the ball
// drop and on the N-ball chain.
// Ball: m = 1 kg from h0 = 1 m, e = 1, Hooke spring k = --k; error at t = 1.5 s (two contacts).
// Chain: --balls equal balls (0.1 kg, touching), striker at 1 m/s from 1 cm, Hooke springs
// k = --chain-k; error once the striker has arrived and three pair contact times per ball have
// passed (0.031 s for 10 balls at 1e6 N/m).
// Two errors per run. Physical (the figures' and the headline): every paradigm against the rigid
// body the tutorial's contact stands for — the ball's closed form with e = 1 (rigid_ball_state), the
// chain's sequential-impulse limit (the last ball leaves at the striker's speed) — so a penalty
// spring's modelling error (its contact lasts pi sqrt(m/k)) counts. Model (the second view): each
// paradigm against its own model's exact solution — spring runs against the Hooke closed form or
// CVODE BDF at rtol 1e-12; game and event-driven runs against the rigid one.
// Error norm: ball max(|x - x*| / h0, |v - v*| / V); chain max_i |v_i - v_i*| / v0; exact zeros
// are drawn at 1e-16 (log axes). Cost: right-hand sides, wall time of the first solve, and CPU time
// per solve: median (and range) of 3 to --repeats solves, as many as fit in 10 ms. The SciPy peer
// (scipy_peer.hpp: solve_ivp BDF, Radau, LSODA, RK45, restarted at the switches, analytic
// Jacobian) runs the ball at the same tolerances, timed the same way.
// Settings: adaptive rtol = 1e-3 .. 1e-9 (atol = rtol / 100); fixed dt halved --halvings times
// from 1/16 of a contact's duration (w dt = pi/16: 2.0e-3 s for the ball, 4.4e-5 s for the chain).
// A failed run (explicit Euler's growing energy on a long chain) is a row with its status, no
// error and no point; its line goes to stderr. Under mpirun the runs are dealt over the ranks.
// Outputs in --out (default results/work_precision): work_precision.{csv,md,tex}, per problem the
// panels (work_panels) {ball,chain}_{explicit,implicit,paradigms,peers}.{png,pdf,gp} of error
// (work_panel_axis) against CPU time, meta.json. Exit codes: 0, 1 solver failure, 2 bad input.
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
constexpr double kBudget = 0.01;  // CPU s of timed solves per point, ours and SciPy's (spread: 1-10 %)
}  // namespace

int program(int argc, char** argv) {
  double k = 1e4, chain_k = 1e6;
  long balls = 10, halvings = 4, repeats = 10;
  std::string integrators = "all", problems = "ball,chain";
  Experiment app(
      "work_precision",
      "Error against cost for every integrator and paradigm, on the ball drop and the N-ball chain.",
      "results/work_precision");
  app.add("--k", k, "ball spring stiffness [N/m]", cli::positive());
  app.add("--chain-k", chain_k, "chain spring stiffness [N/m]", cli::positive());
  // Span and state grow with the chain: 10 balls 4 s, 50 32 s, 100 over 8 min (1000 were accepted).
  app.add("--balls", balls, "balls in the chain (cost grows faster than balls^2)", cli::integer_in(2, 50));
  app.add("--halvings", halvings, "fixed steps: the largest halved this many times",
          cli::integer_at_least(0));
  app.add("--repeats", repeats, "most solves timed per run (CPU median)", cli::integer_in(3, 1000));
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

    Progress progress("work_precision", jobs.size());
    const auto results = app.share(jobs.size(), [&](std::size_t i) -> nlohmann::json {
      const WorkJob& job = jobs[i];
      const std::string what = fmt::format("{} {} {} ({} = {:g})", job.problem->name, job.paradigm,
                                           job.integrator, job.setting, job.value);
      progress.step(what);
      RunResult r;
      const CpuTiming cpu = time_cpu_within(
          [&] {
            r = solve(*job.problem->model, job.method,
                      {.t_end = job.problem->t_end, .sample_dt = job.problem->t_end});
          },
          3, static_cast<int>(repeats), kBudget);
      const bool ok = report(r, what), rigid = job.paradigm == "game" || job.paradigm == "event";
      const double nan = std::nan(""), physical = ok ? job.problem->error(r, true) : nan,
                   model = ok ? job.problem->error(r, rigid) : nan;
      return {physical, model,   r.stats.rhs_evals, r.stats.wall_time_s, cpu.median,
              cpu.min,  cpu.max, cpu.repeats,       to_string(r.status)};
    });
    if (!results) return;  // another MPI rank: its share is done
    Table table({"problem", "paradigm", "integrator", "setting", "value", "error_physical", "error_model",
                 "rhs_evals", "wall_time_s", "cpu_time_s", "cpu_min_s", "cpu_max_s", "repeats", "status"});
    // problem -> panel -> series label -> "cpu,error" lines
    std::map<std::string, std::map<std::string, std::map<std::string, std::string>>> panels;
    const auto add = [&](const std::string& problem, const std::string& paradigm,
                         const std::string& integrator, const std::vector<Table::Cell>& row, double cpu,
                         double physical, double model) {
      table.add_row(row);
      if (std::isnan(physical)) return;  // a failed run: no point
      for (const auto& panel : work_panels(paradigm, integrator))
        panels[problem][panel][paradigm + " " + integrator] += fmt::format(
            "{},{}\n", cpu, std::max(work_panel_axis(problem, panel).physical ? physical : model, kFloor));
    };
    for (std::size_t i = 0; i < jobs.size(); ++i) {
      const WorkJob& job = jobs[i];
      const auto& r = (*results)[i];
      std::vector<Table::Cell> row{job.problem->name, job.paradigm, job.integrator, job.setting, job.value};
      for (auto& cell : row_from_json(r)) row.push_back(std::move(cell));
      add(job.problem->name, job.paradigm, job.integrator, row, r[4], r[0], r[1]);  // cpu, errors
    }
    for (const Problem& ball : problems_run) {
      if (ball.name != "ball") continue;
      std::vector<ScoredScipyRun> peer;
      try {
        peer = scipy_on_ball(ball, k, tols, static_cast<int>(repeats), kBudget);
      } catch (const ScipyPeerMissing& missing) {
        fmt::print(stderr, "work_precision: the SciPy peer is skipped: missing {}\n", missing.what());
      }
      for (const auto& [p, err, physical] : peer)
        add("ball", "scipy", p.method,
            {std::string("ball"), std::string("scipy"), p.method, std::string("rtol"), p.rtol, physical, err,
             p.nfev, std::nan(""), p.cpu_s, p.cpu_min_s, p.cpu_max_s, p.repeats, std::string("success")},
            p.cpu_s, physical, err);
    }
    files.add_table("work_precision", table);
    for (const auto& [problem, by_panel] : panels)
      for (const auto& [panel, lines] : by_panel) {
        Series figure;
        for (const auto& [name, rows] : lines)
          figure.add(rows, fmt::format("using 1:2 with linespoints {} title '{}'",
                                       series_style(figure.count()), name));
        render({problem + "_" + panel, figure.data(),
                loglog("CPU time per solve [s]", work_panel_axis(problem, panel).label) +
                    "set key outside right font ',9'\nplot " + figure.plot()},
               files);
      }
    fmt::print("Work-precision: {} runs (ball k = {:g} N/m; chain of {} balls, k = {:g} N/m)\n\n{}",
               jobs.size(), k, balls, chain_k, table.to_markdown(3));
  });
}

int main(int argc, char** argv) { return contact::guarded_main("work_precision", argc, argv, program); }
