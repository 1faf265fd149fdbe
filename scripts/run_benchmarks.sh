#!/usr/bin/env bash
# Builds in Release, runs the Google Benchmark programs (each case repeated: medians and ranges of
# CPU time), the SciPy peer on problem P1 in the same run, the study and the paper (their wall
# time), and writes benchmarks/RESULTS.md (the table the README shows) with every target's
# verdict computed from these measurements, and benchmarks/HISTORY.md (every committed run's
# targets, this one last). Takes about ten minutes on 2 cores.
#   bash scripts/run_benchmarks.sh                 as above
#   bash scripts/run_benchmarks.sh --fresh-build   also times a fresh Release build (about 5 more minutes)
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
load=$(cut -d' ' -f1-3 /proc/loadavg)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"
build_type=$(grep -E '^CMAKE_BUILD_TYPE:' build/CMakeCache.txt | cut -d= -f2)

out=build/benchmark-results
mkdir -p "$out"
echo "run_benchmarks: integrators (the k sweep, the apex target)"
build/benchmarks/bench_integrators --benchmark_filter='-^(P1/|ExactBounces)' \
  --benchmark_out="$out/integrators.json" --benchmark_out_format=json >/dev/null
echo "run_benchmarks: the chain, N = 10 ... 1e5, five times each"
build/benchmarks/bench_chain --benchmark_out="$out/chain.json" --benchmark_out_format=json >/dev/null
echo "run_benchmarks: the fixed-step methods on a column, N = 10 ... 1e3, five times each"
build/benchmarks/bench_column --benchmark_out="$out/column.json" --benchmark_out_format=json >/dev/null

# P1 beside SciPy's solve_ivp on it: the same Kelvin–Voigt law, c = 2 zeta sqrt(k m) with zeta
# tuned to e = 0.8 (models/contact_law.hpp: zeta = -ln e / sqrt(pi^2 + ln^2 e)), nine solves each.
# This machine's speed drifts (by a third within minutes): P1 timed early in a ten-minute run and
# SciPy at its end gave CVODE's BDF 0.73 ms where it took 0.44 ms minutes before, against SciPy at
# its usual speed. So both are timed in five rounds, each P1 (with the exact bounces) next to
# SciPy's, the order swapped every other round, and bench_report takes the median of the rounds'
# ratios.
echo "run_benchmarks: P1 and the exact bounces beside SciPy's solve_ivp on P1, five rounds"
c=$(/usr/bin/python3 -c "import math; e=0.8; z=-math.log(e)/math.sqrt(math.pi**2+math.log(e)**2); print(repr(2*z*math.sqrt(1e5*1.0)))")
ours() {  # round $1: P1 and the exact bounces
  build/benchmarks/bench_integrators --benchmark_filter='^(P1/|ExactBounces)' --benchmark_min_time=0.1 \
    --benchmark_out="$out/p1_round$1.json" --benchmark_out_format=json >/dev/null
}
scipy() {  # round $1: SciPy's four methods on P1, tuned (the target's peers) and at their defaults
  /usr/bin/python3 python/scipy_peer.py --k 1e5 --c "$c" --h0 1 --t-end 3 --rtols 1e-6 --atol 1e-9 \
    --repeats 9 --setups tuned,defaults >"$out/scipy_p1_round$1.jsonl"
}
scipy_args=() p1_runs=()
for round in 1 2 3 4 5; do
  if ((round % 2)); then
    ours $round
    scipy $round
  else
    scipy $round
    ours $round
  fi
  scipy_args+=(--scipy "$out/scipy_p1_round$round.jsonl")
  p1_runs+=("$out/p1_round$round.json")
done

# Wall time varies by a fifth between runs on a shared 2-core machine: three runs, each into a
# fresh folder, and the run of the median total is reported (with the three totals).
echo "run_benchmarks: the study and the paper, three times"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
runs=()
for run in 1 2 3; do
  rm -rf "$scratch/results"
  t0=$(date +%s.%N)
  build/experiments/study --out "$scratch/results" >/dev/null
  t1=$(date +%s.%N)
  bash scripts/build_paper.sh build "$scratch/results" >/dev/null
  t2=$(date +%s.%N)
  runs+=("$(awk "BEGIN{print $t2 - $t0, $t1 - $t0, $t2 - $t1}")")
done
median=$(printf '%s\n' "${runs[@]}" | sort -g | sed -n 2p)
totals=$(printf '%s\n' "${runs[@]}" | cut -d' ' -f1 | paste -sd, -)
timing="{\"study_s\": $(cut -d' ' -f2 <<<"$median"), \"paper_s\": $(cut -d' ' -f3 <<<"$median"), \"totals_s\": [$totals]"
if [ "${1:-}" = "--fresh-build" ]; then
  echo "run_benchmarks: a fresh Release build"
  t0=$(date +%s.%N)
  cmake -S . -B "$scratch/build" -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$scratch/build" -j"$(nproc)" >/dev/null
  timing="$timing, \"fresh_build_s\": $(awk "BEGIN{print $(date +%s.%N) - $t0}")"
fi
echo "$timing}" > "$out/timing.json"

build/benchmarks/bench_report --build-type "$build_type" --load "$load" "${scipy_args[@]}" \
  --timing "$out/timing.json" "$out/integrators.json" "${p1_runs[@]}" "$out/chain.json" \
  "$out/column.json" >benchmarks/RESULTS.md.tmp
mv benchmarks/RESULTS.md.tmp benchmarks/RESULTS.md
echo "wrote benchmarks/RESULTS.md"
/usr/bin/python3 scripts/bench_history.py  # this run as the last row of benchmarks/HISTORY.md
grep -A30 '^## Targets' benchmarks/RESULTS.md
