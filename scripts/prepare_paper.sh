#!/usr/bin/env bash
# Prepares what the paper's build needs that does not depend on the study's results, so that
# building the paper after a study is two pdfLaTeX passes (scripts/build_paper.sh):
#   BUILD_DIR/paper/preamble.fmt  paper/preamble.tex (class and packages) dumped as a format: a
#                                 pass starts from the loaded packages (0.3 s of 0.45 s a pass);
#   BUILD_DIR/paper/paper.bbl     the bibliography, by BibTeX from the keys paper.tex cites: with
#                                 it in place before the first pass, two passes resolve every
#                                 citation and reference (three, with BibTeX between, without it).
# Each is remade only when older than its sources (or than pdflatex, whose version a format must
# match). Run at build time (the paper_prerequisites target) and again by build_paper.sh.
# Usage: scripts/prepare_paper.sh BUILD_DIR. Exit 1 with the reason on any problem.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
mkdir -p "$1/paper"
dir="$(cd "$1/paper" && pwd)"
src="$root/paper"
for tool in pdflatex bibtex; do
  command -v "$tool" >/dev/null || { echo "prepare_paper: $tool not found (bash scripts/setup.sh installs TeX Live)" >&2; exit 1; }
done

fmt="$dir/preamble.fmt"
if [ ! -s "$fmt" ] || [ "$src/preamble.tex" -nt "$fmt" ] || [ "$(command -v pdflatex)" -nt "$fmt" ]; then
  (cd "$dir" && pdflatex -ini -interaction=batchmode -halt-on-error -jobname=preamble "&pdflatex" \
    "\\input{$src/preamble.tex}\\dump" >/dev/null 2>&1) || {
    tail -20 "$dir/preamble.log" >&2
    rm -f "$fmt"
    echo "prepare_paper: the preamble's format failed; log in $dir/preamble.log" >&2
    exit 1
  }
fi

bbl="$dir/paper.bbl"
if [ ! -s "$bbl" ] || [ "$src/paper.tex" -nt "$bbl" ] || [ "$src/references.bib" -nt "$bbl" ]; then
  # The auxiliary file pdfLaTeX would write for BibTeX: every cited key (\cite, \citep, \citet,
  # with or without optional arguments), the style and the database. A key missed here would be
  # an undefined citation, which build_paper.sh refuses.
  tex=$(tr '\n' ' ' <"$src/paper.tex")
  {
    echo '\relax'
    grep -oE '\\cite[a-zA-Z]*\*?(\[[^]]*\])*\{[^}]*\}' <<<"$tex" | sed -E 's/.*\{([^}]*)\}/\\citation{\1}/'
    grep -oE '\\bibliographystyle\{[^}]*\}' <<<"$tex" | sed 's/\\bibliographystyle/\\bibstyle/'
    grep -oE '\\bibliography\{[^}]*\}' <<<"$tex" | sed 's/\\bibliography/\\bibdata/'
  } >"$dir/paper.aux"
  if ! (cd "$dir" && BIBINPUTS="$src:" bibtex paper >"$dir/bibtex.out" 2>&1) || grep -q "^Warning--" "$dir/paper.blg"; then
    cat "$dir/bibtex.out" >&2
    rm -f "$bbl"  # not kept as if it were up to date
    echo "prepare_paper: BibTeX failed or warned; log in $dir/paper.blg" >&2
    exit 1
  fi
fi
touch "$fmt" "$bbl"  # checked up to date: newer than every source, so that make does not ask again
