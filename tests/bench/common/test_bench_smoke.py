"""bench.smoke: tools/bench.py runs end to end on tiny budgets (hand-built task models, one
30 ms trial per planner) and writes a valid JSON result and a Markdown report.

Checks the structure and the sanity of what is measured, never a time (benchmarks
report speed, tests do not assert it: timings vary with the machine and its load).
"""
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]
BUILD = Path(os.environ.get("GMMRRT_BUILD_DIR", ROOT / "build"))


def _reject_constant(name):
    raise ValueError(f"non-standard JSON constant {name}")


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    # Registered only in a -DGMMRRT_BUILD_BENCH=ON tree, so the programs must be there.
    assert (BUILD / "bin" / "gmmrrt-bench-memory").is_file(), f"gmmrrt-bench-memory not built in {BUILD}"
    out = tmp_path_factory.mktemp("bench")
    results, doc = out / "results.json", out / "benchmarks.md"
    cmd = [sys.executable, str(ROOT / "tools" / "bench.py"), "--quick", "--only", "memory,ompl,social",
           "--trials", "1", "--time-ms", "30", "--hand-built-models", "--build-dir", str(BUILD),
           "--results", str(results), "--doc", str(doc)]
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=170)
    assert proc.returncode == 0, proc.stderr
    data = json.loads(results.read_text(), parse_constant=_reject_constant)
    return data, doc.read_text(), proc


def test_results_are_valid_json_with_every_requested_section(run):
    data, _doc, _proc = run
    for key in ("date_utc", "host", "settings", "targets", "memory", "ompl", "social"):
        assert key in data, key
    assert data["host"]["nproc"] >= 1
    assert data["settings"] == {"trials": 1, "time_ms": 30.0, "seed": 1}


def test_memory_figures_are_measured(run):
    data, _doc, _proc = run
    mem = data["memory"]
    assert "error" not in mem, mem.get("error")
    assert mem["alloc_counter_works"] is True
    assert mem["default_mem_bytes"] > mem["mem_bytes_at_2_nodes"] > 0
    assert mem["bytes_per_node"] > 0
    assert mem["rrtstar_disc"]["iterations"] > 0


def test_planner_sections_hold_trials_or_say_why_not(run):
    data, _doc, _proc = run
    om = data["ompl"]
    if "error" in om:  # OMPL is optional: the reason must be named
        assert "OMPL" in om["error"] or "missing" in om["error"]
    else:
        planners = om["length"]["planners"]
        assert planners["ompl_rrtstar"]["trials"] == 1
        assert planners["gmmrrt_rrtstar"]["trials"] == 1
        assert planners["gmmrrt_rrtstar"]["iterations_per_s_median"] > 0
    for task in ("avoid", "approach"):
        s = data["social"][task]
        assert s["trials"] == 1
        assert s["time_ms"] == 30.0
        assert s["first_solution_ms_median"] is None or s["first_solution_ms_median"] >= 0


def test_every_target_has_a_status_and_the_report_lists_them(run):
    data, doc, _proc = run
    assert len(data["targets"]) >= 8
    for t in data["targets"]:
        assert t["status"] in ("met", "not met", "not run")
        assert t["value"] is None or math.isfinite(t["value"])
        assert t["name"] in doc
    assert "## Where the targets stand" in doc


def _exe(name):
    p = BUILD / "bin" / name
    if not p.is_file():
        pytest.skip(f"{name} not built (optional dependency missing)")
    return str(p)


@pytest.mark.parametrize("args,needle", [
    (["--objective", "speed"], "--objective"),
    (["--trials", "0"], "--trials"),
    (["--time-ms", "nan"], "--time-ms"),
    (["--objective", "task"], "--model"),
    (["--objective", "task", "--model", "/nonexistent.gmm"], "/nonexistent.gmm"),
    (["--planners", "ompl,rrtx"], "rrtx"),
    (["--objective", "task", "--planners", "ompl-informed"], "ompl-informed"),
])
def test_bench_ompl_rejects_bad_flags_by_name(args, needle):
    proc = subprocess.run([_exe("gmmrrt-bench-ompl")] + args, capture_output=True, text=True, timeout=30)
    assert proc.returncode != 0
    assert needle in proc.stderr
    assert proc.stdout == ""


def test_bench_learner_names_the_bad_line(tmp_path):
    csv = tmp_path / "points.csv"
    csv.write_text("x0,x1\n1,2\n3,oops\n")
    proc = subprocess.run([_exe("gmmrrt-bench-learner"), "--points", str(csv), "--k", "1"], capture_output=True,
                          text=True, timeout=30)
    assert proc.returncode == 1
    assert f"{csv}:3" in proc.stderr


def test_bench_social_needs_a_features_model(tmp_path):
    bad = tmp_path / "bad.gmm"
    bad.write_bytes(b"not a model")
    proc = subprocess.run([_exe("gmmrrt-bench-social"), "--task", "avoid", "--model", str(bad)],
                          capture_output=True, text=True, timeout=30)
    assert proc.returncode == 1
    assert proc.stderr.strip()
    assert proc.stdout == ""
