// Ball drop, every method, over k: time per run plus the work counters (steps, right-hand-side
// and Jacobian evaluations, Newton iterations) that make methods comparable across machines.
#include "ball_drop_methods.hpp"

#include <benchmark/benchmark.h>

using namespace contact;

namespace {

void BM_BallDrop(benchmark::State& state, const std::string& method) {
  const double k = std::pow(10.0, static_cast<double>(state.range(0)));
  BallDropSettings s;
  s.model.law = make_law("kelvin-voigt", k, s.model.m, s.model.e);
  s.integrator.rtol = 1e-6;
  s.integrator.atol = 1e-9;
  s.sample_dt = s.t_end;  // no dense output: measure the integration
  RunResult r;
  for (auto _ : state) {
    r = run_ball_drop(method, s);
    benchmark::DoNotOptimize(r);
  }
  state.counters["steps"] = static_cast<double>(r.stats.steps);
  state.counters["rhs_evals"] = static_cast<double>(r.stats.rhs_evals);
  state.counters["jac_evals"] = static_cast<double>(r.stats.jac_evals);
  state.counters["newton_iters"] = static_cast<double>(r.stats.newton_iters);
  state.counters["contacts"] = static_cast<double>(r.contacts.size());
  if (!r.ok()) state.SkipWithError(r.message.c_str());
}

}  // namespace

// k = 10^2 ... 10^8 for the methods whose cost depends on k; once for the others.
BENCHMARK_CAPTURE(BM_BallDrop, penalty, std::string("penalty"))->DenseRange(2, 8, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_BallDrop, penalty_dq, std::string("penalty-dq"))->DenseRange(2, 8, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_BallDrop, game_symplectic_spring, std::string("game-symplectic-spring"))->DenseRange(2, 8, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_BallDrop, game_symplectic, std::string("game-symplectic"))->Arg(5)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_BallDrop, event_ode, std::string("event-ode"))->Arg(5)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_BallDrop, event_exact, std::string("event-exact"))->Arg(5)->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
