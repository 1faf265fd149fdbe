#!/usr/bin/env bash
# Builds paper/paper.tex into RESULTS/paper/paper.pdf from a finished study in RESULTS:
# the quoted numbers (paper_numbers -> RESULTS/paper/numbers.tex), then latexmk, then a check of
# the log: no LaTeX error, no undefined reference or citation, no missing input, and 8-18 pages
# (the revised paper, with related work, limitations and the new sections, has 15).
# Usage: scripts/build_paper.sh BUILD_DIR RESULTS_DIR. Exit 1 on any problem, with the reason.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$(cd "$1" && pwd)"
results="$(cd "$2" && pwd)"
out="$results/paper"
mkdir -p "$out"

command -v latexmk >/dev/null || { echo "build_paper: latexmk not found (bash scripts/setup.sh installs it)" >&2; exit 1; }
"$build/experiments/paper_numbers" --results "$results" --out "$out/numbers.tex"

cd "$root/paper"
# The paper's own sources, the generated numbers, then the experiments' folders (k_sweep/...).
export TEXINPUTS="$root/paper:$out:$results:"
export BIBINPUTS="$root/paper:"
if ! latexmk -pdf -interaction=nonstopmode -halt-on-error -file-line-error -outdir="$out" paper.tex >"$out/latexmk.out" 2>&1; then
  grep -E "^.*:[0-9]+: |^! " "$out/paper.log" >&2 || tail -20 "$out/latexmk.out" >&2
  echo "build_paper: latexmk failed; log in $out/paper.log" >&2
  exit 1
fi

log="$out/paper.log"
# TeX wraps its log at 79 columns, so messages are searched with the line breaks removed.
flat=$(tr -d '\n' < "$log")
problems=$(grep -oE "LaTeX Warning: (Reference|Citation) [^ ]+|There were undefined references|LaTeX Warning: File [^ ]+ not found|No file [^ ]+\.tex" <<<"$flat" || true)
bib=$(grep -E "^Warning--" "$out/paper.blg" 2>/dev/null || true)
if [ -n "$problems$bib" ]; then
  printf '%s\n' "$problems" "$bib" >&2
  echo "build_paper: the paper has undefined references, citations or missing inputs; log in $log" >&2
  exit 1
fi
pages=$(grep -oE "Output written on [^(]*\([0-9]+ pages?" <<<"$flat" | grep -oE "[0-9]+ pages?$" | grep -oE "[0-9]+" || true)
if [ -z "$pages" ] || [ "$pages" -lt 8 ] || [ "$pages" -gt 18 ]; then
  echo "build_paper: the paper has ${pages:-no} pages; a paper of 8 to 18 is expected (log in $log)" >&2
  exit 1
fi
echo "build_paper: $out/paper.pdf ($pages pages)"
