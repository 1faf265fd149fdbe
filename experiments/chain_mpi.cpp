// chain_mpi — the N-ball chain (Newton's cradle of --balls touching balls, Hooke k = --k, the
// striker at 1 m/s) as one penalty ODE distributed over the MPI ranks it is started on
// (integrators/distributed: SUNDIALS' parallel vector, CVODE BDF, GMRES with the band-block-
// diagonal preconditioner, boundary balls exchanged between neighbouring ranks).
//   mpirun -np 4 chain_mpi --balls 100000 --out results/chain_mpi
// Run to --t-end: by default the ball-chain scene's span (0.05 s, as every other entry point runs
// the scene), whose cost grows as N; 0 asks for the pulse through the whole chain (the striker's
// approach plus three pair contacts per ball), whose span grows as N and so its cost as N^2 (1e5
// balls: 210 s of simulated time, more than the 1e7 steps a run may take). Rank 0
// writes velocities.csv (every ball's final displacement and velocity), stats.csv (ranks,
// steps, right-hand sides per rank, GMRES iterations, preconditioner setups, wall time, relative
// energy error) and meta.json.
// Progress is shown on a terminal; SIGINT or SIGTERM stops every rank within a few steps.
// Exit codes: 0, 1 solver failure, 2 bad input, 130/143 interrupted.
#include "cli.hpp"
#include "contact_ode/analysis/references.hpp"
#include "contact_ode/analysis/table.hpp"
#include "contact_ode/integrators/run_recorder.hpp"
#include "contact_ode/models/ball_chain.hpp"
#include "contact_ode/models/scene_registry.hpp"
#include "distributed_penalty.hpp"
#include "output.hpp"
#include "process.hpp"
#include "progress.hpp"

#include <fmt/format.h>
#include <mpi.h>

#include <iostream>
#include <optional>

using namespace contact;

namespace {

// MPI for the life of the program (MPI_Finalize even when the run throws).
struct MpiSession {
  MpiSession(int& argc, char**& argv) { MPI_Init(&argc, &argv); }
  ~MpiSession() { MPI_Finalize(); }
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
};

// A rank needs about 1.5 kB per ball it holds: CVODE's BDF history (~12 vectors), GMRES's 31
// Krylov vectors and the preconditioner's two bands of 10 per entry, 74 doubles per entry, 1.2 kB
// per ball (a run of 2e7 balls reached 23.4 GB), and ~100 bytes per ball of the whole chain (its
// state, gathered, and labels). The ranks on one machine share its memory: a run that cannot fit
// is refused before it starts (1e8 balls on one rank filled the machine until the kernel killed
// it). Every rank gets the same answer (the largest need of any machine decides).
std::string memory_refusal(long balls, int size) {
  MPI_Comm node = MPI_COMM_NULL;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const auto held = block_of(static_cast<std::size_t>(balls), rank, size).second;
  double need = 1536.0 * static_cast<double>(held) + 100.0 * static_cast<double>(balls), here = 0, worst = 0;
  MPI_Allreduce(&need, &here, 1, MPI_DOUBLE, MPI_SUM, node);
  MPI_Comm_free(&node);
  const double memory = memory_limit();  // the machine's, or a container's or ulimit's if less
  double ratio = here / memory;
  MPI_Allreduce(&ratio, &worst, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  if (worst <= 1) return {};
  return fmt::format(
      "--balls: value '{}' needs about {:.3g} GB of memory where a process may use {:.3g} GB (~1.5 kB per "
      "ball a rank holds, shared by the ranks on a machine); use more machines or fewer balls",
      balls, worst * memory / 1e9, memory / 1e9);
}

}  // namespace

int program(int argc, char** argv) {
  const MpiSession mpi(argc, argv);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  long balls = 1000;
  double k = 1e6, t_end = ball_chain_scene().t_end, rtol = 1e-8, atol = 1e-12;
  std::string out = "results/chain_mpi";
  cli::Options app("chain_mpi", "The N-ball chain as one penalty ODE distributed over MPI ranks.");
  app.add("--balls", balls, "balls in the chain", cli::integer_in(2, 100'000'000));
  app.add("--k", k, "Hooke stiffness [N/m]", cli::positive());
  app.add("--t-end", t_end,
          "final time [s]; 0: the pulse through the whole chain (approach plus three pair contacts per "
          "ball: its cost grows as balls^2)",
          cli::non_negative());
  app.add("--rtol", rtol, "CVODE relative tolerance", cli::real_in(0, 1, true, true));
  app.add("--atol", atol, "CVODE absolute tolerance [m, m/s]", cli::positive());
  app.add("--out", out, "results folder (written by rank 0)");
  // Every rank parses (each needs the values); rank 0 alone prints the help or the refusal.
  if (const int code = app.parse(argc, argv, rank == 0); code >= 0) return code;
  // --out is replaced whole: only a new or empty folder or an earlier run's (its meta.json names
  // chain_mpi).
  if (const std::string refusal = check_output_dir(out, "chain_mpi"); !refusal.empty()) {
    if (rank == 0) std::cerr << "chain_mpi: " << refusal << "\n";
    return cli::kExitBadInput;
  }
  if (const std::string refusal = memory_refusal(balls, size); !refusal.empty()) {
    if (rank == 0) std::cerr << "chain_mpi: " << refusal << "\n";
    return cli::kExitBadInput;
  }
  const BallChainParams p{.n = static_cast<std::size_t>(balls), .law = Hooke{k}};
  if (t_end == 0)
    t_end =
        p.approach / p.v0 + 3.0 * static_cast<double>(p.n) * hooke_contact(p.m / 2, k, p.v0, 0.0).duration;
  const BallChain chain(p);
  DistributedOptions options;
  options.integrator.rtol = rtol;
  options.integrator.atol = atol;
  options.integrator.max_steps = 10'000'000;
  // Progress by percent of the span on rank 0's terminal. An interrupt on any rank ends the run on
  // every rank at the same step (exit 130, nothing written).
  std::optional<Progress> progress;
  if (rank == 0) progress.emplace("chain_mpi", 100);
  int shown = 0;
  options.progress = [&](double t) {
    for (; progress && shown < static_cast<int>(100 * t / t_end); ++shown)
      progress->step(fmt::format("t = {:.4g} s", t));
  };
  const RunResult r =
      run_distributed(chain, chain, options, {.t_end = t_end, .sample_dt = t_end}, MPI_COMM_WORLD);
  if (r.status == Status::Interrupted) throw Interrupted();
  if (!r.ok()) {
    std::cerr << fmt::format("chain_mpi: rank {}: {} at t = {:.9g} s: {}\n", rank, to_string(r.status),
                             r.t_reached, r.message);
    return cli::kExitFailure;
  }
  if (rank != 0) return 0;
  Table velocities({"ball", "u_m", "v_mps"});
  const Vector& y = r.samples.back().y;
  for (long b = 0; b < balls; ++b) velocities.add_row({b, y[2 * b], y[2 * b + 1]});
  // The undamped chain conserves energy: its error is what the tolerances cost (a run whose
  // tolerances allow anything succeeds with any answer, and this column says so).
  const double e0 = chain.energy(chain.initial_state()), energy_error = (chain.energy(y) - e0) / e0;
  Table stats({"ranks", "balls", "t_end_s", "steps", "rhs_evals_per_rank", "gmres_iters", "precond_setups",
               "wall_time_s", "energy_error_rel"});
  stats.add_row({static_cast<long>(size), balls, t_end, r.stats.steps, r.stats.rhs_evals,
                 r.stats.linear_iters, r.stats.jac_evals, r.stats.wall_time_s, energy_error});
  OutputSet files;
  files.add("velocities.csv", velocities.to_csv());
  files.add("stats.csv", stats.to_csv());
  files.add("meta.json",
            run_meta_json("chain_mpi", app.values_json(), std::vector<std::string>(argv, argv + argc),
                          r.stats.wall_time_s, size));
  files.write(out, "chain_mpi");
  fmt::print(
      "chain_mpi: {} balls on {} ranks to t = {:g} s: {} steps, {} GMRES iterations, {:.3f} s; energy error "
      "{:.2g}\n",
      balls, size, t_end, r.stats.steps, r.stats.linear_iters, r.stats.wall_time_s, energy_error);
  return 0;
}

int main(int argc, char** argv) { return contact::guarded_main("chain_mpi", argc, argv, program); }
