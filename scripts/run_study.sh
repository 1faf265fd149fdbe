#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine, builds contact-ode in Release and runs the study: every
# experiment in experiments/study.json, then the paper (results/paper/paper.pdf). Everything
# lands under results/ (override with RESULTS=DIR); results/index.md links every table and figure.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
results=${RESULTS:-results}
mkdir -p "$results"
results=$(cd "$results" && pwd)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCONTACT_ODE_RESULTS="$results" >/dev/null
cmake --build build -j"$(nproc)"

start=$(date +%s)
build/experiments/study --out "$results"
cmake --build build --target paper
echo "run_study: study and paper in $(( $(date +%s) - start )) s; open $results/index.md and $results/paper/paper.pdf"
