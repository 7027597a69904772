"""fault.*: fault-injection replays of gmmrrtd. Each test builds an input log with
planted faults (on top of the scenario tooling of tools/make_scenarios.py), replays it through
the daemon deterministically (file:// in and out, log clock, iteration budget) and checks with
tools/gmmrrt_tools/replay_check.py that

  * the daemon stays up and exits cleanly (no sanitizer report: in build-asan this is the
    ASan + UBSan + LeakSanitizer gmmrrtd),
  * it keeps its rate: one cycle per period of input time, whatever the input does,
  * every plan it publishes is valid (starts at the robot, ends at the goal, collision-free),
  * planner_status_t.rejected[] equals exactly the faults planted, and during each planning
    fault the status says which one (state and last_error).

Run one: ctest --test-dir build -R '^fault\\.' --output-on-failure
"""
import math
import random
import struct

import pytest
from tests.common.daemon_fixture import run_log_clock

from gmmrrt import planner_status_t
from gmmrrt_tools import replay_check
from gmmrrt_tools import scenario_logs as ms

R = planner_status_t
AVOID, APPROACH = ms.AVOID, ms.APPROACH
CIRCLE, BOX = (4.0, -1.7, 0.5), (6.2, 1.7, 1.0, 0.6, 0.3)
PERSON = (1, 4.0, 0.0, math.pi, 0.0, 0.0)


def base(name, duration_s=4.0, goal_at=None, persons_at=None, skip_pose=lambda t: False, obst=None):
    """The avoid_obstacles traffic: robot drives slowly past a person, a circle and a box."""
    sc = ms.Scenario(name, "fault replay " + name, duration_s)
    ms.fill(sc, [(0, 0), (2, 0)], 0.2, persons_at or (lambda t: [PERSON]),
            goal_at or (lambda t: ms.goal(t, 8, 0, AVOID)),
            obst=obst or (lambda t: ms.obstacles(t, [CIRCLE], [BOX])), skip_pose=skip_pose)
    return sc


def replay(gmmrrtd, models, tmp_path, sc, min_plans_frac=0.3, iterations=300):
    in_log, out_log = str(tmp_path / (sc.name + ".lcmlog")), str(tmp_path / "out.lcmlog")
    sc.write(in_log)
    run_log_clock(gmmrrtd, models, in_log, out_log, iterations=iterations)
    summary, failures = replay_check.check(in_log, out_log, rate_hz=10.0, robot_radius=0.3, person_radius=0.25,
                                           expected_rejected={replay_check.REASONS[k]: v
                                                              for k, v in sc.expected.items()})
    assert not failures, "\n".join(failures)
    assert summary["plans_nonempty"] >= min_plans_frac * summary["cycles"], summary
    statuses = [(u, planner_status_t.decode(d)) for u, c, d in replay_check.read_events(out_log)
                if c == "PLANNER_STATUS"]
    return summary, statuses


def statuses_between(statuses, t0_s, t1_s):
    lo, hi = ms.us(t0_s), ms.us(t1_s)
    return [s for _, s in statuses if lo <= s.utime < hi]


def set_bytes(data, offset, raw):
    return data[:offset] + raw + data[offset + len(raw):]


# LCM encodings are big-endian: 8-byte fingerprint, then the fields in order: utime, the frame
# ("map": a 4-byte length counting the NUL, then 4 bytes), then the type's own fields.
OFF_FIRST_FIELD = 24
OFF_GOAL_X = OFF_FIRST_FIELD + 8 + 1  # nav_goal_t: goal_id (int64) and command (int8) come first


def test_corrupted_bytes(gmmrrtd, models, tmp_path):
    sc = base("corrupted_bytes")
    rng = random.Random(9)
    good = {"ROBOT_POSE": ms.pose(0, 0, 0, 0).encode(), "PEOPLE": ms.people(0, [PERSON]).encode(),
            "NAV_GOAL": ms.goal(0, 8, 0, AVOID).encode(), "OBSTACLES": ms.obstacles(0, [CIRCLE], [BOX]).encode()}
    channels = sorted(good)
    t = 0.55
    for k in range(24):  # a flipped fingerprint byte: every channel, every byte of it
        ch = channels[k % 4]
        data = bytearray(good[ch])
        data[k % 8] ^= 1 << rng.randrange(8)
        sc.add(t, ch, bytes(data))
        sc.expect(R.REJECT_DECODE, 1)
        t += 0.05
    for ch in channels:  # random bytes of the right length, and another type's message
        sc.add(t, ch, bytes(rng.randrange(256) for _ in range(len(good[ch]))))
        sc.add(t + 0.01, ch, good[channels[(channels.index(ch) + 1) % 4]])
        sc.expect(R.REJECT_DECODE, 2)
        t += 0.05
    # Counts flipped to negative and to over the bound (int32 right after utime).
    sc.add(t, "PEOPLE", set_bytes(ms.people(t, [PERSON]).encode(), OFF_FIRST_FIELD, struct.pack(">i", -1)))
    sc.add(t + 0.01, "PEOPLE", set_bytes(ms.people(t, [PERSON]).encode(), OFF_FIRST_FIELD, struct.pack(">i", 1 << 30)))
    sc.add(t + 0.02, "OBSTACLES", set_bytes(ms.obstacles(t, [CIRCLE]).encode(), OFF_FIRST_FIELD, struct.pack(">i", 65)))
    sc.expect(R.REJECT_COUNT_OVER_BOUND, 3)
    # NaN and Inf written into the first double (pose x, goal x) as raw bytes.
    sc.add(t + 0.03, "ROBOT_POSE", set_bytes(ms.pose(t, 0, 0, 0).encode(), OFF_FIRST_FIELD, struct.pack(">d", math.nan)))
    sc.add(t + 0.04, "NAV_GOAL", set_bytes(ms.goal(t, 8, 0, AVOID).encode(), OFF_GOAL_X, struct.pack(">d", math.inf)))
    sc.expect(R.REJECT_NOT_FINITE, 2)
    # Values in range for the wire, out of range for the planner.
    sc.add(t + 0.05, "OBSTACLES", ms.obstacles(t, [CIRCLE], [(6.2, 1.7, -1.0, 0.6, 0.3)]).encode())
    sc.add(t + 0.06, "NAV_GOAL", ms.goal(t, 8, 0, 7).encode())  # unknown task
    sc.add(t + 0.07, "NAV_GOAL", ms.goal(t, 8, 0, APPROACH, target=-4).encode())
    sc.expect(R.REJECT_BAD_VALUE, 3)
    # utimes outside 0..2^53 us: would overflow the clock arithmetic (found by fuzz_daemon_inputs).
    sc.add(t + 0.08, "ROBOT_POSE", ms.pose(t, 0, 0, 0, utime=-5))
    sc.add(t + 0.09, "ROBOT_POSE", ms.pose(t, 0, 0, 0, utime=1 << 62))
    sc.add(t + 0.10, "PEOPLE", set_bytes(ms.people(t, [PERSON]).encode(), 8, struct.pack(">q", -(1 << 63))))
    sc.expect(R.REJECT_BAD_VALUE, 3)
    replay(gmmrrtd, models, tmp_path, sc)


def test_truncated_messages(gmmrrtd, models, tmp_path):
    sc = base("truncated")
    good = [("ROBOT_POSE", ms.pose(0, 0, 0, 0).encode()), ("PEOPLE", ms.people(0, [PERSON]).encode()),
            ("NAV_GOAL", ms.goal(0, 8, 0, AVOID).encode()), ("OBSTACLES", ms.obstacles(0, [CIRCLE]).encode())]
    t = 0.52
    for ch, data in good:  # every channel cut at 0, 1, 7, 8, 15, 16, half and one byte short
        for cut in sorted({0, 1, 7, 8, 15, 16, len(data) // 2, len(data) - 1}):
            sc.add(t, ch, data[:cut])
            sc.expect(R.REJECT_DECODE, 1)
            t += 0.04
    # Trailing bytes after a complete message are not an error for LCM: accepted, as documented.
    t += 0.013
    x, y, yaw = ms.along([(0, 0), (2, 0)], 0.2, t)
    sc.add(t, "ROBOT_POSE", ms.pose(t, x, y, yaw).encode() + b"\0" * 9)
    replay(gmmrrtd, models, tmp_path, sc)


def test_duplicated_and_out_of_order_timestamps(gmmrrtd, models, tmp_path):
    sc = base("timestamps")
    for k in range(10):  # duplicates: the same pose twice, then a copy with the same utime
        t = 1.0 + 0.1 * k + 0.01
        x, y, yaw = ms.along([(0, 0), (2, 0)], 0.2, 1.0 + 0.1 * k)
        sc.add(t, "ROBOT_POSE", ms.pose(1.0 + 0.1 * k, x, y, yaw))
        sc.add(t, "ROBOT_POSE", ms.pose(1.0 + 0.1 * k, x, y, yaw))
    for k in range(5):  # out of order: a pose 250 ms older than the last one, on every channel
        t = 2.05 + 0.2 * k
        x, y, yaw = ms.along([(0, 0), (2, 0)], 0.2, t - 0.25)
        sc.add(t, "ROBOT_POSE", ms.pose(t, x, y, yaw, utime=ms.us(t - 0.25)))
    sc.expect(R.REJECT_TIME_BACKWARDS, 5)
    late_people = ms.people(2.4, [PERSON])
    sc.add(2.95, "PEOPLE", late_people)
    sc.add(3.05, "NAV_GOAL", ms.goal(2.0, 8, 0, AVOID))  # one from before the 3.0 s re-send
    late_obst = ms.obstacles(2.5, [CIRCLE], [BOX])
    sc.add(3.1, "OBSTACLES", late_obst)
    sc.expect(R.REJECT_TIME_BACKWARDS, 3)
    replay(gmmrrtd, models, tmp_path, sc)


def test_floods_of_poses_and_obstacles(gmmrrtd, models, tmp_path):
    """1 kHz poses and 100 obstacle messages per second (alternating content, so each one is a
    change the daemon must take in): still one cycle per period, nothing rejected."""
    sc = base("flood", duration_s=3.0)
    for k in range(3000):
        t = k * 1e-3 + 0.0005
        x, y, yaw = ms.along([(0, 0), (2, 0)], 0.2, t)
        sc.add(t, "ROBOT_POSE", ms.pose(t, x, y, yaw))
    for k in range(300):
        t = k * 0.01 + 0.003
        r = CIRCLE[2] + (0.02 if k % 2 else 0.0)
        sc.add(t, "OBSTACLES", ms.obstacles(t, [(CIRCLE[0], CIRCLE[1], r)], [BOX]))
    summary, _ = replay(gmmrrtd, models, tmp_path, sc)
    assert summary["cycles"] >= 29, summary


def test_people_appearing_and_vanishing(gmmrrtd, models, tmp_path):
    """Bystanders come and go every 200 ms (0 to 5 of them, ids reused); the approach target
    vanishes for a second: stops saying UNKNOWN_TARGET (counted once for the goal), then plans again."""
    spots = [(2, 3.0, 2.2), (3, 5.0, -2.6), (4, 6.5, 2.6), (5, 2.0, -2.5), (6, 7.5, -2.4)]

    def persons_at(t):
        k = int(round(t / 0.2))
        out = [(pid, x, y, 0.0, 0.0, 0.0) for i, (pid, x, y) in enumerate(spots) if (k >> i) & 1]
        if not 1.5 <= t < 2.5:
            out.append((7, 6.0, 0.0, math.pi, 0.0, 0.0))
        return out

    sc = base("people_churn", duration_s=4.0, persons_at=persons_at,
              goal_at=lambda t: ms.goal(t, 5.0, 0.0, APPROACH, target=7))
    for k in range(20):  # PEOPLE at 10 Hz here, between the regular 5 Hz ones
        t = 0.1 + 0.2 * k
        sc.add(t, "PEOPLE", ms.people(t, persons_at(t)))
    sc.expect(R.REJECT_UNKNOWN_TARGET, 1)
    _, statuses = replay(gmmrrtd, models, tmp_path, sc)
    gone = statuses_between(statuses, 1.7, 2.5)
    assert gone and all(s.state == R.STATE_STOPPED and s.last_error == 52 for s in gone), \
        [(s.state, s.last_error) for s in gone]
    back = statuses_between(statuses, 2.8, 4.0)
    assert any(s.state == R.STATE_PLANNING for s in back), [(s.state, s.last_error) for s in back]


def test_goal_inside_an_obstacle(gmmrrtd, models, tmp_path):
    """The goal moves into the box, then into the circle, then out again: each bad goal is
    counted once, each cycle meanwhile stops with GMMRRT_ERR_GOAL_IN_COLLISION (31)."""
    def goal_at(t):
        if 1.0 <= t < 2.0:
            return ms.goal(t, BOX[0], BOX[1], AVOID)
        if 2.0 <= t < 3.0:
            return ms.goal(t, CIRCLE[0], CIRCLE[1], AVOID)
        return ms.goal(t, 8, 0, AVOID)

    sc = base("goal_in_obstacle", duration_s=4.5, goal_at=goal_at)
    sc.expect(R.REJECT_GOAL_IN_COLLISION, 2)
    _, statuses = replay(gmmrrtd, models, tmp_path, sc, min_plans_frac=0.2)
    bad = statuses_between(statuses, 1.1, 3.0)
    assert bad and all(s.state == R.STATE_STOPPED and s.last_error == 31 for s in bad), \
        [(s.state, s.last_error) for s in bad]
    assert any(s.state == R.STATE_PLANNING for s in statuses_between(statuses, 3.3, 4.5))


def test_goal_beyond_the_clearance_grid(gmmrrtd, models, tmp_path):
    """A goal 60 m away on both axes: the planning box (66 x 66 m at 5 cm) needs more cells than
    the default grid (2^20, 51 x 51 m). Counted once (REJECT_PLANNING_BOX), each cycle stops with
    gmmrrtd's code 54 in STATE_ERROR, and a goal in reach plans again. (It used to publish status
    2 every cycle with no counter and no log line.)"""
    def goal_at(t):
        return ms.goal(t, 60, 60, AVOID) if 1.0 <= t < 2.0 else ms.goal(t, 8, 0, AVOID)

    sc = base("goal_beyond_grid", duration_s=3.5, goal_at=goal_at)
    sc.expect(R.REJECT_PLANNING_BOX, 1)
    _, statuses = replay(gmmrrtd, models, tmp_path, sc, min_plans_frac=0.2)
    bad = statuses_between(statuses, 1.1, 2.0)
    assert bad and all(s.state == R.STATE_ERROR and s.last_error == 54 for s in bad), \
        [(s.state, s.last_error) for s in bad]
    assert bad[-1].stops[R.STOP_PLANNING_BOX] >= len(bad)
    assert any(s.state == R.STATE_PLANNING for s in statuses_between(statuses, 2.3, 3.5))


def test_unreachable_goal(gmmrrtd, models, tmp_path):
    """A free goal walled in by four boxes: no path; after unreachable_after_cycles cycles the
    goal is counted unreachable (once), stops say NO_PATH_YET (40); a reachable goal plans again."""
    room = [(6.0, 4.0, 2.0, 0.2, 0.0), (6.0, 6.0, 2.0, 0.2, 0.0), (5.0, 5.0, 0.2, 2.2, 0.0), (7.0, 5.0, 0.2, 2.2, 0.0)]

    def goal_at(t):
        return ms.goal(t, 6.0, 5.0, AVOID) if 1.0 <= t < 2.5 else ms.goal(t, 8, 0, AVOID)

    sc = base("unreachable", duration_s=4.0, goal_at=goal_at,
              obst=lambda t: ms.obstacles(t, [CIRCLE], [BOX] + room))
    sc.expect(R.REJECT_GOAL_UNREACHABLE, 1)
    _, statuses = replay(gmmrrtd, models, tmp_path, sc, min_plans_frac=0.2)
    walled = statuses_between(statuses, 1.05, 2.5)
    assert walled and all(s.state == R.STATE_STOPPED for s in walled), [(s.state, s.last_error) for s in walled]
    assert walled[-1].last_error == 40, walled[-1].last_error
    assert any(s.state == R.STATE_PLANNING for s in statuses_between(statuses, 2.8, 4.0))


def test_no_leaks_or_memory_errors_under_valgrind(gmmrrtd, models, tmp_path):
    """The plain build's daemon through a log with every kind of bad message under valgrind's
    memcheck: no invalid access, no definite or indirect leak (exit 1 otherwise). Registered only
    in builds without ASan (fault.valgrind); the ASan build runs LeakSanitizer on every fault test."""
    import shutil
    valgrind = shutil.which("valgrind")
    if valgrind is None:
        pytest.fail("valgrind is not installed (tools/run setup installs it)")
    sc = base("valgrind", duration_s=2.0)
    good = ms.people(0, [PERSON]).encode()
    sc.add(0.55, "PEOPLE", good[:40])
    sc.add(0.65, "PEOPLE", set_bytes(good, OFF_FIRST_FIELD, struct.pack(">i", 1 << 30)))
    sc.add(0.75, "ROBOT_POSE", set_bytes(ms.pose(0.75, 0, 0, 0).encode(), OFF_FIRST_FIELD, struct.pack(">d", math.nan)))
    sc.add(0.85, "NAV_GOAL", b"\xff" * 60)
    sc.add(0.95, "ROBOT_POSE", ms.pose(0.95, 0, 0, 0, utime=ms.us(0.2)))
    sc.expect(R.REJECT_DECODE, 2)
    sc.expect(R.REJECT_COUNT_OVER_BOUND, 1)
    sc.expect(R.REJECT_NOT_FINITE, 1)
    sc.expect(R.REJECT_TIME_BACKWARDS, 1)
    in_log, out_log = str(tmp_path / "in.lcmlog"), str(tmp_path / "out.lcmlog")
    sc.write(in_log)
    stderr = run_log_clock(gmmrrtd, models, in_log, out_log, iterations=300,
                           wrapper=(valgrind, "--leak-check=full", "--errors-for-leak-kinds=definite,indirect",
                                    "--error-exitcode=1", "--quiet"))
    assert "Invalid" not in stderr and "definitely lost" not in stderr, stderr[-4000:]
    _, failures = replay_check.check(in_log, out_log, expected_rejected={replay_check.REASONS[k]: v
                                                                         for k, v in sc.expected.items()})
    assert not failures, "\n".join(failures)


def test_far_away_obstacles_and_people(gmmrrtd, models, tmp_path):
    """Finite but huge coordinates are valid on the wire: a circle, a box and a person 1e300 m
    away change nothing (the clearance grid once converted them to int: UB, found by
    tests/fuzz/fuzz_daemon_inputs; the plain and ASan builds replay this, the fuzz build's
    UBSan checks the conversion itself)."""
    def obst(t):
        return ms.obstacles(t, [CIRCLE, (1e300, -1e300, 0.5)], [BOX, (-1e300, 1e300, 1e300, 2.0, 0.3)])

    def persons_at(t):
        return [PERSON, (2, 1e300, 1e300, 0.0, 0.0, 0.0)]

    sc = base("far_away", duration_s=3.0, obst=obst, persons_at=persons_at)
    replay(gmmrrtd, models, tmp_path, sc)
