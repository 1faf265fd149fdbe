#!/usr/bin/env bash
# Builds paper/paper.tex into RESULTS/paper/paper.pdf from a finished study in RESULTS:
# the quoted numbers (paper_numbers -> RESULTS/paper/numbers.tex), then pdfLaTeX passes from the
# precompiled preamble with the bibliography in place (scripts/prepare_paper.sh: two passes, a
# third only if LaTeX still asks), then a check of the log: no LaTeX error, no undefined reference
# or citation, no missing input, and 8-18 pages (the revised paper, with related work, limitations
# and the new sections, has 15).
# Usage: scripts/build_paper.sh BUILD_DIR RESULTS_DIR. Exit 1 on any problem, with the reason.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$(cd "$1" && pwd)"
results="$(cd "$2" && pwd)"
out="$results/paper"
mkdir -p "$out"

bash "$root/scripts/prepare_paper.sh" "$build"  # (made at build time: checks only, unless stale)
"$build/experiments/paper_numbers" --results "$results" --out "$out/numbers.tex"

cd "$root/paper"
# The paper's own sources, the generated numbers, then the experiments' folders (k_sweep/...).
export TEXINPUTS="$root/paper:$out:$results:"
cp "$build/paper/paper.bbl" "$out/paper.bbl"
rm -f "$out/paper.aux"  # an earlier build's labels would be read as this one's
# LaTeX asks for another pass ("Rerun to get ...") while labels, citations or outlines change;
# with the bibliography in place two passes settle, and four that do not are an error.
passes=0
while :; do
  passes=$((passes + 1))
  if ! pdflatex -fmt="$build/paper/preamble" -interaction=nonstopmode -halt-on-error -file-line-error \
    -output-directory="$out" paper.tex >"$out/pdflatex.out" 2>&1; then
    grep -E "^.*:[0-9]+: |^! " "$out/paper.log" >&2 || tail -20 "$out/pdflatex.out" >&2
    echo "build_paper: pdflatex failed (pass $passes); log in $out/paper.log" >&2
    exit 1
  fi
  tr -d '\n' <"$out/paper.log" | grep -q "Rerun to get" || break
  if [ "$passes" -ge 4 ]; then
    echo "build_paper: LaTeX still asks for a rerun after $passes passes; log in $out/paper.log" >&2
    exit 1
  fi
done

log="$out/paper.log"
# TeX wraps its log at 79 columns, so messages are searched with the line breaks removed.
flat=$(tr -d '\n' < "$log")
problems=$(grep -oE "(LaTeX|Package natbib) Warning: (Reference|Citation) [^ ]+|There were undefined (references|citations)|LaTeX Warning: File [^ ]+ not found|No file [^ ]+\.tex" <<<"$flat" || true)
if [ -n "$problems" ]; then
  printf '%s\n' "$problems" >&2
  echo "build_paper: the paper has undefined references, citations or missing inputs; log in $log" >&2
  exit 1
fi
pages=$(grep -oE "Output written on [^(]*\([0-9]+ pages?" <<<"$flat" | grep -oE "[0-9]+ pages?$" | grep -oE "[0-9]+" || true)
if [ -z "$pages" ] || [ "$pages" -lt 8 ] || [ "$pages" -gt 18 ]; then
  echo "build_paper: the paper has ${pages:-no} pages; a paper of 8 to 18 is expected (log in $log)" >&2
  exit 1
fi
echo "build_paper: $out/paper.pdf ($pages pages)"
