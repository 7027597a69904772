"""planner.learned_*: GMM-RRT* (paper Sect. 4) with the avoid models learned from logs/demos/ by
gmmrrt-learn. The models are fitted by the
CTest fixture planner.learned_fit (fit_learned_models.py) into $GMMRRT_BUILD_DIR/tests/learned_models.

Scene: a robot walks head-on past a standing person, from 3 m in front of them to 3 m behind (in the
person's frame: person at the origin facing +x, start (3, 0), goal (-3, 0)). The person stands at a
non-trivial world pose so the world <-> person-frame mapping is exercised too. Every run is capped by
iterations (deterministic: same seed, same path), several seeds each.

- side (planner.learned_side): the 'left' model passes on the person's left, the 'right' model on
  their right. The side is the sign of the bearing angle the path sweeps around the person
  (gmmrrt_tools.metrics.swept_angle: +pi = round their left, -pi = round their right).
- clearance (planner.learned_clearance): every path keeps clear of the person: its closest approach
  to the person's centre is >= CLEARANCE_M = 0.6 m (contact is at 0.55 m = robot disc 0.3 +
  person disc 0.25, the planner's defaults: 0.6 m leaves at least 5 cm between the bodies, and the
  robot's centre stays outside Hall's 0.45 m intimate zone) and >= the closest passing distance of
  any demonstration of that side minus DEMO_SLACK_M = 0.1 m (the model must keep roughly what the
  demonstrators kept, not merely avoid contact: plain RRT* passes at ~0.55-0.6 m), and <= the
  farthest closest-approach of those demonstrations plus DEMO_SLACK_M (no needless detour).
- switch (planner.learned_switch, the paper's Fig. 5): with the two-homotopy ('all') model, a wall
  from the person outwards on one side makes every path take the other side, and the path is free
  of the wall and the person.
"""
import json
import math
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

from gmmrrt_tools import core, metrics
from gmmrrt_tools import scenes as S

REPO = Path(__file__).resolve().parents[3]
BIN = Path(os.environ.get("GMMRRT_BIN_DIR", REPO / "build" / "bin"))
MODELS = Path(os.environ.get("GMMRRT_BUILD_DIR", REPO / "build")) / "tests" / "learned_models"

PERSON = (1.0, -0.5, 2.0)          # world pose of the person (x, y [m], yaw [rad])
START_P, GOAL_P = (3.0, 0.0), (-3.0, 0.0)   # person frame
BOUNDS_P = (-4.5, -3.5, 4.5, 3.5)  # person frame; world bounds = the box around its corners
SEEDS = (1, 2, 3, 4)
ITERATIONS = 4000
CLEARANCE_M = 0.6
DEMO_SLACK_M = 0.1
ROBOT_RADIUS_M, PERSON_RADIUS_M = 0.3, 0.25   # gmmrrt-plan defaults


def world(p):
    return core.person_to_world(PERSON, p[0], p[1])


def world_bounds():
    xs, ys = zip(*(world((x, y)) for x in BOUNDS_P[0::2] for y in BOUNDS_P[1::2]))
    return (min(xs), min(ys), max(xs), max(ys))


def wall(side):
    """A box from inside the person's disc outwards on `side` ('left' = +y' in the person frame), 0.4 m
    thick and 8 m long (past the bounds): closes that side, leaves the other open. World cx,cy,w,h,yaw."""
    sign = 1.0 if side == "left" else -1.0
    length = 8.0
    cx, cy = world((0.0, sign * (0.5 * PERSON_RADIUS_M + length / 2)))
    return (cx, cy, 0.4, length, PERSON[2])


def model(name):
    path = MODELS / name
    if not path.is_file():
        pytest.fail(f"{path} missing: the CTest fixture planner.learned_fit makes it "
                    f"(ctest -R planner.learned runs it first)")
    return path


def plan(model_file, seed, boxes=(), planner=None):
    b = world_bounds()
    argv = [str(BIN / "gmmrrt-plan"), "--start", "%r,%r" % world(START_P), "--goal", "%r,%r" % world(GOAL_P),
            "--person", "%r,%r,%r" % PERSON, "--bounds", ",".join(map(repr, b)),
            "--iterations", str(ITERATIONS), "--seed", str(seed), "--json"]
    argv += ["--model", str(model_file)] if model_file else []
    argv += ["--planner", planner] if planner else []
    for box in boxes:
        argv += ["--obstacle", "box:" + ",".join(map(repr, box))]
    proc = subprocess.run(argv, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, f"{' '.join(argv)}: exit {proc.returncode}\n{proc.stderr}"
    obj = json.loads(proc.stdout)
    # A path: "ok", or flagged for a corner tighter than the turning radius (status 45).
    assert obj["status_code"] in (0, 45), obj["status"]
    path = np.asarray(obj["path"], dtype=float)
    assert np.linalg.norm(path[0] - world(START_P)) < 1e-6
    assert np.linalg.norm(path[-1] - world(GOAL_P)) < 0.11   # goal tolerance 0.1 m
    return path


def side(path):
    """'left' / 'right' of the person from the swept bearing (about +pi / -pi for this scene)."""
    a = metrics.swept_angle(path, PERSON)
    assert abs(abs(a) - math.pi) < 0.5, f"swept angle {a:.2f} rad: the path does not go round the person once"
    return "left" if a > 0 else "right"


def demo_passing_distances(homotopy):
    """Closest approach of each avoid demonstration of `homotopy` to its person [m]."""
    eps = [e for e in S.load_demo_logs(str(REPO / "logs" / "demos")) if e.task == "avoid" and e.homotopy == homotopy]
    assert len(eps) >= 5, f"expected the 9 avoid/{homotopy} demonstrations in logs/demos, found {len(eps)}"
    return [float(np.min(np.linalg.norm(e.xy - np.asarray(e.person[:2]), axis=1))) for e in eps]


@pytest.mark.parametrize("homotopy", ["left", "right"])
def test_side(homotopy):
    m = model(f"avoid_{homotopy}.gmm")
    got = [side(plan(m, s)) for s in SEEDS]
    assert got == [homotopy] * len(SEEDS), f"{homotopy} model: sides {got} for seeds {SEEDS}"


@pytest.mark.parametrize("homotopy", ["left", "right", "all"])
def test_clearance(homotopy):
    m = model(f"avoid_{homotopy}.gmm")
    dists = [x for h in (("left", "right") if homotopy == "all" else (homotopy,)) for x in demo_passing_distances(h)]
    demo_min, demo_max = min(dists), max(dists)
    need = max(CLEARANCE_M, demo_min - DEMO_SLACK_M)
    for s in SEEDS:
        path = plan(m, s)
        d = metrics.min_distance_to_people(path, [PERSON])
        print(f"{homotopy} model, seed {s}: closest approach {d:.3f} m (need {need:.3f} .. {demo_max + DEMO_SLACK_M:.3f})")
        assert d >= need, (f"{homotopy} model, seed {s}: passes {d:.3f} m from the person's centre, "
                           f"need >= {need:.3f} m (demonstrations' closest {demo_min:.3f} m - {DEMO_SLACK_M})")
        assert d <= demo_max + DEMO_SLACK_M, (f"{homotopy} model, seed {s}: passes {d:.3f} m from the person, "
                                              f"farther than any demonstration ({demo_max:.3f} m) + {DEMO_SLACK_M}")
        assert not metrics.path_collides(path, people=[PERSON], robot_radius_m=ROBOT_RADIUS_M,
                                         person_radius_m=PERSON_RADIUS_M)


@pytest.mark.parametrize("blocked", ["left", "right"])
def test_switch(blocked):
    m = model("avoid_all.gmm")
    box = wall(blocked)
    other = "right" if blocked == "left" else "left"
    for s in SEEDS:
        path = plan(m, s, boxes=[box])
        assert side(path) == other, f"wall on the {blocked}, seed {s}: the path still passes on the {blocked}"
        assert not metrics.path_collides(path, boxes=[box], people=[PERSON], robot_radius_m=ROBOT_RADIUS_M,
                                         person_radius_m=PERSON_RADIUS_M ), f"seed {s}: collides"
