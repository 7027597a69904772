"""daemon.grid_reuse: gmmrrtd keeps the static obstacles' clearance grid across cycles and
rebuilds it exactly when the obstacles change (docs/daemon.md, "Main loop"; collision.h,
gmmrrt_world_update).

A log is made here (tools/make_scenarios.py helpers): the robot drives towards an avoid goal
past two walking people, OBSTACLES is re-sent every second (as a map server would), and at
t = 3 s a circle appears on the straight line ahead. Replayed with the log clock and an iteration
budget, --log-level debug: the daemon's per-cycle line says whether the grid was built, shifted
(bounds follow the robot) or kept. Built must happen exactly twice (first cycle, the new circle),
and the plans after the change must go around the circle (tools/gmmrrt_tools/replay_check.py
against the obstacles in force), which a stale grid would not do.
"""
import os
import re
import subprocess
import sys

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
from gmmrrt_tools import scenario_logs as ms  # noqa: E402
from gmmrrt_tools import replay_check  # noqa: E402
from gmmrrt_tools.scenario_models import write_models  # noqa: E402

ROBOT_RADIUS, PERSON_RADIUS = 0.3, 0.25
CHANGE_S = 3.0


def gmmrrtd_path():
    path = os.path.join(os.environ.get("GMMRRT_BIN_DIR", os.path.join(ROOT, "build", "bin")), "gmmrrtd")
    if not os.access(path, os.X_OK):
        pytest.fail("gmmrrtd not found at %s (build first: tools/run build)" % path)
    return path


def make_log(path):
    sc = ms.Scenario("grid_reuse", "avoid, robot drives, a circle appears at 3 s", 6.0)
    box = (2.0, -2.0, 1.0, 0.6, 0.3)

    def obst(t):
        circles = [(-1.0, 2.0, 0.5)]
        if t >= CHANGE_S:
            circles.append((5.0, 0.0, 0.6))  # on the straight line from the robot to the goal
        return ms.obstacles(t, circles, [box])

    ms.fill(sc, robot_path=[(0.0, 0.0), (8.0, 0.0)], robot_speed=0.4,
            persons_at=lambda t: [ms.walker(1, 4.0, 1.8, 0.0, -0.2)(t), ms.walker(2, 6.0, -2.0, -0.1, 0.3)(t)],
            goal_at=lambda t: ms.goal(t, 9.0, 0.0, ms.AVOID), obst=obst)
    sc.write(path)


def test_grid_is_kept_while_obstacles_stay_and_rebuilt_when_they_change(tmp_path):
    log, out = str(tmp_path / "in.lcmlog"), str(tmp_path / "out.lcmlog")
    make_log(log)
    models = write_models(str(tmp_path))
    cmd = [gmmrrtd_path(), "--lcm-url", "file://%s?speed=0" % log, "--lcm-out-url", "file://%s?mode=w" % out,
           "--exit-at-eof", "--model-avoid", models["avoid"], "--model-approach", models["approach"],
           "--budget-ms", "0", "--budget-iterations", "1500", "--seed", "3", "--robot-radius", str(ROBOT_RADIUS),
           "--person-radius", str(PERSON_RADIUS), "--log-level", "debug"]
    res = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    assert res.returncode == 0, res.stderr
    kinds = re.findall(r"cycle set-up [0-9.]+ ms \(grid (built|shifted|kept), ([0-9]+) cells\)", res.stderr)
    assert len(kinds) >= 40, "too few planning cycles:\n%s" % res.stderr[-2000:]
    built = [i for i, (k, _) in enumerate(kinds) if k == "built"]
    # Cycle k plans at t = k / 10 s with the inputs up to then: the circle arrives at cycle ~30.
    assert len(built) == 2 and built[0] == 0, "built at cycles %s" % built
    assert abs(built[1] - CHANGE_S * 10) <= 2, "rebuilt at cycle %d, the circle came at %.0f" % (built[1], CHANGE_S * 10)
    n_shifted = sum(1 for k, _ in kinds if k == "shifted")
    n_kept = sum(1 for k, _ in kinds if k == "kept")
    # The grid moves by whole tiles of 8 cells (40 cm at 5 cm), so a shift every few cycles.
    assert n_shifted >= 4, "the bounds follow the driving robot: expected shifts, got %s" % kinds
    assert all(int(c) == 0 for k, c in kinds if k == "kept")
    summary = re.search(r"clearance grid: ([0-9]+) built, ([0-9]+) shifted, ([0-9]+) kept", res.stderr)
    assert summary and tuple(map(int, summary.groups())) == (2, n_shifted, n_kept), res.stderr[-1000:]

    summary, failures = replay_check.check(log, out, rate_hz=10.0, robot_radius=ROBOT_RADIUS,
                                           person_radius=PERSON_RADIUS, expected_rejected={})
    assert not failures, "\n".join(failures)
    assert summary["plans_nonempty"] >= 40, summary
