#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine, builds contact-ode and runs the whole test suite.
#   bash scripts/run_tests.sh              Release build in build/
#   bash scripts/run_tests.sh --sanitize   AddressSanitizer + UndefinedBehaviorSanitizer build in build-asan/
#   bash scripts/run_tests.sh --native     Release build for this CPU (-march=native) in build-native/: the
#                                          numbers must not depend on the flags a user builds with
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh

build_dir=build
config=(-DCMAKE_BUILD_TYPE=Release)
if [ "${1:-}" = "--sanitize" ]; then
  build_dir=build-asan
  config=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DCONTACT_ODE_SANITIZE=ON -DCONTACT_ODE_BENCHMARKS=OFF)
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
  export LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp"  # Siconos's own shared_ptr cycles
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
elif [ "${1:-}" = "--native" ]; then
  build_dir=build-native
  config=(-DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS=-march=native -DCONTACT_ODE_BENCHMARKS=OFF)
fi

# CI builds with warnings as errors (.ci/run sets CONTACT_ODE_WERROR=ON); a newcomer's build only warns.
# Only the Release build: GCC 12 reports false -Wmaybe-uninitialized inside libstdc++'s <regex>
# with -fsanitize (the instrumentation hides the initialisation from the flow analysis) and inside
# its own AVX-512 intrinsics with -march=native (the '__Y' that _mm512_undefined_pd leaves unset).
if [ "${CONTACT_ODE_WERROR:-OFF}" = "ON" ] && [ "$build_dir" = build ]; then
  config+=(-DCMAKE_COMPILE_WARNING_AS_ERROR=ON)
fi

jobs=$(nproc)
cmake -S . -B "$build_dir" "${config[@]}" >/dev/null
cmake --build "$build_dir" -j"$jobs"
ctest --test-dir "$build_dir" --output-on-failure -j"$jobs"
