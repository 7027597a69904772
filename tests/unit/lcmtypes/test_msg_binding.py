"""lcmtypes.msg_binding: the Python tools judge messages with the daemon's own rules.

gmmrrt_tools.core.validate_message calls lcmtypes/msg_decode.c (build/lib/libgmmrrt_msg.so), so
the replay checker (gmmrrt_tools.replay_check) accepts exactly the inputs gmmrrtd accepts. Here:
valid messages pass, and each rule the old Python copy missed (velocity fields, the goal's yaw,
an approach goal without a person, a NaN circle) gives the daemon's reason code and a reason that
names the field.
"""
import math

import pytest

from gmmrrt_tools import core, replay_check

try:
    from gmmrrt import nav_goal_t, obstacles_t, occupancy_grid_t, people_t, person_t, planar_scan_t, pose2d_t
except ImportError as exc:  # the generated types come with the build
    pytest.fail(f"generated Python message types missing ({exc}): build first (tools/run build)",
                pytrace=False)

OK, DECODE_FAILED, COUNT_OVER_BOUND, NOT_FINITE, BAD_VALUE = 0, 1, 2, 3, 4


def pose(**kw):
    m = pose2d_t()
    m.frame = "map"
    m.utime, m.x, m.y, m.yaw = 1_000_000, 1.0, 2.0, 0.5
    for k, v in kw.items():
        setattr(m, k, v)
    return m.encode()


def goal(**kw):
    m = nav_goal_t()
    m.frame = "map"
    m.goal_id, m.command = 1, nav_goal_t.COMMAND_NEW
    m.utime, m.x, m.y, m.yaw, m.tolerance_m, m.task, m.target_person_id = 1_000_000, 3.0, 0.0, 0.0, 0.3, 1, -1
    for k, v in kw.items():
        setattr(m, k, v)
    return m.encode()


def obstacles(circle_r=0.5, circle_x=0.0):
    m = obstacles_t()
    m.frame = "map"
    m.utime = 1_000_000
    m.num_circles = 1
    m.circle_x = [circle_x] + [0.0] * (obstacles_t.MAX_CIRCLES - 1)
    m.circle_y = [0.0] * obstacles_t.MAX_CIRCLES
    m.circle_radius = [circle_r] + [0.0] * (obstacles_t.MAX_CIRCLES - 1)
    z = [0.0] * obstacles_t.MAX_BOXES
    m.box_x, m.box_y, m.box_width, m.box_height, m.box_yaw = z, z, z, z, z
    return m.encode()


def people(n=1, pid=7):
    m = people_t()
    m.frame = "map"
    m.utime = 1_000_000
    m.num_people = n
    ps = []
    for i in range(people_t.MAX_PEOPLE):
        p = person_t()
        p.utime, p.id = 1_000_000, pid
        ps.append(p)
    m.people = ps
    return m.encode()


def scan(n=4, ranges=None, **kw):
    m = planar_scan_t()
    m.utime, m.rad0, m.radstep, m.range_min_m, m.range_max_m, m.num_ranges = 1_000_000, -1.0, 0.5, 0.1, 10.0, n
    r = list(ranges) if ranges is not None else [1.0] * n
    m.ranges = r + [0.0] * (planar_scan_t.MAX_RANGES - len(r))
    for k, v in kw.items():
        setattr(m, k, v)
    return m.encode()


def test_scan_no_returns_are_kept_and_the_geometry_is_judged():
    """NaN, inf and out-of-range ranges are "no return": the scan is valid. The rules are the C
    decoder's (the binding only reports them)."""
    assert core.validate_message("planar_scan", scan(4, [math.nan, math.inf, -math.inf, 50.0])) == (OK, "")
    assert core.validate_message("planar_scan", scan(planar_scan_t.MAX_RANGES)) == (OK, "")
    code, why = core.validate_message("planar_scan", scan(planar_scan_t.MAX_RANGES + 1))
    assert code == COUNT_OVER_BOUND and "num_ranges" in why
    code, why = core.validate_message("planar_scan", scan(4, radstep=math.nan))
    assert code == NOT_FINITE and "planar_scan_t.radstep" in why
    code, why = core.validate_message("planar_scan", scan(4, range_max_m=0.05))
    assert code == BAD_VALUE and "range_max_m" in why


def grid(w=3, h=2, cells=None, **kw):
    m = occupancy_grid_t()
    m.utime, m.frame, m.resolution_m, m.width, m.height, m.num_cells = 1_000_000, "map", 0.05, w, h, w * h
    c = list(cells) if cells is not None else [0] * (w * h)
    m.data = c + [0] * (occupancy_grid_t.MAX_CELLS - len(c))
    for k, v in kw.items():
        setattr(m, k, v)
    return m.encode()


def test_grid_is_judged_by_the_c_decoder():
    """The daemon's rules for a local grid, through the binding: cells -1..100, sizes that agree,
    a frame by the one rule of every framed type (the receiver's frame only)."""
    assert core.validate_message("occupancy_grid", grid(3, 2, [-1, 0, 50, 65, 100, 0])) == (OK, "")
    code, why = core.validate_message("occupancy_grid", grid(3, 2, [0, 0, 0, 0, 0, 101]))
    assert code == BAD_VALUE and "data[5]" in why
    code, why = core.validate_message("occupancy_grid", grid(3, 2, num_cells=5))
    assert code == BAD_VALUE and "num_cells" in why
    code, why = core.validate_message("occupancy_grid", grid(300, 300, num_cells=90000))
    assert code == COUNT_OVER_BOUND and "MAX_CELLS" in why
    code, why = core.validate_message("occupancy_grid", grid(frame="odom"), frame="map")
    assert code == core.MSG_WRONG_FRAME and "occupancy_grid_t.frame \"odom\"" in why
    assert core.validate_message("occupancy_grid", grid(frame="odom"), frame="odom") == (OK, "")
    code, why = core.validate_message("occupancy_grid", grid(frame=""))
    assert code == BAD_VALUE and "occupancy_grid_t.frame" in why


def test_valid_messages_pass():
    for kind, data in (("pose2d", pose()), ("nav_goal", goal()), ("obstacles", obstacles()), ("people", people())):
        assert core.validate_message(kind, data) == (OK, ""), kind


@pytest.mark.parametrize("kind,data,code,field", [
    ("pose2d", pose(x=math.nan), NOT_FINITE, "pose2d_t.x"),
    ("pose2d", pose(velocity_valid=True, vx=math.inf), NOT_FINITE, "pose2d_t.vx"),
    ("nav_goal", goal(yaw=math.nan), NOT_FINITE, "nav_goal_t.yaw"),
    ("nav_goal", goal(tolerance_m=0.0), BAD_VALUE, "tolerance_m"),
    ("nav_goal", goal(task=2, target_person_id=-1), BAD_VALUE, "target_person_id"),
    ("nav_goal", goal(task=9), BAD_VALUE, "nav_goal_t.task"),
    ("obstacles", obstacles(circle_x=math.nan), NOT_FINITE, "circle_x[0]"),
    ("obstacles", obstacles(circle_r=-1.0), BAD_VALUE, "circle_radius[0]"),
    ("people", people(pid=-3), BAD_VALUE, "id = -3"),
])
def test_each_rule_gives_the_daemons_code_and_names_the_field(kind, data, code, field):
    got, reason = core.validate_message(kind, data)
    assert got == code and field in reason, (got, reason)


def test_truncated_or_foreign_bytes_do_not_decode():
    assert core.validate_message("pose2d", pose()[:-3])[0] == DECODE_FAILED
    assert core.validate_message("nav_goal", pose())[0] == DECODE_FAILED  # wrong fingerprint


def test_unknown_type_is_an_error():
    with pytest.raises(ValueError, match="no validating decoder"):
        core.validate_message("robot_t", b"")


def test_replay_checker_drops_what_the_daemon_rejects():
    assert replay_check._valid("ROBOT_POSE", pose()) is not None
    assert replay_check._valid("ROBOT_POSE", pose(velocity_valid=True, vy=math.nan)) is None
    assert replay_check._valid("NAV_GOAL", goal(task=2, target_person_id=-1)) is None
    assert replay_check._valid("ROBOT_POSE", pose(utime=(1 << 53) + 1)) is None  # the daemon's utime range
    assert replay_check._valid("PLAN", pose()) is None  # not an input channel


def test_frames_and_goal_commands_are_judged_by_the_core():
    """The frame rules (msg_decode.c) and the receiver's frame check (gmmrrt_msg_check_frame) through
    the binding, which also releases each decoded frame (a thousand decodes hold nothing)."""
    UNKNOWN_COMMAND, WRONG_FRAME = 5, core.MSG_WRONG_FRAME
    assert core.validate_message("pose2d", pose(), frame="map") == (OK, "")
    r, why = core.validate_message("pose2d", pose(frame="odom"), frame="map")
    assert r == WRONG_FRAME and '"odom"' in why and '"map"' in why
    assert core.validate_message("pose2d", pose(frame="odom"))[0] == OK  # no receiver frame: any is fine
    for bad in ("", "a b", "x" * 65, "tab\t"):
        r, why = core.validate_message("pose2d", pose(frame=bad))
        assert r == BAD_VALUE and "pose2d_t.frame" in why, (bad, r, why)
    assert core.validate_message("pose2d", pose(frame="x" * 64))[0] == OK
    for command in (0, 3, -1):
        r, why = core.validate_message("nav_goal", goal(command=command))
        assert r == UNKNOWN_COMMAND and "command" in why
    assert core.validate_message("nav_goal", goal(goal_id=0))[0] == BAD_VALUE
    assert core.validate_message("nav_goal", goal(command=nav_goal_t.COMMAND_CANCEL, tolerance_m=0.0))[0] == OK
    assert core.validate_message("nav_goal", goal(yaw_tolerance_rad=float("nan")))[0] == NOT_FINITE
    assert core.validate_message("nav_goal", goal(preferred_side=2))[0] == BAD_VALUE
    for _ in range(1000):
        assert core.validate_message("obstacles", obstacles(), frame="map")[0] == OK
    # The replay checker drops what gmmrrtd refuses: a pose in another frame, a cancel as a goal.
    assert replay_check._valid("ROBOT_POSE", pose(frame="odom")) is None
    assert replay_check._valid("NAV_GOAL", goal(command=nav_goal_t.COMMAND_CANCEL)) is None
    assert replay_check._valid("NAV_GOAL", goal()) is not None
