// The fixed-step methods on a column of N balls released touching on the floor (the stack
// experiment's scene: 0.1 kg, Kelvin–Voigt k = 1e5 N/m tuned to e = 0.5), N = 10, 100, 1000: 100
// steps of 0.1 ms (at 1 ms semi-implicit Euler on the springs is past its stability bound,
// 2 sqrt(k / m) dt = 2, from 100 balls on). A step touches each contact a bounded number of times
// (a sweep, a sub-step, a banded factorisation), so its cost should grow as N; bench_report fits
// the exponent. Three costs beyond that hid here: the game loop evaluated the whole scene's energy
// around every contact's impulse (O(N^2) a step: 77 s for 2 s of 1000 balls), the implicit Euler
// spring factorised a dense 2001 x 2001 matrix (over 300 s), and Moreau–Jean's exact LCP solve
// pivoted one contact per dense solve (7 s for the first step of 1000 balls). Five repetitions of
// each case (median, min, max).
#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/models/scene_registry.hpp"

#include "bench_repeated.hpp"

using namespace contact;

namespace {

constexpr double kDt = 1e-4, kTEnd = 0.01;

void Column(benchmark::State& state, const char* method) {
  const auto n = static_cast<double>(state.range(0));
  const auto column = make_scene("ball-stack", {{"n", n}}, "kelvin-voigt");
  const Method m{.name = method, .dt = kDt};
  const SolveOptions span{.t_end = kTEnd, .sample_dt = kTEnd};
  RunResult r;
  for (auto _ : state) r = solve(*column, m, span);
  state.counters["N"] = n;
  state.counters["steps"] = static_cast<double>(r.stats.steps);
  state.counters["rhs_evals"] = static_cast<double>(r.stats.rhs_evals);
  if (!r.ok()) state.SkipWithError(r.message.c_str());
}

void sizes(benchmark::internal::Benchmark* b) { bench::repeated_sizes(b, 1000); }

}  // namespace

BENCHMARK_CAPTURE(Column, game_symplectic, "game-symplectic")->Apply(sizes);
BENCHMARK_CAPTURE(Column, game_symplectic_spring, "game-symplectic-spring")->Apply(sizes);
BENCHMARK_CAPTURE(Column, game_implicit_spring, "game-implicit-spring")->Apply(sizes);
BENCHMARK_CAPTURE(Column, sequential_impulses, "sequential-impulses")->Apply(sizes);
BENCHMARK_CAPTURE(Column, soft_step, "soft-step")->Apply(sizes);
BENCHMARK_CAPTURE(Column, xpbd, "xpbd")->Apply(sizes);
BENCHMARK_CAPTURE(Column, moreau_jean, "moreau-jean")->Apply(sizes);

BENCHMARK_MAIN();
