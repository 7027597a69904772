"""planner.problem_bounds: one scene, one planning problem. gmmrrt-plan (without --bounds), the
Python tools (gmmrrt_tools.core.problem_bounds, and runner.plan_argv for a scene without its own
workspace) and gmmrrtd (daemon.people_motion, test_planning_bounds_are_the_core_rule, on the same
scene) build the same bounds, by the core's rule (problem_bounds.h): the box around start and goal
grown by the margin; the person and the far circle do not widen it.
"""
import json
import os
import subprocess
from pathlib import Path

import gmmrrt_constants
import pytest

from gmmrrt_tools import core, runner

BIN = Path(os.environ.get("GMMRRT_BIN_DIR", Path(__file__).resolve().parents[3] / "build" / "bin"))
# The scene of daemon.people_motion's bounds case.
START, GOAL, PERSON, CIRCLE = (0.5, -1.0), (5.0, 1.0), (2.0, 3.0, 0.0), (10.0, 10.0, 0.5)
EXPECTED = (-2.5, -4.0, 8.0, 4.0)  # margin 3 m


def plan_bounds(*extra):
    exe = BIN / "gmmrrt-plan"
    if not exe.exists():
        pytest.fail(f"{exe} is missing: build the project first (tools/run build)")
    r = subprocess.run([str(exe), "--start", "%r,%r" % START, "--goal", "%r,%r" % GOAL,
                        "--person", "%r,%r,%r" % PERSON, "--obstacle", "circle:%r,%r,%r" % CIRCLE,
                        "--iterations", "200", "--json", *extra], capture_output=True, text=True, timeout=60)
    assert r.returncode in (0, 3), r.stderr
    return tuple(json.loads(r.stdout)["bounds"])


def test_cli_python_and_runner_build_the_same_bounds():
    assert gmmrrt_constants.GMMRRT_DEFAULT_BOUNDS_MARGIN_M == 3.0
    python = core.problem_bounds(START, GOAL)
    assert python == EXPECTED
    assert plan_bounds() == python
    scene = runner.Scene(START, GOAL, [PERSON], None, circles=[CIRCLE])
    argv = runner.plan_argv(scene, "rrt-star", 1)
    assert tuple(float(v) for v in argv[argv.index("--bounds") + 1].split(",")) == python


def test_the_margin_is_one_setting_and_explicit_bounds_win():
    assert plan_bounds("--bounds-margin", "1.5") == core.problem_bounds(START, GOAL, 1.5) == (-1.0, -2.5, 6.5, 2.5)
    assert plan_bounds("--bounds", "-6,-6,12,12", "--bounds-margin", "1") == (-6.0, -6.0, 12.0, 12.0)


def test_bad_margins_are_refused():
    for bad in (0.0, 0.05, -1.0, 2e4, float("nan"), float("inf")):
        with pytest.raises(ValueError, match="no planning bounds"):
            core.problem_bounds(START, GOAL, bad)
