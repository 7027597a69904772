"""Metrics on geometry with known answers (tools/gmmrrt_tools/metrics.py; paper Sect. 5.2, eqs. (2)-(4))."""
import math

import numpy as np
import pytest

from gmmrrt_tools import metrics as m


def test_tdm_uses_polyline_segments_not_only_vertices():
    # Planned path: two vertices only; demo points lie on the segment between them -> distance 0.
    planned = [[0.0, 0.0], [10.0, 0.0]]
    demo = [[1.0, 0.0], [5.0, 0.0], [9.0, 0.0]]
    assert m.tdm_pair(demo, planned) == pytest.approx(0.0, abs=1e-12)
    # With vertex-only distances this would be 1, 5, 1 -> mean 7/3; the segment reading gives 0.
    assert m.tdm_pair(demo, planned) != pytest.approx(7.0 / 3.0)


def test_tdm_parallel_offset_line_is_the_offset():
    planned = [[0.0, 0.0], [4.0, 0.0]]
    demo = np.column_stack((np.linspace(0, 4, 9), np.full(9, 0.3)))
    assert m.tdm_pair(demo, planned) == pytest.approx(0.3)


def test_tdm_beyond_segment_end_measures_to_endpoint():
    planned = [[0.0, 0.0], [1.0, 0.0]]
    demo = [[4.0, 4.0]]  # closest point is the end (1, 0): distance 5
    assert m.tdm_pair(demo, planned) == pytest.approx(5.0)


def test_tdm_is_mean_over_demo_points_not_symmetric():
    planned = [[0.0, 0.0], [2.0, 0.0]]
    demo = [[0.0, 1.0], [2.0, 3.0]]
    assert m.tdm_pair(demo, planned) == pytest.approx(2.0)
    # reversed roles: planned points (0,0) -> 1, (2,0) -> dist to segment (0,1)-(2,3)
    d = abs(2 - 0 + 1) / math.sqrt(2)  # line y = x + 1 through both demo points
    assert m.tdm_pair(planned, demo) == pytest.approx((1.0 + d) / 2)


def test_tdm_single_point_planned_path():
    assert m.tdm_pair([[3.0, 4.0]], [[0.0, 0.0]]) == pytest.approx(5.0)


def test_eq3_mean_over_all_pairs():
    d1 = [[0.0, 1.0], [1.0, 1.0]]
    d2 = [[0.0, 3.0], [1.0, 3.0]]
    p1 = [[0.0, 0.0], [1.0, 0.0]]
    p2 = [[0.0, 2.0], [1.0, 2.0]]
    # pairs: (d1,p1)=1 (d1,p2)=1 (d2,p1)=3 (d2,p2)=1 -> 1.5
    assert m.tdm([d1, d2], [p1, p2]) == pytest.approx(1.5)
    t, le = m.per_plan_tdm_le([d1, d2], [p1, p2])
    assert np.mean(t) == pytest.approx(1.5)
    assert list(t) == pytest.approx([2.0, 1.0])


def test_length_error_eq4():
    demo = [[0.0, 0.0], [4.0, 0.0]]                 # length 4
    planned = [[0.0, 0.0], [0.0, 3.0], [4.0, 3.0]]  # length 7
    assert m.length_error_pair(demo, planned) == pytest.approx(0.75)
    short = [[0.0, 0.0], [3.0, 0.0]]                # length 3 -> 0.25
    assert m.length_error([demo], [planned, short]) == pytest.approx(0.5)


def test_zero_length_demo_is_an_error():
    with pytest.raises(ValueError, match="zero length"):
        m.length_error_pair([[1.0, 1.0], [1.0, 1.0]], [[0.0, 0.0], [1.0, 0.0]])


@pytest.mark.parametrize("bad", [[], [[np.nan, 0.0]], [[1.0, 2.0, 3.0]], [[np.inf, 1.0]]])
def test_bad_paths_are_rejected(bad):
    with pytest.raises(ValueError):
        m.path_length(bad)


def test_min_distance_to_person_on_segment_interior():
    path = [[-5.0, 1.0], [5.0, 1.0]]
    assert m.min_distance_to_people(path, [[0.0, 0.0, 0.0]]) == pytest.approx(1.0)
    assert m.min_distance_to_people(path, []) == math.inf


def test_fraction_within_exact_chord():
    # Line y = 0.3 through a disc of radius 0.45 at the origin: chord 2*sqrt(0.45^2 - 0.3^2).
    path = [[-5.0, 0.3], [5.0, 0.3]]
    chord = 2 * math.sqrt(0.45 ** 2 - 0.3 ** 2)
    assert m.fraction_within(path, [[0.0, 0.0]], 0.45) == pytest.approx(chord / 10.0)
    chord12 = 2 * math.sqrt(1.2 ** 2 - 0.3 ** 2)
    assert m.fraction_within(path, [[0.0, 0.0]], 1.2) == pytest.approx(chord12 / 10.0)


def test_fraction_within_overlapping_people_counts_once():
    path = [[-5.0, 0.0], [5.0, 0.0]]
    # discs [-1, 1] and [0, 2] overlap: union [-1, 2] = 3 m of 10 m
    assert m.fraction_within(path, [[0.0, 0.0], [1.0, 0.0]], 1.0) == pytest.approx(0.3)
    # far person: nothing inside
    assert m.fraction_within(path, [[0.0, 5.0]], 1.0) == 0.0


def test_smoothness_right_angle_and_straight():
    assert m.smoothness([[0, 0], [1, 0], [2, 0]]) == pytest.approx(0.0)
    assert m.smoothness([[0, 0], [1, 0], [1, 1]]) == pytest.approx(math.pi / 2)
    # zigzag: +90 then -90 -> pi in total (absolute values add)
    assert m.smoothness([[0, 0], [1, 0], [1, 1], [2, 1]]) == pytest.approx(math.pi)
    # duplicate points are ignored, heading change wraps across +-pi
    assert m.smoothness([[0, 0], [1, 0], [1, 0], [0, 0.001]]) == pytest.approx(math.pi, abs=1e-2)


def test_box_distance_and_collisions():
    box = (0.0, 0.0, 2.0, 1.0, 0.0)  # x in [-1, 1], y in [-0.5, 0.5]
    assert m.distance_to_box([[-3.0, 2.0], [3.0, 2.0]], box) == pytest.approx(1.5)
    assert m.distance_to_box([[-3.0, 0.0], [3.0, 0.0]], box) == 0.0  # passes through, no vertex inside
    rotated = (0.0, 0.0, 2.0, 1.0, math.pi / 2)  # now x in [-0.5, 0.5], y in [-1, 1]
    assert m.distance_to_box([[2.0, -3.0], [2.0, 3.0]], rotated) == pytest.approx(1.5)
    line = [[-5.0, 1.0], [5.0, 1.0]]
    assert m.path_collides(line, circles=[(0.0, 0.0, 0.9)]) is False
    assert m.path_collides(line, circles=[(0.0, 0.0, 0.9)], robot_radius_m=0.2) is True
    assert m.path_collides(line, people=[(0.0, 0.5, 0.0)], person_radius_m=0.3) is False
    assert m.path_collides(line, people=[(0.0, 0.5, 0.0)], person_radius_m=0.6) is True
    assert m.path_collides(line, boxes=[(0.0, 0.0, 2.0, 1.0, 0.0)], robot_radius_m=0.4) is False
    assert m.path_collides(line, boxes=[(0.0, 0.0, 2.0, 1.0, 0.0)], robot_radius_m=0.6) is True


def test_outcomes_and_rates():
    line = [[0.0, 0.0], [5.0, 0.0]]
    assert m.outcome("ok", line, (5.0, 0.0)) == m.SUCCESS
    # A drivable path flagged for a tight corner is a path (the core's text for GMMRRT_TIGHT_TURNS).
    assert m.outcome("path turns tighter than the minimum turning radius somewhere", line, (5.0, 0.0)) == m.SUCCESS
    assert m.outcome("ok", line, (5.0, 0.0), circles=[(2.5, 0.0, 0.5)]) == m.COLLISION
    assert m.outcome("timeout", [], (5.0, 0.0)) == m.TIMEOUT
    assert m.outcome("ok", line, (9.0, 0.0)) == m.FAILURE
    r = m.rates([m.SUCCESS, m.SUCCESS, m.TIMEOUT, m.COLLISION])
    assert r == {"success": 0.5, "collision": 0.25, "timeout": 0.25, "failure": 0.0}


def _core_or_skip():
    from gmmrrt_tools import core
    try:
        core.lib()
    except core.CoreNotBuilt as exc:  # pragma: no cover - only without a build
        pytest.fail(f"libgmmrrt.so not built: {exc}")
    return core


def test_approach_end_errors():
    _core_or_skip()
    person = (0.0, 0.0, 0.0)  # faces +x; in front is theta = 0
    path = [[3.0, 0.0], [1.0, 0.0]]  # ends 1 m in front, heading straight at the person
    e = m.approach_end(path, person, reference_end=(0.0, 1.2))  # reference: 1.2 m on the left
    assert e.final_distance_m == pytest.approx(1.0)
    assert e.distance_error_m == pytest.approx(0.2)
    assert e.theta_error_rad == pytest.approx(math.pi / 2)
    assert e.heading_error_rad == pytest.approx(0.0, abs=1e-12)
    e2 = m.approach_end([[1.0, -2.0], [1.0, 0.0]], person)  # heading +y, person at -x: 90 deg
    assert e2.heading_error_rad == pytest.approx(math.pi / 2)
    assert math.isnan(e2.theta_error_rad)


def test_passing_side_person_frame():
    _core_or_skip()
    # Person at origin facing -x (towards an oncoming robot from -x). World +y is the person's right.
    person = (0.0, 0.0, math.pi)
    assert m.passing_side([[-5.0, 1.0], [5.0, 1.0]], person) == "right"
    assert m.passing_side([[-5.0, -1.0], [5.0, -1.0]], person) == "left"


def test_swept_angle_and_same_homotopy():
    person = (0.0, 0.0, 0.0)
    above = [[-2.0, 0.0], [0.0, 1.0], [2.0, 0.0]]   # person on the mover's right: clockwise, -pi
    below = [[-2.0, 0.0], [0.0, -1.0], [2.0, 0.0]]  # counter-clockwise, +pi
    assert m.swept_angle(above, person) == pytest.approx(-math.pi)
    assert m.swept_angle(below, person) == pytest.approx(math.pi)
    assert not m.same_homotopy(above, below, person)
    wide = [[-2.0, 0.0], [-1.0, 3.0], [1.0, 3.0], [2.0, 0.0]]
    assert m.same_homotopy(above, wide, person)
    # A path that passes right behind the person (closest point on the axis) still has a side.
    behind = [[-2.0, 2.0], [0.0, 0.3], [2.0, 2.0]]
    assert m.swept_angle(behind, person) < 0 and m.same_homotopy(behind, above, person)


def test_collision_tolerance_for_grazing_paths():
    line = [[-5.0, 0.7998], [5.0, 0.7998]]  # 0.2998 m from the box top edge (y = 0.5)
    box = (0.0, 0.0, 2.0, 1.0, 0.0)
    assert m.path_collides(line, boxes=[box], robot_radius_m=0.3) is True
    assert m.path_collides(line, boxes=[box], robot_radius_m=0.3, tolerance_m=0.01) is False
    assert m.path_collides([[-5.0, 0.7], [5.0, 0.7]], boxes=[box], robot_radius_m=0.3, tolerance_m=0.01) is True


def test_turns_tighter_than_counts_steps_beyond_the_radius():
    # Waypoints every 0.1 m along an arc of radius 0.5 m, the yaw its tangent: what a radius of 0.5 m
    # or less allows, a step too tight for 0.6 m; a kink of 90 degrees is too tight for any radius.
    step = 0.1 / 0.5
    ang = np.arange(0, 12) * step
    arc = np.stack([0.5 * np.sin(ang), 0.5 - 0.5 * np.cos(ang)], axis=1)
    assert m.turns_tighter_than(arc, ang, 0.5) == 0
    assert m.turns_tighter_than(arc, ang, 0.3) == 0
    assert m.turns_tighter_than(arc, ang, 0.6) == len(ang) - 1
    kink = np.array([[0.0, 0.0], [0.1, 0.0], [0.1, 0.1]])
    assert m.turns_tighter_than(kink, [0.0, math.pi / 2, math.pi / 2], 0.1) == 1  # an arc of 0.1 m: 60 deg
    assert m.turns_tighter_than(kink, [0.0, math.pi / 2, math.pi / 2], 0.0) == 0  # turning in place allowed
    with pytest.raises(ValueError, match="yaw has 2 values for 3 waypoints"):
        m.turns_tighter_than(kink, [0.0, 0.0], 0.3)


def test_max_turn_per_step_sees_kinks_and_arcs():
    kink = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]  # a 90 degree corner
    assert m.max_turn_per_step(kink, 0.1) == pytest.approx(math.pi / 2)
    # The same corner on waypoints 1 cm apart: still the whole angle within one 0.1 m step.
    dense = np.concatenate([np.stack([np.linspace(0, 1, 101), np.zeros(101)], 1),
                            np.stack([np.ones(100), np.linspace(0.01, 1, 100)], 1)])
    assert m.max_turn_per_step(dense, 0.1) == pytest.approx(math.pi / 2, abs=1e-9)
    # A quarter circle of radius 0.5 m: about 0.1 / 0.5 rad per 0.1 m (chords of an arc).
    a = np.linspace(0.0, math.pi / 2, 400)
    arc = np.stack([0.5 * np.cos(a), 0.5 * np.sin(a)], 1)
    assert m.max_turn_per_step(arc, 0.1) == pytest.approx(0.2, rel=0.02)
    assert m.max_turn_per_step([[0.0, 0.0], [3.0, 0.0]], 0.1) == 0.0
    with pytest.raises(ValueError):
        m.max_turn_per_step(kink, 0.0)


def test_summed_heading_change_and_arrival_error():
    zigzag = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [2.0, 1.0]]
    assert m.summed_heading_change(zigzag) == pytest.approx(math.pi)
    assert m.arrival_heading_error(zigzag, 0.0) == pytest.approx(0.0)
    assert m.arrival_heading_error(zigzag, math.pi) == pytest.approx(math.pi)
    assert m.arrival_heading_error(zigzag, -0.1, final_yaw=3.1) == pytest.approx(2 * math.pi - 3.2)
    assert math.isnan(m.arrival_heading_error([[1.0, 1.0], [1.0, 1.0]], 0.0))


def test_min_distance_to_predicted_people_uses_the_time_along_the_path():
    path = [[-4.0, 0.0], [4.0, 0.0]]
    # A walker crossing x = 1 at t = 5 s, when a robot at 1 m/s from x = -4 is there too.
    walker = [(1.0, 3.0, 0.0)]
    assert m.min_distance_to_predicted_people(path, walker, [(0.0, -0.6)], 1.0) == pytest.approx(0.0, abs=0.02)
    # Standing: the centre distance of the static metric.
    assert m.min_distance_to_predicted_people(path, walker, [(0.0, 0.0)], 1.0) == pytest.approx(3.0)
    # Past the horizon the walker is held where the horizon leaves them (y = 3 - 0.6 * 2).
    assert m.min_distance_to_predicted_people(path, walker, [(0.0, -0.6)], 1.0, horizon_s=2.0) == \
        pytest.approx(1.8, abs=1e-9)
    assert m.min_distance_to_predicted_people(path, [], [], 1.0) == math.inf
    with pytest.raises(ValueError):
        m.min_distance_to_predicted_people(path, walker, [(math.nan, 0.0)], 1.0)
