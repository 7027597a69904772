"""planner.cli: gmmrrt-plan end to end.

Runs the installed-layout binary from GMMRRT_BIN_DIR on the disc problem, with a
hand-made model file (written by the C core through gmmrrt_tools.core: the format's one
implementation; its independent oracle is tools/gen_model_vectors.py), and checks the CSV and JSON outputs, determinism, and that bad input
gets a clear error and a non-zero exit with nothing on stdout.
"""
import json
import math
import os
import subprocess
from pathlib import Path

import pytest

from gmmrrt_tools import core

BIN = Path(os.environ.get("GMMRRT_BIN_DIR", "build/bin")) / "gmmrrt-plan"
DISC = ["--start", "-5,0", "--goal", "5,0", "--obstacle", "circle:0,0,2", "--robot-radius", "0",
        "--bounds", "-7,-5,7,5"]


def run(*args):
    if not BIN.exists():
        pytest.fail(f"{BIN} is missing: build the project first (tools/run build)")
    return subprocess.run([str(BIN), *args], capture_output=True, text=True, timeout=120)


def write_features_model(path, thetas, d=1.2, sd=0.2, st=0.25, task=1):
    """kind 1 (features), D = 2, angle_mask 0x2; components (d, theta_i), equal weights."""
    k = len(thetas)
    weights = [1.0 / k] * (k - 1) + [1.0 - (k - 1) * (1.0 / k)]
    model = core.model_from_arrays(1, task, 0, weights, [(d, th) for th in thetas], [(sd, 0.0, st)] * k, 0x2, 0.001)
    core.save_model(str(path), model)
    return path


def test_help_lists_every_option():
    r = run("--help")
    assert r.returncode == 0
    for opt in ["--model", "--start", "--goal", "--person", "--obstacle", "--planner", "--bias",
                "--budget-ms", "--iterations", "--seed", "--robot-radius", "--bounds", "--json", "--delta",
                "--w-task", "--rewire-k", "--informed", "cost_history"]:
        assert opt in r.stdout


def test_json_disc_detour_is_near_the_closed_form():
    r = run(*DISC, "--iterations", "20000", "--json")
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    assert out["status"] == "ok"
    path = out["path"]
    assert path[0] == [-5.0, 0.0] and path[-1] == [5.0, 0.0]
    optimum = 2 * math.sqrt(21) + 2 * (math.pi - 2 * math.acos(0.4))
    length = sum(math.dist(a, b) for a, b in zip(path, path[1:]))
    assert optimum - 1e-6 <= length <= optimum * 1.02
    assert all(math.hypot(x, y) >= 2.0 - 1e-6 for x, y in path)
    stats = out["stats"]
    assert stats["iterations"] == 20000
    assert stats["nodes"] > 1000
    assert stats["first_solution_ms"] is not None and stats["first_solution_ms"] >= 0
    assert optimum - 1e-6 <= stats["best_cost"] <= optimum * 1.02
    assert stats["time_ms"] > 0


def test_csv_output_and_same_seed_same_path():
    a = run(*DISC, "--iterations", "3000", "--seed", "5")
    b = run(*DISC, "--iterations", "3000", "--seed", "5")
    c = run(*DISC, "--iterations", "3000", "--seed", "6")
    assert a.returncode == 0 and b.returncode == 0 and c.returncode == 0
    lines = a.stdout.strip().splitlines()
    assert lines[0] == "x,y"
    pts = [tuple(map(float, ln.split(","))) for ln in lines[1:]]
    assert pts[0] == (-5.0, 0.0) and pts[-1] == (5.0, 0.0)
    assert a.stdout == b.stdout
    assert a.stdout != c.stdout


def test_model_run_passes_on_the_models_side(tmp_path):
    model = write_features_model(tmp_path / "left.gmm", [math.pi * i / 6 for i in range(1, 6)])
    r = run("--model", str(model), "--start", "-4,0", "--goal", "4,0", "--person", "0,0,3.141592653589793",
            "--iterations", "8000", "--json")
    assert r.returncode == 0, r.stderr
    path = json.loads(r.stdout)["path"]
    # person faces -x, so their left (theta > 0) is world y < 0
    cross = [y for (x0, y), (x1, _) in zip(path, path[1:]) if x0 < 0 <= x1]
    assert cross and cross[0] < -0.5


@pytest.mark.parametrize("args, message", [
    (["--start", "nan,0", "--goal", "1,1"], "--start"),
    (["--start", "0,0", "--goal", "1,inf"], "--goal"),
    (["--start", "0,0", "--goal", "1,1", "--planner", "rrt"], "unknown planner"),
    (["--start", "0,0", "--goal", "3,3", "--obstacle", "circle:0,0,1"], "start in collision"),
    (["--start", "-3,0", "--goal", "0,0", "--obstacle", "circle:0,0,1"], "goal in collision"),
    (["--start", "0,0", "--goal", "1,1", "--obstacle", "triangle:0,0,1"], "--obstacle"),
    (["--start", "0,0", "--goal", "1,1", "--bias", "1.5"], "--bias"),
    (["--start", "0,0", "--goal", "1,1", "--iterations", "ten"], "--iterations"),
    (["--start", "0,0", "--goal", "1,1", "--bounds", "1,0,0,1"], "--bounds"),
    (["--start", "0,0", "--goal", "1,1", "--planner", "gmm-rrt-star"], "needs --model"),
    (["--model", "/nonexistent/model.gmm", "--start", "0,0", "--goal", "1,1"], "/nonexistent/model.gmm"),
    (["--start", "0,0"], "--goal"),
    (["--start"], "needs a value"),
    (["--start", "0,0", "--goal", "1,1", "--frobnicate"], "unknown option"),
    (["--start", "0,0", "--goal", "1,1", "--delta", "-1"], "--delta '-1': config.delta must be finite and >= 0"),
    (["--start", "0,0", "--goal", "1,1", "--delta", "nan"], "--delta"),
    (["--start", "0,0", "--goal", "1,1", "--w-task", "-1"], "--w-task"),
    (["--start", "0,0", "--goal", "1,1", "--rewire-k", "-1"], "--rewire-k"),
    (["--start", "0,0", "--goal", "1,1", "--rewire-k", "x"], "--rewire-k"),
    (["--start", "0,0", "--goal", "1,1", "--informed", "2"], "--informed"),
    (["--start", "0,0", "--goal", "1,1", "--bias", "1.5"], "--bias '1.5': config.gmm_bias must be in [0, 1]"),
    (["--start", "0,0", "--goal", "1,1", "--robot-radius", "-0.1"], "--robot-radius '-0.1': config.robot_radius_m"),
])
def test_bad_input_is_refused_with_a_clear_error(args, message):
    r = run(*args)
    assert r.returncode == 1
    assert r.stdout == ""
    assert message in r.stderr
    assert "error" in r.stderr


def test_corrupt_model_is_refused(tmp_path):
    model = write_features_model(tmp_path / "m.gmm", [1.0, 2.0])
    data = bytearray(model.read_bytes())
    data[40] ^= 0x10
    model.write_bytes(bytes(data))
    r = run("--model", str(model), "--start", "-4,0", "--goal", "4,0", "--person", "0,0,0")
    assert r.returncode == 1 and r.stdout == ""
    assert "CRC" in r.stderr or "checksum" in r.stderr


def test_xy_planner_with_features_model_is_a_mismatch(tmp_path):
    model = write_features_model(tmp_path / "m.gmm", [1.0])
    r = run("--model", str(model), "--planner", "gmm-rrt", "--start", "-4,0", "--goal", "4,0",
            "--person", "0,0,0")
    assert r.returncode == 1
    assert "model" in r.stderr


def test_no_path_exits_3():
    # the goal is walled in: a ring of boxes around it
    walls = ["--obstacle", "box:3,1,2.2,0.2,0", "--obstacle", "box:3,-1,2.2,0.2,0",
             "--obstacle", "box:2,0,0.2,2.2,0", "--obstacle", "box:4,0,0.2,2.2,0"]
    r = run("--start", "-3,0", "--goal", "3,0", "--robot-radius", "0", *walls, "--iterations", "2000", "--json")
    assert r.returncode == 3
    out = json.loads(r.stdout)
    assert out["status"] != "ok" and out["path"] == [] and out["stats"]["best_cost"] is None
    assert "no path" in r.stderr


def test_cost_history_is_the_best_cost_after_each_improvement():
    """--json stats.cost_history: [iteration, best cost] at every improvement, iterations increasing
    within the cap, costs decreasing, the last one the reported best cost; and the best cost of a run
    capped at N equals the history of a longer run with the same seed read at N (what Fig. 1 uses)."""
    r = run(*DISC, "--iterations", "3000", "--seed", "7", "--json")
    assert r.returncode == 0, r.stderr
    st = json.loads(r.stdout)["stats"]
    hist = st["cost_history"]
    assert st["cost_history_complete"] is True
    assert len(hist) >= 2
    its = [h[0] for h in hist]
    costs = [h[1] for h in hist]
    assert all(1 <= i <= 3000 for i in its) and its == sorted(set(its))
    assert all(b < a for a, b in zip(costs, costs[1:]))
    assert costs[-1] == st["best_cost"]
    for cap in (its[0], its[len(its) // 2] + 1, 1500):
        short = json.loads(run(*DISC, "--iterations", str(cap), "--seed", "7", "--json").stdout)["stats"]
        expected = [c for i, c in hist if i <= cap][-1]
        assert short["best_cost"] == expected, f"cap {cap}"


def test_delta_and_w_task_change_the_objective(tmp_path):
    """--w-task 0 leaves only length (best cost = path length); a larger --delta than the model's
    0.001 pulls a 'left' model's path (components at d = 1.2 m) farther from the person."""
    model = write_features_model(tmp_path / "left.gmm", [math.pi * i / 6 for i in range(1, 6)])
    base = ["--model", str(model), "--start", "-4,0", "--goal", "4,0", "--person", "0,0,3.141592653589793",
            "--iterations", "6000", "--json"]
    st = json.loads(run(*base, "--w-task", "0").stdout)["stats"]
    assert st["best_cost"] == pytest.approx(st["length_m"], rel=1e-6)

    def closest(*extra):
        out = json.loads(run(*base, *extra).stdout)
        return min(math.hypot(x, y) for x, y in out["path"])
    assert closest("--delta", "0.1") > closest() + 0.15


def test_search_flags_take_effect():
    """--informed 0 and --rewire-k 0 (radius rewiring) plan the disc problem too, and each
    changes the search: the same seed then gives other cost histories. The bounds are tight and
    the tree dense enough that the step_m disc holds more nodes than the k-nearest set takes;
    on a sparser tree both near sets are 'every node within step_m' and the searches agree."""
    base = ["--start", "-5,0", "--goal", "5,0", "--obstacle", "circle:0,0,2", "--robot-radius", "0",
            "--bounds", "-6,-3,6,3", "--iterations", "6000", "--json"]
    hist = {}
    for name, extra in (("default", []), ("plain", ["--informed", "0"]), ("radius", ["--rewire-k", "0"])):
        r = run(*base, *extra)
        assert r.returncode == 0, r.stderr
        out = json.loads(r.stdout)
        assert out["status"] == "ok"
        hist[name] = out["stats"]["cost_history"]
    assert hist["default"] != hist["plain"]
    assert hist["default"] != hist["radius"]
