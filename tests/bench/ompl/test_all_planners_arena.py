"""bench.all_planners_arena: gmmrrt-bench-all on the map scene (1 ms, one trial per planner) writes
Planner Arena logs that the harness reads back and counts against the JSON records, with a
MAP row for every planner; a log with a run missing, or one whose solved count disagrees with the
JSON, is refused by name.

Checks structure and sanity, never a time.
"""
import json
import os
import subprocess
from pathlib import Path

import pytest

from gmmrrt_tools.bench.planner import BenchError, check_arena_logs

ROOT = Path(__file__).resolve().parents[3]
BUILD = Path(os.environ.get("GMMRRT_BUILD_DIR", ROOT / "build"))
PLANNERS = ["gmmrrt", "RRTConnect", "RRTstar", "InformedRRTstar", "SORRTstar", "RRTsharp", "RRTXstatic",
            "LBTRRT", "BITstar", "ABITstar", "AITstar", "FMT"]


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    exe = BUILD / "bin" / "gmmrrt-bench-all"
    # Registered only in a -DGMMRRT_BUILD_BENCH=ON tree with OMPL, so the program must be there.
    assert exe.is_file(), f"gmmrrt-bench-all not built in {BUILD}"
    out = tmp_path_factory.mktemp("arena")
    arena, records = out / "arena", out / "records.jsonl"
    arena.mkdir()
    cmd = [str(exe), "--problems", str(ROOT / "tests" / "data" / "bench_problems"), "--trials", "1",
           "--budgets", "1,5", "--only", "MAP", "--map", str(ROOT / "logs" / "maps" / "floor.yaml"),
           "--json", str(records), "--arena", str(arena)]
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    recs = [json.loads(line) for line in records.read_text().splitlines() if line.strip()]
    return arena, recs, proc.stdout


def test_every_planner_runs_the_map_scene_at_every_budget(run):
    _arena, recs, text = run
    assert sorted({(r["planner"], r["budget_ms"]) for r in recs}) == sorted(
        (p, b) for p in PLANNERS for b in (1.0, 5.0))
    assert {r["problem"] for r in recs} == {"MAP"}
    for p in PLANNERS:
        assert f"| {p} |" in text
    # A path that is returned has the length of at least the straight line start -> goal.
    straight = ((8 - -9) ** 2 + (4 - -2) ** 2) ** 0.5
    assert all(r["cost"] is None or r["cost"] >= straight for r in recs)


def test_arena_logs_read_back_and_match_the_records(run):
    arena, recs, _text = run
    logs = check_arena_logs(arena, recs)
    assert sorted(x["log"] for x in logs) == ["MAP_1ms.log", "MAP_5ms.log"]
    assert all(x["planners"] == len(PLANNERS) and x["runs"] == len(PLANNERS) for x in logs)


def test_a_log_with_a_run_missing_is_refused(run, tmp_path):
    arena, recs, _text = run
    bad = tmp_path / "MAP_5ms.log"
    lines = (arena / "MAP_5ms.log").read_text().splitlines(keepends=True)
    i = lines.index("geometric_RRTstar\n")
    # The planner's run table: "1 runs" then one run line; drop the line and say 0 runs.
    k = next(j for j in range(i, len(lines)) if lines[j].endswith(" runs\n"))
    lines[k] = "0 runs\n"
    del lines[k + 1]
    bad.write_text("".join(lines))
    with pytest.raises(BenchError, match="planner RRTstar: 0 runs"):
        check_arena_logs(tmp_path, recs)


def test_a_log_whose_solved_runs_disagree_is_refused(run, tmp_path):
    arena, recs, _text = run
    flipped = [dict(r) for r in recs]
    for r in flipped:
        if r["budget_ms"] == 5.0 and r["planner"] == "gmmrrt":
            r["cost"] = None if r["cost"] is not None else 20.0
    (tmp_path / "MAP_5ms.log").write_text((arena / "MAP_5ms.log").read_text())
    with pytest.raises(BenchError, match="planner gmmrrt"):
        check_arena_logs(tmp_path, flipped)
