#!/usr/bin/env bash
# Strong and weak scaling of the distributed N-ball chain (chain_mpi) on this machine's cores:
# every case repeated REPEATS times, the median of the solve's wall time (chain_mpi's stats.csv,
# the CVODE solve only), and the efficiency against one rank:
#   strong: N balls on P ranks, efficiency T(1) / (P T(P));
#   weak:   N_PER_RANK balls per rank, efficiency T(1) / T(P).
#   bash benchmarks/scaling_mpi.sh [build-dir] [out.md]     (REPEATS, N, N_PER_RANK, T_END, RANKS)
set -euo pipefail
build=${1:-build}
out=${2:-benchmarks/SCALING.md}
repeats=${REPEATS:-5}
n=${N:-10000}
per_rank=${N_PER_RANK:-5000}
t_end=${T_END:-0.015}
ranks=${RANKS:-"1 2"}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

# median wall time of `repeats` runs: balls, ranks
median() {
  local times=()
  for _ in $(seq "$repeats"); do
    mpirun --oversubscribe -np "$2" "$build/experiments/chain_mpi" --balls "$1" --t-end "$t_end" \
      --out "$scratch/run" >/dev/null
    # the column by its name: stats.csv has gained columns after it before (energy_error_rel)
    times+=("$(awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "wall_time_s") c = i }
                        END { if (!c || !($c > 0)) exit 1; print $c }' "$scratch/run/stats.csv")") ||
      { echo "scaling_mpi.sh: no positive wall_time_s in chain_mpi's stats.csv" >&2; exit 1; }
  done
  printf '%s\n' "${times[@]}" | sort -g | awk '{a[NR]=$1} END {printf "%.9g\n", (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'
}
# A median in the table: four significant digits (fixed decimals gave a 200-ball chain's 0.26 ms
# as 0.0003, one digit); the efficiencies, computed from the unrounded medians, three (two
# decimals printed a loaded machine's 0.0025 as 0.00).
shown() { awk -v t="$1" 'BEGIN {printf "%#.4g", t}'; }

{
  echo "# Scaling of the distributed chain"
  echo
  echo "$(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')), load $(cut -d' ' -f1-3 /proc/loadavg),"
  echo "median of $repeats runs, t_end = $t_end s, $(date -u +%Y-%m-%d)."
  echo
  echo "| kind | ranks | balls | median solve [s] | efficiency |"
  echo "|---|---|---|---|---|"
  base=""
  for p in $ranks; do
    t=$(median "$n" "$p"); base=${base:-$t}
    echo "| strong | $p | $n | $(shown "$t") | $(awk -v a="$base" -v b="$t" -v p="$p" 'BEGIN {printf "%#.3g", a / (p * b)}') |"
  done
  base=""
  for p in $ranks; do
    t=$(median $((per_rank * p)) "$p"); base=${base:-$t}
    echo "| weak | $p | $((per_rank * p)) | $(shown "$t") | $(awk -v a="$base" -v b="$t" 'BEGIN {printf "%#.3g", a / b}') |"
  done
} > "$out"
cat "$out"
