"""benchmarks/HISTORY.md is what scripts/bench_history.py makes of RESULTS.md's git history: no
row typed in, none missing, and its last row the run RESULTS.md shows."""
import pathlib
import re
import shutil
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


def git_history_available():
    if shutil.which("git") is None or not (ROOT / ".git").exists():
        return False
    shallow = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--is-shallow-repository"],
                             capture_output=True, text=True)
    return shallow.returncode == 0 and shallow.stdout.strip() == "false"


needs_history = pytest.mark.skipif(not git_history_available(),
                                   reason="needs a git checkout with its whole history")


def generated():
    run = subprocess.run([sys.executable, str(ROOT / "scripts" / "bench_history.py"), "--stdout"],
                         capture_output=True, text=True, check=True)
    return run.stdout


@needs_history
def test_the_committed_history_is_the_generated_one():
    assert (ROOT / "benchmarks" / "HISTORY.md").read_text(encoding="utf-8") == generated()


@needs_history
def test_its_last_row_is_the_run_results_md_shows():
    results = (ROOT / "benchmarks" / "RESULTS.md").read_text(encoding="utf-8")
    run = re.search(r"run (\d{4}-\d\d-\d\d)T(\d\d:\d\d)", results)
    lsoda = re.search(r"^- P1 \(rtol 1e-6\), .*?LSODA (\d+)x", results, re.M)
    klu = re.search(r"klu is (\d+)x faster than dense", results)
    last = generated().rstrip("\n").split("\n")[-1].split(" | ")
    assert last[0] == f"| {run.group(1)} {run.group(2)}"
    assert last[3] == lsoda.group(1)  # x LSODA
    assert last[9] == klu.group(1)  # KLU x


def test_it_refuses_an_unknown_argument():
    run = subprocess.run([sys.executable, str(ROOT / "scripts" / "bench_history.py"), "--bogus"],
                         capture_output=True, text=True)
    assert run.returncode == 2
    assert "unknown argument(s) ['--bogus']; accepted: --stdout" in run.stderr


def history_rows():
    text = (ROOT / "benchmarks" / "HISTORY.md").read_text(encoding="utf-8")
    return [line.split(" | ") for line in text.splitlines() if re.match(r"\| \d{4}-", line)]


def number(text):
    return None if text.strip(" |") == "—" else float(text.strip(" |"))


def test_the_readme_cites_the_history_as_it_reads():
    """What the README says of all the runs, read from HISTORY.md's rows."""
    rows = history_rows()
    study = [number(r[10]) for r in rows if number(r[10]) is not None]
    build = [number(r[11]) for r in rows if number(r[11]) is not None]
    machines = {r[1] for r in rows}
    words = {2: "two", 3: "three", 4: "four", 5: "five", 6: "six", 7: "seven"}
    readme = (ROOT / "README.md").read_text(encoding="utf-8").replace("\n", " ")
    for claim in [
        f"from {min(study):.1f} to {max(study):.1f} s over the runs that timed it, on "
        f"{words[len(machines)]} machines",
        f"({min(build):.0f} to {max(build):.0f} s in the runs that timed it)",
        f"has every committed run's, {len(rows)} runs on {words[len(machines)]} machines",
        f"and in {sum(s <= 10 for s in study)} of the {len(study)} runs that timed it, as the study grew",
    ]:
        assert claim in readme
