#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine, builds contact-ode in Release and runs the study: every
# experiment in experiments/study.json, then the paper. Everything lands under results/
# (override with RESULTS=DIR); results/index.md links every table and figure.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"

results=${RESULTS:-results}
build/experiments/study --out "$results"
