"""lcmtypes.roundtrip_py: every gmmrrt message type round-trips through the generated Python
package (build/python/gmmrrt), and the wire rules the Python side must respect hold:
fixed-size arrays must be given at full length, a wrong fingerprint does not decode.
(the C side is tests/unit/lcmtypes/test_roundtrip.c.)
"""
import math
import struct

import pytest

try:
    from gmmrrt import (demo_info_t, nav_goal_t, obstacles_t, people_t, person_t, planner_status_t,
                        pose2d_t, waypoints_t)
except ImportError as exc:  # a missing input is a failure, never a skip
    pytest.fail(f"generated Python message types missing ({exc}): build first (tools/run build)",
                pytrace=False)


def _person(i):
    p = person_t()
    p.utime = 1_700_000_000_000_000 + i
    p.id = 100 + i
    p.x, p.y, p.yaw, p.vx, p.vy = 0.5 * i, -0.25 * i, 0.01 * i, 0.1 + i, 0.2 - i
    return p


def make_pose():
    m = pose2d_t()
    m.utime, m.x, m.y, m.yaw = 2**62, 1.25, -2.5, 0.75
    m.velocity_valid, m.vx, m.vy, m.yaw_rate = True, 0.3, -0.1, 0.05
    return m


def make_people():
    m = people_t()
    m.utime = 1_700_000_000_200_000
    m.num_people = people_t.MAX_PEOPLE
    m.people = [_person(i) for i in range(people_t.MAX_PEOPLE)]
    return m


def make_goal():
    m = nav_goal_t()
    m.utime, m.x, m.y, m.yaw, m.tolerance_m = -1, 8.0, 1.5, -0.5, 0.3
    m.task, m.target_person_id = nav_goal_t.TASK_APPROACH, 7
    return m


def make_obstacles():
    m = obstacles_t()
    n_c, n_b = obstacles_t.MAX_CIRCLES, obstacles_t.MAX_BOXES
    m.utime, m.num_circles, m.num_boxes = 1_700_000_000_400_000, n_c, n_b
    m.circle_x = [1.0 + i for i in range(n_c)]
    m.circle_y = [2.0 - i for i in range(n_c)]
    m.circle_radius = [0.1 + 0.01 * i for i in range(n_c)]
    m.box_x = [-1.0 - i for i in range(n_b)]
    m.box_y = [3.0 + i for i in range(n_b)]
    m.box_width = [0.5 + 0.01 * i for i in range(n_b)]
    m.box_height = [0.25 + 0.02 * i for i in range(n_b)]
    m.box_yaw = [0.001 * i for i in range(n_b)]
    return m


def make_waypoints():
    m = waypoints_t()
    n = waypoints_t.MAX_WAYPOINTS
    m.utime, m.seq, m.num_waypoints = 1_700_000_000_500_000, 42, n
    m.x = [0.1 * i for i in range(n)]
    m.y = [-0.05 * i for i in range(n)]
    m.yaw = [0.002 * i for i in range(n)]
    m.total_cost, m.length_m = 12.5, 10.75
    m.planner, m.task, m.status = waypoints_t.PLANNER_GMM_RRT_STAR, nav_goal_t.TASK_AVOID, 40
    return m


def make_status():
    m = planner_status_t()
    m.utime, m.state, m.last_error = 1_700_000_000_600_000, planner_status_t.STATE_STOPPED, 31
    m.iterations, m.nodes = 2**40, 4321
    m.first_solution_ms, m.best_cost, m.plan_time_ms = -1.0, math.inf, 80.0
    m.plans_published, m.missed_deadlines = 99, 2
    m.rejected = [1000 + i for i in range(planner_status_t.NUM_REJECT_REASONS)]
    return m


def make_demo():
    m = demo_info_t()
    m.utime, m.episode, m.task = 1_700_000_000_700_000, 12, nav_goal_t.TASK_AVOID
    m.homotopy, m.person_id = demo_info_t.HOMOTOPY_RIGHT, 3
    return m


MAKERS = [make_pose, make_people, make_goal, make_obstacles, make_waypoints, make_status, make_demo]


def as_plain(msg):
    """The message as nested plain Python values (tuples and lists compare alike)."""
    out = {}
    for name in msg.__slots__:
        v = getattr(msg, name)
        if isinstance(v, (list, tuple)):
            out[name] = [as_plain(e) if hasattr(e, "__slots__") else e for e in v]
        elif hasattr(v, "__slots__"):
            out[name] = as_plain(v)
        else:
            out[name] = v
    return out


@pytest.mark.parametrize("make", MAKERS, ids=lambda f: f.__name__[5:])
def test_every_type_round_trips(make):
    msg = make()
    data = msg.encode()
    back = type(msg).decode(data)
    assert as_plain(back) == as_plain(msg)
    assert back.encode() == data


@pytest.mark.parametrize("make", MAKERS, ids=lambda f: f.__name__[5:])
def test_wrong_fingerprint_does_not_decode(make):
    data = bytearray(make().encode())
    data[0] ^= 0x01
    with pytest.raises(ValueError):
        type(make()).decode(bytes(data))


@pytest.mark.parametrize("make", MAKERS, ids=lambda f: f.__name__[5:])
def test_truncated_message_does_not_decode(make):
    data = make().encode()
    with pytest.raises((ValueError, struct.error)):
        type(make()).decode(data[:-1])


@pytest.mark.parametrize("make,field", [
    (make_obstacles, "circle_x"), (make_obstacles, "box_yaw"),
    (make_waypoints, "x"), (make_waypoints, "yaw"), (make_status, "rejected"),
])
def test_fixed_arrays_must_be_full_length(make, field):
    msg = make()
    setattr(msg, field, list(getattr(msg, field))[:3])
    with pytest.raises(struct.error):
        msg.encode()


def test_people_array_must_be_full_length():
    msg = make_people()
    msg.people = msg.people[:2]
    with pytest.raises((struct.error, IndexError, AssertionError)):
        msg.encode()


def test_default_constructed_messages_encode_at_full_length():
    for cls, field, n in [(people_t, "people", people_t.MAX_PEOPLE),
                          (obstacles_t, "circle_radius", obstacles_t.MAX_CIRCLES),
                          (waypoints_t, "x", waypoints_t.MAX_WAYPOINTS),
                          (planner_status_t, "rejected", planner_status_t.NUM_REJECT_REASONS)]:
        m = cls()
        assert len(getattr(m, field)) == n
        assert len(cls.decode(m.encode()).__getattribute__(field)) == n


def test_constants_match_the_c_limits():
    # planner/include/gmmrrt/limits.h sizes the planner from the same numbers.
    assert people_t.MAX_PEOPLE == 32
    assert obstacles_t.MAX_CIRCLES == 64 and obstacles_t.MAX_BOXES == 64
    assert waypoints_t.MAX_WAYPOINTS == 256
    assert planner_status_t.NUM_REJECT_REASONS == len(make_status().rejected) == 16
    assert planner_status_t.REJECT_MODEL_RELOAD < planner_status_t.NUM_REJECT_REASONS
