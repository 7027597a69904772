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
    for opt in ["--model", "--start", "--goal", "--person", "--obstacle", "--planner", "--gmm-bias",
                "--budget-ms", "--iterations", "--seed", "--robot-radius", "--bounds", "--json", "--delta",
                "--w-task", "--rewire-k", "--informed", "--connect", "--map", "cost_history", "setup_ms",
                "--goal-yaw-tolerance", "--min-turn-radius", "--nominal-speed", "--raw-path", "--approach-models",
                "--side", "--side-person", "--task-cost", "--background-model", "--face-target"]:
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
    assert stats["setup_ms"] is not None and stats["setup_ms"] >= 0


MAPS = Path(__file__).resolve().parents[3] / "logs" / "maps"


def test_map_plans_in_the_floor_plan():
    r = run("--map", str(MAPS / "floor.yaml"), "--start", "-9,-2", "--goal", "8,4", "--iterations", "20000", "--json")
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    # A path; through a doorway a corner may have no free arc of the default 0.3 m radius: then the
    # status flags it (45, GMMRRT_TIGHT_TURNS) and the drive report counts it.
    tight = out["drive"]["tight_turns"] + out["drive"]["turns_in_place"]
    assert (out["status_code"], out["status"]) == ((45, "path turns tighter than the minimum turning radius somewhere")
                                                    if tight else (0, "ok"))
    # The first room (x < -3, y < -1) to the far room above the corridor (x > 0, y > 1): through the
    # doorways, so longer than the straight line.
    assert out["stats"]["length_m"] > math.dist((-9, -2), (8, 4)) + 0.5


def test_bad_map_is_refused_naming_the_key(tmp_path):
    (tmp_path / "m.yaml").write_text("image: floor.pgm\nresolution: -1\norigin: [0, 0, 0]\nnegate: 0\n"
                                     "occupied_thresh: 0.65\nfree_thresh: 0.196\n")
    r = run("--map", str(tmp_path / "m.yaml"), "--start", "0,0", "--goal", "1,1")
    assert r.returncode == 1 and r.stdout == ""
    assert "m.yaml:2: key 'resolution'" in r.stderr, r.stderr
    r = run("--map", str(tmp_path / "missing.yaml"), "--start", "0,0", "--goal", "1,1")
    assert r.returncode == 1 and "cannot open map YAML" in r.stderr, r.stderr


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
    (["--start", "0,0", "--goal", "1,1", "--planner", "rrt"], "expected gmm-rrt-star, rrt-star or gmm-rrt"),
    (["--start", "0,0", "--goal", "9,0", "--obstacle", "circle:0,0,6"], "frozen"),
    (["--start", "0,0", "--goal", "4,0", "--person", "2,2,0,0,nan"], "--person"),
    (["--start", "0,0", "--goal", "4,0", "--person", "2,2,0,3.5,0"], "at most 3 m/s"),
    (["--start", "0,0", "--goal", "4,0", "--person", "2,2,0,1"], "--person"),
    (["--start", "0,0", "--goal", "4,0,1", "--goal-yaw-tolerance", "0"], "--goal-yaw-tolerance"),
    (["--start", "0,0", "--goal", "4,0,1", "--goal-yaw-tolerance", "-5"], "--goal-yaw-tolerance"),
    (["--start", "0,0", "--goal", "4,0", "--min-turn-radius", "-1"], "--min-turn-radius"),
    (["--start", "0,0", "--goal", "4,0", "--nominal-speed", "0"], "--nominal-speed"),
    (["--start", "0,0", "--goal", "4,0,nan"], "--goal"),
    (["--start", "-3,0", "--goal", "0,0", "--obstacle", "circle:0,0,1"], "goal in collision"),
    (["--start", "0,0", "--goal", "1,1", "--obstacle", "triangle:0,0,1"], "--obstacle"),
    (["--start", "0,0", "--goal", "1,1", "--gmm-bias", "1.5"], "--gmm-bias"),
    (["--start", "0,0", "--goal", "1,1", "--bias", "0.5"], "--bias was renamed --gmm-bias"),
    (["--start", "0,0", "--goal", "1,1", "--cost", "paper"], "--cost was renamed --task-cost"),
    (["--start", "0,0", "--goal", "1,1", "--face-target=2"], "--face-target"),
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
    (["--start", "0,0", "--goal", "1,1", "--connect", "2"], "--connect '2': config.connect_first: \"2\" is not a switch (0 or 1)"),
    (["--start", "0,0", "--goal", "1,1", "--max-nodes", "1"], "--max-nodes '1': config.max_nodes must be in 2..4194304"),
    (["--start", "0,0", "--goal", "1,1", "--max-nodes", "99999999"], "--max-nodes"),
    (["--start", "0,0", "--goal", "1,1", "--max-nodes", "1e4"], "--max-nodes"),
    (["--start", "0,0", "--goal", "1,1", "--side", "up"], "--side"),
    (["--start", "0,0", "--goal", "1,1", "--side-person", "-1"], "--side-person"),
    (["--start", "0,0", "--goal", "3,3", "--person", "1,1,0", "--side-person", "1"], "--side-person"),
    (["--start", "0,0", "--goal", "1,1", "--task-cost", "max"], "--task-cost 'max'"),
    (["--start", "0,0", "--goal", "1,1", "--background-model", "/nonexistent/bg.gmm"], "/nonexistent/bg.gmm"),
    (["--start", "0,0", "--goal", "1,1", "--gmm-bias", "1.5"], "--gmm-bias '1.5': config.gmm_bias must be in [0, 1]"),
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


def test_full_pool_is_pruned_and_a_pool_full_without_a_path_is_flagged():
    # With a path, a full pool is pruned and the search runs its whole budget.
    r = run(*DISC, "--iterations", "20000", "--max-nodes", "300", "--json")
    assert r.returncode == 0, r.stderr
    stats = json.loads(r.stdout)["stats"]
    assert stats["pool_full"] is False and stats["max_nodes"] == 300
    assert stats["nodes"] <= 300 and stats["pruned"] > 0 and stats["iterations"] == 20000
    assert "filled" not in r.stderr

    # Without a path nothing can be pruned: the run ends early, flagged, with the way out named.
    r = run(*DISC, "--iterations", "20000", "--max-nodes", "10", "--json")
    assert r.returncode == 3, r.stderr
    stats = json.loads(r.stdout)["stats"]
    assert stats["pool_full"] is True and stats["max_nodes"] == 10
    assert stats["nodes"] <= 10 and stats["iterations"] < 20000
    assert "node pool (10 nodes) filled" in r.stderr and "--max-nodes" in r.stderr

    r = run(*DISC, "--iterations", "20000", "--max-nodes", "100000", "--json")
    assert r.returncode == 0, r.stderr
    stats = json.loads(r.stdout)["stats"]
    assert stats["pool_full"] is False and stats["max_nodes"] == 100000 and stats["pruned"] == 0
    assert stats["iterations"] == 20000 and "filled" not in r.stderr


@pytest.mark.parametrize("model_task,flag,other", [(2, "avoid", "approach"), (1, "approach", "avoid")])
def test_model_of_the_other_task_is_refused_naming_both(tmp_path, model_task, flag, other):
    model = write_features_model(tmp_path / "m.gmm", [1.0, 2.0], task=model_task)
    r = run("--model", str(model), "--task", flag, "--start", "-4,0", "--goal", "4,0", "--person", "0,0,0",
            "--iterations", "100")
    assert r.returncode == 1 and r.stdout == ""
    assert "--task %s" % flag in r.stderr and "learned for task %s" % other in r.stderr, r.stderr
    # The model's own task still plans.
    r = run("--model", str(model), "--task", other, "--start", "-4,0", "--goal", "4,0", "--person", "0,0,0",
            "--iterations", "300")
    assert r.returncode in (0, 3) and "learned for task" not in r.stderr, r.stderr


def test_background_cost_needs_a_background_only_under_a_planner_that_uses_it(tmp_path):
    """--task-cost background with a model file that has no background: RRT* (length cost only,
    the task cost never read) plans; GMM-RRT* (the default with --model) is refused, the
    background named."""
    model = write_features_model(tmp_path / "plain.gmm", [1.0, 2.0])
    common = ["--model", str(model), "--start", "-4,0", "--goal", "4,0", "--person", "0,0,0",
              "--task-cost", "background", "--iterations", "300", "--seed", "3"]
    r = run(*common, "--planner", "rrt-star")
    assert r.returncode == 0, r.stderr
    r = run("--start", "0,0", "--goal", "1,1", "--task-cost", "background", "--iterations", "300")
    assert r.returncode == 0, r.stderr
    for planner in ([], ["--planner", "gmm-rrt-star"]):
        r = run(*common, *planner)
        assert r.returncode == 1 and r.stdout == ""
        assert "--task-cost background needs a background model" in r.stderr, r.stderr


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
    st = json.loads(run(*base, "--w-task", "0", "--raw-path").stdout)["stats"]
    assert st["best_cost"] == pytest.approx(st["length_m"], rel=1e-6)

    def closest(*extra):
        out = json.loads(run(*base, *extra).stdout)
        return min(math.hypot(x, y) for x, y in out["path"])
    assert closest("--delta", "0.1") > closest() + 0.15


def _turn_per_m(path):
    worst = 0.0
    for a, b, c in zip(path, path[1:], path[2:]):
        la, lb = math.dist(a, b), math.dist(b, c)
        if la < 1e-3 or lb < 1e-3:
            continue
        t = math.atan2(c[1] - b[1], c[0] - b[0]) - math.atan2(b[1] - a[1], b[0] - a[0])
        t = abs(math.atan2(math.sin(t), math.cos(t)))
        worst = max(worst, t / (0.5 * (la + lb)))
    return worst


def test_start_in_collision_escapes_with_exit_0():
    r = run("--start", "0,0", "--goal", "4,0", "--person", "0.35,0.1,3.14", "--iterations", "2000", "--json")
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    assert out["status_code"] == 43 and out["status"].startswith("escaping")
    assert "person 0" in out["drive"]["escape"]
    assert out["path"][0] == [0.0, 0.0] and out["path"][-1] == [4.0, 0.0]


def test_goal_yaw_turn_radius_and_walkers_take_effect():
    """--goal x,y,yaw arrives within --goal-yaw-tolerance; --min-turn-radius bounds the turn per
    metre of the printed path; a walker (--person with vx,vy) is kept clear of where they will be."""
    base = ["--start", "-4,0", "--goal", "2,0,1.5707963", "--iterations", "3000", "--json",
            "--goal-yaw-tolerance", "5"]
    for radius in ("0.3", "0.8"):
        out = json.loads(run(*base, "--min-turn-radius", radius).stdout)
        assert out["drive"]["arrival_met"] and out["drive"]["arrival_error_deg"] <= 5.0
        assert abs(out["yaw"][-1] - math.pi / 2) <= math.radians(5.0)
        assert out["drive"]["tight_turns"] == 0
        assert _turn_per_m(out["path"]) <= 1.02 / float(radius)
    walker = ["--start", "-4,0", "--goal", "4,0", "--person", "1,3,-1.5708,0,-0.6", "--nominal-speed", "1",
              "--iterations", "4000", "--json"]
    out = json.loads(run(*walker).stdout)
    assert out["drive"]["walker_conflict"] is False
    assert out["drive"]["min_walker_clearance_m"] > 0.15
    standing = json.loads(run(*walker[:5], "1,3,-1.5708", *walker[6:]).stdout)
    assert standing["drive"]["min_walker_clearance_m"] is None  # nobody walks: nothing predicted


APPROACH_NAMES = ["1-front", "2-45_right", "3-90_right", "4-135_right", "5-back", "6-135_left", "7-90_left",
                  "8-45_left"]


def test_approach_model_set_picks_the_start_direction_and_refuses_a_missing_one(tmp_path):
    for k, name in enumerate(APPROACH_NAMES):  # direction k's components at its own bearing
        write_features_model(tmp_path / f"{name}.gmm", [math.remainder(-k * math.pi / 4, 2 * math.pi)], task=2)
    base = ["--approach-models", str(tmp_path), "--person", "0,0,0", "--goal", "1.2,0", "--iterations", "1500",
            "--json"]
    for start, name in (("-3,0.2", "5-back"), ("0.3,-3", "3-90_right"), ("3,2.5", "8-45_left")):
        r = run(*base, "--start", start)
        assert r.returncode == 0, r.stderr
        out = json.loads(r.stdout)
        assert out["approach_model"] == name
        assert out["drive"]["arrival_met"]  # approach arrives facing the person by default
        assert abs(math.atan2(math.sin(out["yaw"][-1] - math.pi), math.cos(out["yaw"][-1] - math.pi))) <= \
            math.radians(15)
    # --face-target=0: no turn to face the person at the end; the path arrives on its own tangent
    # (from the right side, about 73 degrees, far from the 180 that faces the person).
    for flag, facing in (("--face-target=0", False), ("--face-target=1", True), ("--face-target", True)):
        r = run(*base, "--start", "0.3,-3", flag)
        assert r.returncode == 0, r.stderr
        yaw = json.loads(r.stdout)["yaw"][-1]
        off = abs(math.atan2(math.sin(yaw - math.pi), math.cos(yaw - math.pi)))
        assert (off <= math.radians(15)) == facing, (flag, math.degrees(yaw))
    (tmp_path / "6-135_left.gmm").unlink()
    r = run(*base, "--start", "-3,0.2")
    assert r.returncode == 1 and r.stdout == ""
    assert "6-135_left.gmm" in r.stderr and "--approach-models" in r.stderr


def test_search_flags_take_effect():
    """--informed 0, --connect 0 and --rewire-k 0 (radius rewiring) plan the disc problem too, and each
    changes the search: the same seed then gives other cost histories. The bounds are tight and
    the tree dense enough that the step_m disc holds more nodes than the k-nearest set takes;
    on a sparser tree both near sets are 'every node within step_m' and the searches agree."""
    base = ["--start", "-5,0", "--goal", "5,0", "--obstacle", "circle:0,0,2", "--robot-radius", "0",
            "--bounds", "-6,-3,6,3", "--iterations", "6000", "--json"]
    hist = {}
    for name, extra in (("default", []), ("plain", ["--informed", "0"]), ("radius", ["--rewire-k", "0"]),
                        ("no-connect", ["--connect", "0"])):
        r = run(*base, *extra)
        assert r.returncode == 0, r.stderr
        out = json.loads(r.stdout)
        assert out["status"] == "ok"
        hist[name] = out["stats"]["cost_history"]
    assert hist["default"] != hist["plain"]
    assert hist["default"] != hist["radius"]
    assert hist["default"] != hist["no-connect"]


def test_side_is_kept_and_either_reports_both_sides(tmp_path):
    """The left-only model prefers world y < 0 (the person faces -x); --side right still passes at
    y > 0; --side either plans both and answers with the cheaper (the model's side), both costed;
    a wall on the preferred side gives the side status and exit 3."""
    model = write_features_model(tmp_path / "left.gmm", [math.pi * i / 6 for i in range(1, 6)])
    base = ["--model", str(model), "--start", "-4,0", "--goal", "4,0", "--person", "0,0,3.141592653589793",
            "--iterations", "4000", "--json"]

    def crossing(path):
        return [y for (x0, y), (x1, _) in zip(path, path[1:]) if x0 < 0 <= x1][0]

    r = run(*base, "--side", "right")
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    assert out["side"] == "right" and crossing(out["path"]) > 0.5
    # The sides are the tree's paths: compare the chosen one with --raw-path's answer.
    r = run(*base, "--side", "either", "--raw-path")
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    sides = out["sides"]
    assert crossing(sides["left"]["path"]) < -0.5 and crossing(sides["right"]["path"]) > 0.5
    assert sides["left"]["cost"] < sides["right"]["cost"]
    assert out["side"] == "left" and out["path"] == sides["left"]["path"]
    wall = ["--obstacle", "box:0,-3,0.4,4.4,0", "--bounds", "-6,-5,6,5"]
    r = run(*base, *wall, "--side", "left")
    assert r.returncode == 3
    out = json.loads(r.stdout)
    assert out["status"] == "no path on the preferred side" and out["path"] == []


def test_cost_choice_changes_the_plan(tmp_path):
    """Start and goal 2.5 m to the side of the person, the model's support at 1.2 m: the paper's cost
    bends the path in, the inward cost does not; the default is the paper's."""
    model = write_features_model(tmp_path / "both.gmm", [math.pi * i / 6 for i in range(-5, 6) if i])
    base = ["--model", str(model), "--start", "-4,2.5", "--goal", "4,2.5", "--person", "0,0,3.141592653589793",
            "--iterations", "6000", "--gmm-bias", "0.5", "--bounds", "-6,-4,6,5", "--json"]
    closest = {}
    for cost in ("paper", "inward", None):
        r = run(*base, *(["--task-cost", cost] if cost else []))
        assert r.returncode == 0, r.stderr
        closest[cost] = min(math.hypot(x, y) for x, y in json.loads(r.stdout)["path"])
    assert closest["paper"] < 2.0 < 2.3 < closest["inward"]
    assert closest[None] == closest["paper"]
