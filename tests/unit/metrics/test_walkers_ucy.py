"""tools/walkers_ucy.py: the UCY replay's pieces on hand-made tracks (interpolation, the crowd a plan
sees, replaying a path against where people really were), and one end-to-end closed loop through
gmmrrt-plan with a walker crossing the robot's line."""
import math
import os
from pathlib import Path

import numpy as np
import pytest
from tool_script import load_tool_script

BIN = Path(os.environ.get("GMMRRT_BIN_DIR", "build/bin")) / "gmmrrt-plan"


W = load_tool_script("walkers_ucy")


def test_position_interpolates_and_is_none_outside_the_track():
    tr = {10: (0.0, 0.0), 11: (0.4, 0.0)}
    assert np.allclose(W.position(tr, 10.5), [0.2, 0.0])
    assert np.allclose(W.position(tr, 11.0), [0.4, 0.0])
    assert W.position(tr, 9.5) is None and W.position(tr, 11.5) is None


def test_crowd_velocity_heading_radius_and_speed_clip():
    walking = {0: (0.0, 1.0), 1: (0.4, 1.0)}        # 1 m/s along +x
    ending = {0: (2.0, -1.0)} | {-1: (2.0, -1.4)}     # last step: +y at 1 m/s (from the step before)
    jump = {0: (1.0, 2.0), 1: (1.0, 4.0)}             # 5 m/s: a tracking jump, clipped to 3 m/s
    far = {0: (0.0, 30.0), 1: (0.0, 30.4)}
    crowd = W.crowd_at([walking, ending, jump, far], 0.0, (-5.0, 0.0), (5.0, 0.0))
    assert len(crowd) == 3  # the far one is beyond CROWD_RADIUS_M
    by_x = {round(c[0], 3): c for c in crowd}
    x, y, yaw, vx, vy = by_x[0.0]
    assert (vx, vy) == pytest.approx((1.0, 0.0)) and yaw == pytest.approx(0.0)
    assert by_x[2.0][3:] == pytest.approx((0.0, 1.0))
    assert math.hypot(*by_x[1.0][3:]) == pytest.approx(3.0)


def test_replay_measures_against_the_real_tracks_at_the_robots_time():
    # Robot from (-2, 0) to (2, 0) at 1 m/s; a pedestrian crossing x = 0 at t = 2 s (step 5).
    tr = {k: (0.0, -2.0 + 0.4 * k) for k in range(0, 11)}
    assert W.replay([(-2.0, 0.0), (2.0, 0.0)], 1.0, 0, [tr]) == pytest.approx(0.0, abs=0.06)
    # The same pedestrian one second later: the robot has passed.
    late = {k + 3: v for k, v in tr.items()}
    assert W.replay([(-2.0, 0.0), (2.0, 0.0)], 1.0, 0, [late]) > 0.5


def test_closed_loop_with_prediction_keeps_clear_of_a_constant_velocity_walker():
    if not BIN.exists():
        pytest.fail(f"{BIN} is missing: build the project first (tools/run build)")
    # A walker at 0.6 m/s crossing the robot's line where the robot will be (as planner.drivable).
    tr = {k: (1.0, 3.0 - 0.6 * 0.4 * k) for k in range(0, 60)}
    closest, status = W.closed_loop(str(BIN), (-4.0, 0.0), (4.0, 0.0), 1.0, 0, [tr], 1, True)
    assert status == "ok"
    assert closest > W.CONTACT_M
    blind, _ = W.closed_loop(str(BIN), (-4.0, 0.0), (4.0, 0.0), 1.0, 0, [tr], 1, False)
    assert blind < closest
