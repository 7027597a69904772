"""tools/experiments.py plumbing, with test doubles of gmmrrt-plan and gmmrrt-learn.

The doubles stand in for the real executables only to check the harness: that it passes the scene to
the planner, scores what comes back with gmmrrt_tools.metrics, records seeds and command lines, writes
no output when a tool is missing, and says so. The experiments' numbers come from the real tools.
"""
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]
REAL = Path(os.environ.get("GMMRRT_REAL_DATA", ROOT.parent / "shared" / "data" / "real"))

FAKE_PLAN = r'''#!/usr/bin/env python3
import json, math, sys
a = sys.argv[1:]
get = lambda f: a[a.index(f) + 1] if f in a else None
sx, sy = map(float, get("--start").split(",")); gx, gy = map(float, get("--goal").split(","))
px, py, _ = map(float, get("--person").split(","))
# Straight to the goal through a point 2 m beside the person, on the +y side of the world.
path = [[sx, sy], [px, py + 2.0], [gx, gy]]
print(json.dumps({"status": "ok", "path": path, "stats": {"iterations": int(get("--iterations") or 0),
      "nodes": 3, "first_solution_ms": 0.5, "best_cost": 1.0, "time_ms": 1.0}}))
'''

# Episodes are read by the real learner's reader (`gmmrrt-learn dump`); only fitting is doubled.
REAL_LEARN = str(Path(os.environ.get("GMMRRT_BIN_DIR", ROOT / "build" / "bin")) / "gmmrrt-learn")
FAKE_LEARN = r'''#!/usr/bin/env python3
import os, sys
a = sys.argv[1:]
if a and a[0] == "dump":
    os.execv(REAL_LEARN, [REAL_LEARN] + a)
open(a[a.index("-o") + 1], "w").write(" ".join(a))
'''.replace("REAL_LEARN", repr(REAL_LEARN))


def _tool(dirpath, name, text):
    p = dirpath / name
    p.write_text(text)
    p.chmod(0o755)


def _run(args, bin_dir, tmp_path):
    env = dict(os.environ, GMMRRT_BIN_DIR=str(bin_dir))
    return subprocess.run([sys.executable, str(ROOT / "tools" / "experiments.py"), *args, "--bin-dir", str(bin_dir),
                           "--out", str(tmp_path / "out"), "--work", str(tmp_path / "work"),
                           "--real-data", str(REAL)], capture_output=True, text=True, env=env, timeout=300)


def test_missing_tool_is_named(tmp_path):
    from gmmrrt_tools import runner
    with pytest.raises(runner.MissingTool, match="gmmrrt-nosuchtool not found in .*tools/run build"):
        runner.find_tool("gmmrrt-nosuchtool", str(tmp_path))


def test_failed_runs_are_kept_as_errors_and_all_failing_aborts(tmp_path):
    if not (REAL / "upo_avoid_episodes.csv").is_file():
        pytest.skip(f"real data not found at {REAL} (set GMMRRT_REAL_DATA)")
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    _tool(bin_dir, "gmmrrt-plan", "#!/bin/sh\necho 'gmmrrt-plan: error: planning problem refused' >&2\nexit 1\n")
    _tool(bin_dir, "gmmrrt-learn", FAKE_LEARN)
    proc = _run(["real", "--quick", "--max-episodes", "2"], bin_dir, tmp_path)
    assert proc.returncode == 1
    assert "every gmmrrt-plan run of real upo avoid failed" in proc.stderr
    assert "planning problem refused" in proc.stderr
    assert not list((tmp_path / "out").glob("*.md"))


def test_missing_demos_are_reported(tmp_path):
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    proc = subprocess.run([sys.executable, str(ROOT / "tools" / "experiments.py"), "table1", "--quick",
                           "--demos-dir", str(tmp_path / "nodemos"), "--out", str(tmp_path / "out"),
                           "--work", str(tmp_path / "work")], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 1
    assert "table1: NOT RUN" in proc.stderr and "no demonstration logs" in proc.stderr
    assert not list((tmp_path / "out").glob("*"))


def test_real_data_harness_scores_what_the_planner_returns(tmp_path):
    if not (REAL / "upo_avoid_episodes.csv").is_file():
        pytest.skip(f"real data not found at {REAL} (set GMMRRT_REAL_DATA)")
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    _tool(bin_dir, "gmmrrt-plan", FAKE_PLAN)
    _tool(bin_dir, "gmmrrt-learn", FAKE_LEARN)
    proc = _run(["real", "--quick", "--max-episodes", "2", "--seed", "7"], bin_dir, tmp_path)
    assert proc.returncode == 0, proc.stderr[-3000:]
    out = tmp_path / "out"
    md = (out / "real_upo_avoid-quick.md").read_text()
    for row in ("| GMM-RRT* (paper cost) |", "| GMM-RRT* (inward cost) |", "| RRT* |", "| human (reference) |",
                "| GMM-RRT* (background cost) |", "| GMM-RRT* (background cost, human's side) |",
                "| GMM-RRT* (paper cost, human's side) |", "| GMM-RRT* (paper cost, own person only) |"):
        assert row in md
    assert "tools/experiments.py real --quick" in md and "two humans in nearly the same situation" in md
    data = json.loads((out / "real_upo_avoid-quick.json").read_text())
    runs = data["runs"]
    assert len(runs) == 18  # 2 episodes x 9 planners
    assert sorted({r["seed"] for r in runs}) == [7, 8]
    assert all("--seed" in r["argv"] and "--json" in r["argv"] for r in runs)
    gmm_runs = [r for r in runs if r["planner"].startswith("GMM-RRT*")]
    assert all("--model" in r["argv"] and "--gmm-bias 0.95" in r["argv"] and "--task-cost " in r["argv"] for r in gmm_runs)
    assert all("--model" not in r["argv"] for r in runs if r["planner"].startswith("RRT*"))
    assert sum(r["planner"] == "RRT* (human's side)" for r in runs) == 2  # the side's worth without a model
    # every standing person of the recording, except in the one-person row; the sides as asked
    for r in runs:
        n = r["argv"].count("--person ")
        assert n == (1 if "own person only" in r["planner"] else r["people"]) and n >= 1
        assert ("--side " in r["argv"]) == ("side)" in r["planner"])
    # the learner was asked for the train split only
    # with its background in the same file (gmmrrt-learn fit --background straight)
    model_args = (tmp_path / "work" / "models" / "upo_avoid_train_all_bg.gmm").read_text()
    assert "--split train" in model_args and "--task avoid" in model_args and "--background straight" in model_args
    assert all("--task-cost background" in r["argv"] and "--background-model" not in r["argv"]
               for r in runs if "background" in r["planner"])
    ucy_args = (tmp_path / "work" / "models" / "ucy_avoid_train_all_bg.gmm").read_text()
    assert "--split train" in ucy_args and "ucy_index.csv" in ucy_args and "--background straight" in ucy_args
    # UCY: the walking-people rows pass people with a velocity and the walker's pace
    ucy = json.loads((out / "real_ucy_avoid-quick.json").read_text())["runs"]
    walking = [r for r in ucy if "walking people given" in r["planner"]]
    assert len(walking) == 2 * 3 and all("--nominal-speed" in r["argv"] for r in walking)
    assert not any("--nominal-speed" in r["argv"] for r in ucy if "walking" not in r["planner"])
    assert (out / "real_upo_avoid-quick.png").stat().st_size > 1000
    episodes = (out / "real_upo_avoid_episodes-quick.md").read_text()
    assert sum(line.startswith("| avoid_upo_") for line in episodes.splitlines()) == 2
    for name in ("real_ucy_avoid-quick.md", "real_ucy_approach-quick.md", "real_ucy_avoid_episodes-quick.md"):
        assert (out / name).is_file()


def test_real_data_without_the_split_is_named(tmp_path):
    if not (REAL / "upo_avoid_episodes.csv").is_file():
        pytest.skip(f"real data not found at {REAL} (set GMMRRT_REAL_DATA)")
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    _tool(bin_dir, "gmmrrt-plan", FAKE_PLAN)
    _tool(bin_dir, "gmmrrt-learn", FAKE_LEARN)
    proc = _run(["real", "--quick", "--split", "validation"], bin_dir, tmp_path)
    assert proc.returncode == 1
    assert "upo_avoid_index.csv: no episode in split 'validation'" in proc.stderr


FAKE_PLAN_HISTORY = FAKE_PLAN.replace(
    '"best_cost": 1.0, "time_ms": 1.0}}))',
    '"best_cost": 5.0, "time_ms": 1.0, "cost_history": [[50, 10.0 + int(get("--seed"))], [400, 5.0]], '
    '"cost_history_complete": True}}))')


def test_fig1_reads_each_runs_cost_history(tmp_path):
    """Fig. 1 makes one run per (bias, trial) and reads its best cost at every checkpoint from
    stats.cost_history: before the first entry there is no solution, between entries the earlier cost."""
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    _tool(bin_dir, "gmmrrt-plan", FAKE_PLAN_HISTORY)
    _tool(bin_dir, "gmmrrt-learn", FAKE_LEARN)
    proc = _run(["fig1", "--quick", "--seed", "3"], bin_dir, tmp_path)
    assert proc.returncode == 0, proc.stderr[-3000:]
    data = json.loads((tmp_path / "out" / "fig1-quick.json").read_text())
    assert len(data["runs"]) == 2 * 5                       # two biases x 5 quick trials, one run each
    assert {r["seed"] for r in data["runs"]} == {3, 4, 5, 6, 7}
    md = (tmp_path / "out" / "fig1-quick.md").read_text()
    # seeds 3..7: cost 13..17 from iteration 50 (mean 15, population std 1.414), 5 from iteration 400
    assert "| 100% | 100 | 5/5 | 15.000 ± 1.414 |" in md
    assert "| 0% | 300 | 5/5 | 15.000 ± 1.414 |" in md
    assert "| 100% | 500 | 5/5 | 5.000 ± 0.000 |" in md
    assert "| 0% | 2000 | 5/5 | 5.000 ± 0.000 |" in md


def test_fig1_refuses_a_planner_without_cost_history(tmp_path):
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    _tool(bin_dir, "gmmrrt-plan", FAKE_PLAN)
    _tool(bin_dir, "gmmrrt-learn", FAKE_LEARN)
    proc = _run(["fig1", "--quick"], bin_dir, tmp_path)
    assert proc.returncode != 0
    assert "cost_history" in proc.stderr
    assert not list((tmp_path / "out").glob("fig1*"))
