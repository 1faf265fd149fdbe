#!/usr/bin/env bash
# Builds in Release, runs the Google Benchmark programs and writes benchmarks/RESULTS.md (the
# table the README shows) from their JSON. Takes a few minutes on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" --target bench_integrators bench_chain bench_report

out=build/benchmark-results
mkdir -p "$out"
build/benchmarks/bench_integrators --benchmark_out="$out/integrators.json" --benchmark_out_format=json
build/benchmarks/bench_chain --benchmark_out="$out/chain.json" --benchmark_out_format=json
build/benchmarks/bench_report "$out/integrators.json" "$out/chain.json" > benchmarks/RESULTS.md.tmp
mv benchmarks/RESULTS.md.tmp benchmarks/RESULTS.md
echo "wrote benchmarks/RESULTS.md"
