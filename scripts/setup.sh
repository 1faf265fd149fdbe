#!/usr/bin/env bash
# Installs, from Debian 12's packages only, everything contact-ode needs to build, test and run
# its study. Idempotent: packages already present are skipped, and when nothing is missing apt
# is not touched at all (so a prepared machine needs no network).
set -euo pipefail

packages=(
  build-essential cmake git pkg-config
  clang-format         # the checked-in .clang-format, checked by .ci/run
  libsundials-dev      # CVODE (BDF/Adams, root finding) and ARKODE
  libeigen3-dev        # small dense vectors and matrices for states and Jacobians
  libgsl-dev           # least-squares fits (observed orders), roots, statistics
  libgtest-dev         # the test suite
  libbenchmark-dev     # benchmarks/
  libcli11-dev         # command-line options of the experiments
  nlohmann-json3-dev   # meta.json
  libfmt-dev           # formatting of tables and messages
  gnuplot-nox          # figures (PNG and PDF, cairo terminals)
  libopenmpi-dev openmpi-bin  # the study's sweeps over MPI ranks (mpirun)
  pybind11-dev python3-pybind11 python3-numpy  # the Python module contact_ode (python/)
  python3-pytest python3-matplotlib            # its tests and the example (tests/python, examples/)
  libmujoco-dev libqhull-dev libbullet-dev libode-dev  # the peer engines (integrators/engines)
  libsiconos-kernel-dev libsiconos-mechanics-dev python3-siconos  # Siconos (its CMake targets need the io libraries)
  python3-scipy        # the SciPy peer of the work-precision study and the benchmarks
  texlive-latex-base texlive-latex-recommended texlive-fonts-recommended  # the paper
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

echo "setup: installing ${missing[*]}"
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done"
