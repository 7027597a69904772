"""bench.first_paths: the first-path counter runs gmmrrt-plan at the benchmark's settings and
reports exact iterations (the same seeds give the same figures), and refuses a bad problem file
with its line."""
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from gmmrrt_tools.bench import first_paths

ROOT = Path(__file__).resolve().parents[3]
PLAN = Path(os.environ.get("GMMRRT_BIN_DIR", ROOT / "build" / "bin")) / "gmmrrt-plan"


def run(*args):
    out = subprocess.run([sys.executable, "-m", "gmmrrt_tools.bench.first_paths", "--plan", str(PLAN), *args],
                         capture_output=True, text=True, cwd=ROOT)
    return out


def test_problem_c_first_paths_are_exact_and_switchable():
    problem = str(ROOT / "tests" / "data" / "bench_problems" / "problem_C.txt")
    a = run("--problem", problem, "--seeds", "5")
    assert a.returncode == 0, a.stderr
    ra = json.loads(a.stdout)
    assert ra["seeds"] == 5 and ra["with_path"] == 5
    assert 1 <= ra["iterations_median"] <= ra["iterations_p90"] <= ra["iterations_max"]
    assert ra["first_solution_ms_median"] > 0.0
    b = json.loads(run("--problem", problem, "--seeds", "5").stdout)
    for key in ("iterations_median", "iterations_p90", "iterations_max"):
        assert b[key] == ra[key]  # deterministic per seed
    # Arguments after -- reach gmmrrt-plan: RRT* alone takes more iterations than the connect phase.
    c = json.loads(run("--problem", problem, "--seeds", "5", "--", "--connect", "0").stdout)
    assert c["iterations_median"] > ra["iterations_median"]


def test_a_bad_problem_line_is_named(tmp_path):
    bad = tmp_path / "p.txt"
    bad.write_text("bounds -1 -1 1 1\nstart 0 0\ngoal 0.5 x\n")
    with pytest.raises(SystemExit) as e:
        first_paths.problem_args(bad)
    assert "p.txt:3" in str(e.value) and "not a number" in str(e.value)
    bad.write_text("bounds -1 -1 1 1\nstart 0 0\n")
    with pytest.raises(SystemExit) as e:
        first_paths.problem_args(bad)
    assert "needs a 'bounds', a 'start' and a 'goal'" in str(e.value)


def test_summary_counts_runs_without_a_path_as_never():
    s = first_paths.summarise([{"iteration": 3, "ms": 0.1}, None, {"iteration": 7, "ms": 0.3}])
    assert s["seeds"] == 3 and s["with_path"] == 2
    # [3, never, 7]: the median is 7, the 90th percentile and the slowest are never (null).
    assert s["iterations_median"] == 7 and s["iterations_p90"] is None and s["iterations_max"] is None
    assert s["first_solution_ms_median"] == 0.3 and s["first_solution_ms_mean"] is None
    full = first_paths.summarise([{"iteration": k, "ms": 0.1 * k} for k in range(1, 11)])
    assert full["iterations_p90"] == 9 and full["iterations_max"] == 10  # nearest rank
    assert abs(full["first_solution_ms_mean"] - 0.55) < 1e-12
