// N-ball chain under CVODE BDF with each linear solver, N = 10 ... 1e5 (dense to 1e3, where
// its N^3 factorisations already take seconds). Ten touching balls' worth of wave: t in
// [0, 2 ms] after the striker (touching ball 1, v0 = 1 m/s) hits; Hooke k = 1e6 N/m, m = 0.1 kg.
// Five repetitions of each case (median, min, max). Counter time_per_sim_s: CPU time per
// simulated second, the number the targets are about.
#include "contact_ode/integrators/penalty.hpp"
#include "contact_ode/models/ball_chain.hpp"

#include "bench_repeated.hpp"

#include <ctime>

using namespace contact;

namespace {

constexpr double kTEnd = 2e-3;

void Chain(benchmark::State& state, LinearSolverKind solver) {
  BallChainParams p;
  p.n = static_cast<std::size_t>(state.range(0));
  p.approach = 0.0;
  p.law = Hooke{1e6};
  const BallChain chain(p);
  PenaltyOptions o;
  SolveOptions o_span;
  o_span.t_end = kTEnd;
  o_span.sample_dt = kTEnd;
  o.integrator.rtol = 1e-6;
  o.integrator.atol = 1e-10;
  o.integrator.linear_solver = solver;
  o.integrator.max_steps = 10000000;
  RunResult r;
  double seconds = 0;
  auto cpu = [] {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
  };
  for (auto _ : state) {
    const double t0 = cpu();
    r = run_penalty(chain, o, o_span);
    seconds += cpu() - t0;
  }
  state.counters["N"] = static_cast<double>(p.n);
  state.counters["steps"] = static_cast<double>(r.stats.steps);
  state.counters["rhs_evals"] = static_cast<double>(r.stats.rhs_evals);
  state.counters["jac_evals"] = static_cast<double>(r.stats.jac_evals);
  state.counters["linear_iters"] = static_cast<double>(r.stats.linear_iters);
  state.counters["restarts"] = static_cast<double>(r.stats.restarts);
  state.counters["events"] = static_cast<double>(r.stats.events);
  state.counters["root_evals"] = static_cast<double>(r.stats.root_evals);
  state.counters["time_per_sim_s"] = seconds / static_cast<double>(state.iterations()) / kTEnd;
  if (!r.ok()) state.SkipWithError(r.message.c_str());
}

// Dense to 1e3, where its N^3 factorisations already take seconds; the others to 1e5.
void up_to_1e3(benchmark::internal::Benchmark* b) { bench::repeated_sizes(b, 1000); }
void up_to_1e5(benchmark::internal::Benchmark* b) { bench::repeated_sizes(b, 100000); }

}  // namespace

BENCHMARK_CAPTURE(Chain, dense, LinearSolverKind::Dense)->Apply(up_to_1e3);
BENCHMARK_CAPTURE(Chain, band, LinearSolverKind::Band)->Apply(up_to_1e5);
BENCHMARK_CAPTURE(Chain, klu, LinearSolverKind::Klu)->Apply(up_to_1e5);
BENCHMARK_CAPTURE(Chain, gmres, LinearSolverKind::Gmres)->Apply(up_to_1e5);
BENCHMARK_CAPTURE(Chain, gmres_band, LinearSolverKind::GmresBandPreconditioned)->Apply(up_to_1e5);

BENCHMARK_MAIN();
