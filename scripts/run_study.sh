#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine, builds contact-ode in Release and runs the study.
# Everything it produces lands under results/ (override with RESULTS=DIR).
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"

results=${RESULTS:-results}
start=$(date +%s)
build/experiments/ball_drop --out "$results/ball_drop"
echo
build/experiments/ball_drop --sweep --out "$results/ball_drop_sweep"
echo
echo "study finished in $(( $(date +%s) - start )) s; results in $results/"
