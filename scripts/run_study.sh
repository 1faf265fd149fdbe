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
for experiment in contact_laws rigid_scenes k_sweep stability_map convergence_k zeno; do
  build/experiments/$experiment --out "$results/$experiment"
  echo
done
# A worked question: 1 kg at 5 m/s, e = 0.8, at most 1 mm of penetration.
build/experiments/contact_advisor --m 1 --v 5 --e 0.8 --max-penetration 1e-3 --out "$results/contact_advisor"
echo
echo "study finished in $(( $(date +%s) - start )) s; results in $results/"
