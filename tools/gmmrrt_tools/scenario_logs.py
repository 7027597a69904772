"""Writes the scenario logs of logs/scenarios/ for gmmrrtd's replay tests.

Each scenario is a small LCM log (lcm.EventLog) of the daemon's inputs: ROBOT_POSE at 10 Hz,
PEOPLE at 5 Hz, OBSTACLES and NAV_GOAL re-sent at 1 Hz, event timestamps equal to the messages'
utime (scan_box: SCAN at 5 Hz, each arriving 50 ms after it was taken, in the floor plan of
logs/maps/, which its index entry's daemon_args give the daemon). scenarios.json (written next to the logs) lists each scenario with what it shows and
the planner_status_t.rejected counters its planted faults must produce, which the replay
checker (tools/gmmrrt_tools/replay_check.py) compares with the daemon's last status.

Deterministic: the same command writes the same bytes.

    .venv/bin/python tools/make_scenarios.py                 # writes logs/scenarios/
    .venv/bin/python tools/make_scenarios.py --out DIR --check   # exit 1 if DIR is stale
"""
import argparse
import json
import math
import os
import struct
import sys
import tempfile

import lcm
from gmmrrt import nav_goal_t, obstacles_t, people_t, person_t, planner_status_t, pose2d_t  # generated (PYTHONPATH)

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))

T0 = 1_700_000_000_000_000  # utime of every scenario's start, us
PERIOD_US = 100_000         # 10 Hz inputs
FRAME = "map"               # gmmrrtd's default [world] frame: every message is in it
R = planner_status_t        # REJECT_* constants


def us(t_s):
    return T0 + int(round(t_s * 1e6))


class Scenario:
    def __init__(self, name, what, duration_s):
        self.name, self.what, self.duration_s = name, what, duration_s
        self.events = []  # (utime, order, channel, bytes)
        self.expected = {}
        self.daemon_args = []  # gmmrrtd flags the replay needs (paths relative to the checkout)

    def add(self, t_s, channel, data, utime=None):
        self.events.append((us(t_s), len(self.events), channel, data if isinstance(data, bytes) else data.encode()))

    def add_at(self, utime, channel, data):
        """An event at an exact utime (us), for inputs whose arrival is not on the 1 ms grid."""
        self.events.append((int(utime), len(self.events), channel, data if isinstance(data, bytes) else data.encode()))

    def expect(self, reason, n):
        self.expected[reason] = self.expected.get(reason, 0) + n

    def write(self, path):
        tmp = path + ".tmp"
        log = lcm.EventLog(tmp, "w", overwrite=True)
        for utime, _, channel, data in sorted(self.events, key=lambda e: (e[0], e[1])):
            log.write_event(utime, channel, data)
        log.close()
        os.replace(tmp, path)


def pose(t_s, x, y, yaw, utime=None):
    m = pose2d_t()
    m.utime = us(t_s) if utime is None else utime
    m.frame = FRAME
    m.x, m.y, m.yaw = float(x), float(y), float(yaw)
    return m


def people(t_s, persons):
    """persons: (id, x, y, yaw, vx, vy)"""
    m = people_t()
    m.utime = us(t_s)
    m.frame = FRAME
    m.num_people = len(persons)
    for i, (pid, x, y, yaw, vx, vy) in enumerate(persons):
        p = person_t()
        p.utime, p.id = m.utime, pid
        p.x, p.y, p.yaw, p.vx, p.vy = float(x), float(y), float(yaw), float(vx), float(vy)
        m.people[i] = p
    return m


def goal(t_s, x, y, task, target=-1, tol=0.3, goal_id=1, yaw=0.0, yaw_tol=0.0, side=0):
    m = nav_goal_t()
    m.utime = us(t_s)
    m.frame = FRAME
    m.goal_id, m.command = goal_id, nav_goal_t.COMMAND_NEW
    m.x, m.y, m.yaw, m.tolerance_m, m.task, m.target_person_id = float(x), float(y), float(yaw), tol, task, target
    m.yaw_tolerance_rad, m.preferred_side = float(yaw_tol), side
    return m


def cancel(t_s, goal_id):
    m = nav_goal_t()
    m.utime = us(t_s)
    m.frame = FRAME
    m.goal_id, m.command = goal_id, nav_goal_t.COMMAND_CANCEL
    return m


def obstacles(t_s, circles=(), boxes=()):
    """circles: (x, y, r); boxes: (x, y, width, height, yaw)"""
    m = obstacles_t()
    m.utime = us(t_s)
    m.frame = FRAME
    m.num_circles, m.num_boxes = len(circles), len(boxes)
    cx, cy, cr = [0.0] * 64, [0.0] * 64, [0.0] * 64
    for i, (x, y, r) in enumerate(circles):
        cx[i], cy[i], cr[i] = x, y, r
    bx, by, bw, bh, byaw = [0.0] * 64, [0.0] * 64, [0.0] * 64, [0.0] * 64, [0.0] * 64
    for i, (x, y, w, h, a) in enumerate(boxes):
        bx[i], by[i], bw[i], bh[i], byaw[i] = x, y, w, h, a
    m.circle_x, m.circle_y, m.circle_radius = cx, cy, cr
    m.box_x, m.box_y, m.box_width, m.box_height, m.box_yaw = bx, by, bw, bh, byaw
    return m


def along(points, speed, t_s):
    """Position and heading at time t_s on a polyline driven at `speed` m/s (stops at the end)."""
    dist = speed * t_s
    for (x0, y0), (x1, y1) in zip(points, points[1:]):
        seg = math.hypot(x1 - x0, y1 - y0)
        yaw = math.atan2(y1 - y0, x1 - x0)
        if dist <= seg:
            f = dist / seg
            return x0 + f * (x1 - x0), y0 + f * (y1 - y0), yaw
        dist -= seg
    (xa, ya), (xb, yb) = points[-2], points[-1]
    return xb, yb, math.atan2(yb - ya, xb - xa)


def fill(sc, robot_path, robot_speed, persons_at, goal_at, obst=None, skip_pose=lambda t: False):
    """The regular traffic: pose every 100 ms, people every 200 ms, obstacles and goal every second."""
    n = int(round(sc.duration_s * 1e6 / PERIOD_US))
    for k in range(n + 1):
        t = k * PERIOD_US * 1e-6
        if not skip_pose(t):
            x, y, yaw = along(robot_path, robot_speed, t)
            sc.add(t, "ROBOT_POSE", pose(t, x, y, yaw))
        if k % 2 == 0:  # 5 Hz: a people_t is 1.6 kB, the logs stay small
            sc.add(t, "PEOPLE", people(t, persons_at(t)))
        if k % 10 == 0:
            if obst is not None:
                sc.add(t, "OBSTACLES", obst(t))
            g = goal_at(t)
            if g is not None:
                sc.add(t, "NAV_GOAL", g)


def walker(pid, x0, y0, vx, vy, yaw=None):
    def at(t):
        return (pid, x0 + vx * t, y0 + vy * t, math.atan2(vy, vx) if yaw is None else yaw, vx, vy)
    return at


AVOID, APPROACH = nav_goal_t.TASK_AVOID, nav_goal_t.TASK_APPROACH


def build_all():
    out = []

    sc = Scenario("avoid_one_person", "avoid: one standing person facing the robot, no obstacles, robot still", 5.0)
    fill(sc, [(0, 0), (1, 0)], 0.0, lambda t: [(1, 4.0, 0.1, math.pi, 0.0, 0.0)], lambda t: goal(t, 8, 0, AVOID))
    out.append(sc)

    sc = Scenario("avoid_moving_robot", "avoid: one person, the robot drives towards the goal past the person", 8.0)
    fill(sc, [(0, 0), (2.0, 0.0), (4.0, 1.4), (6.0, 1.4)], 0.5,
         lambda t: [(1, 4.0, 0.0, math.pi, 0.0, 0.0)], lambda t: goal(t, 8, 0, AVOID))
    out.append(sc)

    obst = [(4.0, -1.7, 0.5)], [(6.2, 1.7, 1.0, 0.6, 0.3)]
    sc = Scenario("avoid_obstacles", "avoid: one person between a circle and a box, robot drives slowly", 6.0)
    fill(sc, [(0, 0), (2, 0)], 0.2, lambda t: [(1, 4.0, 0.0, math.pi, 0.0, 0.0)], lambda t: goal(t, 8, 0, AVOID),
         obst=lambda t: obstacles(t, *obst))
    out.append(sc)

    people_crowd = [walker(1, 3.0, 0.3, 0.0, 0.0, yaw=math.pi), walker(2, 5.0, -2.5, 0.0, 0.3),
                    walker(3, 6.5, 1.8, -0.2, 0.0)]
    sc = Scenario("avoid_crowd", "avoid: three people, two walking, a circle obstacle, robot drives", 8.0)
    fill(sc, [(0, 0), (1.6, -0.2)], 0.2, lambda t: [w(t) for w in people_crowd], lambda t: goal(t, 9, 0, AVOID),
         obst=lambda t: obstacles(t, [(7.5, -1.5, 0.4)]))
    out.append(sc)

    sc = Scenario("approach_person", "approach: person 7 facing the robot, a bystander (id 3), robot still", 5.0)
    fill(sc, [(0, 0), (1, 0)], 0.0,
         lambda t: [(3, 2.5, -1.5, 0.5, 0.0, 0.0), (7, 5.0, 1.0, math.pi, 0.0, 0.0)],
         lambda t: goal(t, 4.0, 1.0, APPROACH, target=7))
    out.append(sc)

    sc = Scenario("approach_obstacles", "approach: person 7 behind a circle and a box, robot drives", 6.0)
    fill(sc, [(0, 0), (1.5, 0)], 0.25, lambda t: [(7, 6.0, 0.0, math.pi, 0.0, 0.0)],
         lambda t: goal(t, 5.0, 0.0, APPROACH, target=7),
         obst=lambda t: obstacles(t, [(3.0, 0.0, 0.4)], [(3.0, 1.6, 0.8, 0.4, 0.0)]))
    out.append(sc)

    out.append(build_faults())
    out.append(build_goal_life())
    out.append(build_scan_box())
    return out


def build_goal_life():
    """Each step of a goal's life, and each refusal of its messages (docs/daemon.md, "The goal's
    life"). The robot stands at the origin until 3 s, then drives to (1.5, 0) at 1 m/s."""
    sc = Scenario("goal_life", "goal lifecycle: cancel, reused id, unknown command, wrong frame, a goal replaced "
                  "while planning, reached on position and heading, failed (goal in an obstacle)", 9.0)
    circle = (6.0, -2.0, 0.5)
    for k in range(int(round(sc.duration_s * 10)) + 1):
        t = k * 0.1
        x = min(max(t - 3.0, 0.0) * 1.0, 1.5)
        sc.add(t, "ROBOT_POSE", pose(t, x, 0.0, 0.0))
        if k % 2 == 0:
            sc.add(t, "PEOPLE", people(t, [(1, 4.0, 0.1, math.pi, 0.0, 0.0)]))
        if k % 10 == 0:
            sc.add(t, "OBSTACLES", obstacles(t, [circle]))
    sc.add(0.0, "NAV_GOAL", goal(0.0, 8.0, 0.0, AVOID, goal_id=1))      # accepted, planning
    sc.add(0.5, "NAV_GOAL", goal(0.5, 8.0, 0.0, AVOID, goal_id=1))      # a re-send: nothing changes
    sc.add(1.0, "NAV_GOAL", cancel(1.0, 1))                              # cancelled: one empty plan
    sc.add(1.2, "NAV_GOAL", cancel(1.2, 1))                              # a re-sent cancel: ignored
    sc.add(1.5, "NAV_GOAL", goal(1.5, 8.0, 0.0, AVOID, goal_id=1))      # a finished id again
    sc.expect(R.REJECT_GOAL_ID_REUSED, 1)
    bad = goal(1.6, 8.0, 0.0, AVOID, goal_id=2)
    bad.command = 3
    sc.add(1.6, "NAV_GOAL", bad)
    sc.expect(R.REJECT_UNKNOWN_COMMAND, 1)
    odom = pose(1.7, 0.0, 0.0, 0.0)
    odom.frame = "odom"
    sc.add(1.7, "ROBOT_POSE", odom)
    sc.expect(R.REJECT_WRONG_FRAME, 1)
    sc.add(2.0, "NAV_GOAL", goal(2.0, 8.0, 0.0, AVOID, goal_id=2))      # planning ...
    sc.add(3.0, "NAV_GOAL", goal(3.0, 1.5, 0.0, AVOID, goal_id=3, yaw=0.0, yaw_tol=0.3))  # ... replaced
    # goal 3 is reached at about 4.2 s (within 0.3 m, heading 0 within 0.3 rad): one empty plan
    sc.add(5.0, "NAV_GOAL", goal(5.0, circle[0], circle[1], AVOID, goal_id=4))  # inside the circle
    sc.expect(R.REJECT_GOAL_IN_COLLISION, 1)                             # and failed 3 s later
    return sc


# scan_box: in the corridor of logs/maps/floor.yaml (y -0.9 .. 0.9 inside its walls) a box that
# is in no map and on no OBSTACLES message appears at BOX_APPEARS_S; only the scans show it.
SCAN_MAP = os.path.join("logs", "maps", "floor.yaml")
SCAN_BOX = (-0.25, 0.25, 0.25, 0.8)    # xmin, ymin, xmax, ymax (m): 0.1 m from the upper wall
SCAN_BOX_APPEARS_S = 2.0
SCAN_ROBOT_PATH = [(-4.0, 0.0), (-1.5, 0.0), (-0.7, -0.4), (0.7, -0.4), (1.5, 0.0), (6.0, 0.0)]
SCAN_GOAL = (6.0, 0.0)


def pose_between_samples(robot_path, speed, t_s):
    """The robot's pose at t_s as the interpolation of its two 10 Hz pose samples around t_s (position
    linearly, heading along the shorter arc): the trajectory the poses describe, which is how the
    daemon places a scan. (The polyline itself turns on the spot at its corners, which no pose shows.)"""
    k = math.floor(t_s / (PERIOD_US * 1e-6) + 1e-9)
    ta, tb = k * PERIOD_US * 1e-6, (k + 1) * PERIOD_US * 1e-6
    (xa, ya, wa), (xb, yb, wb) = along(robot_path, speed, ta), along(robot_path, speed, tb)
    f = (t_s - ta) / (tb - ta)
    dw = math.remainder(wb - wa, 2 * math.pi)
    return xa + f * (xb - xa), ya + f * (yb - ya), wa + f * dw


def scan_traffic(sc, caster, robot_path, speed, box_at, first_scan_s=0.2, period_s=0.2, latency_s=0.05):
    """SCAN every period_s from first_scan_s: each taken latency_s before it arrives (so the poses
    that bracket its stamp have arrived), ray-cast from the robot's pose at its stamp."""
    t = first_scan_s
    while t <= sc.duration_s + 1e-9:
        taken = t - latency_s
        x, y, yaw = pose_between_samples(robot_path, speed, taken)
        sc.add(t, "SCAN", caster.message(us(taken), caster.ranges(x, y, yaw, box_at(taken))))
        t = round(t + period_s, 6)


def build_scan_box():
    from gmmrrt_tools.scan_sim import Caster  # numpy: only the scan scenario needs it
    sc = Scenario("scan_box", "avoid in the floor plan's corridor (--map): a box that only the laser scans "
                  "show appears at 2 s in the robot's way; the plans go round it", 8.0)
    sc.daemon_args = ["--map", SCAN_MAP, "--bounds-margin", "2"]
    caster = Caster(os.path.join(ROOT, SCAN_MAP))
    fill(sc, SCAN_ROBOT_PATH, 0.8, lambda t: [], lambda t: goal(t, SCAN_GOAL[0], SCAN_GOAL[1], AVOID))
    scan_traffic(sc, caster, SCAN_ROBOT_PATH, 0.8, lambda t: [SCAN_BOX] if t >= SCAN_BOX_APPEARS_S else [])
    return sc


def build_faults():
    """Planted faults, each with the counter it must bump (see the table in logs/README.md)."""
    sc = Scenario("faults", "avoid with planted faults: garbage, truncation, count over bound, NaN, bad radius, "
                  "time backwards, wrong type, goal in an obstacle, unknown approach target, unreachable goal "
                  "(walled in), pose gap", 9.0)
    circle = (4.0, -2.0, 0.5)
    room = [(6.0, 4.0, 2.0, 0.2, 0.0), (6.0, 6.0, 2.0, 0.2, 0.0), (5.0, 5.0, 0.2, 2.2, 0.0), (7.0, 5.0, 0.2, 2.2, 0.0)]

    def goal_at(t):  # each change is a new goal id; a finished id is never sent again
        if t < 2.0:
            return goal(t, 8.0, 0.0, AVOID, goal_id=1)
        if t < 3.0:
            return goal(t, circle[0], circle[1], AVOID, goal_id=2)        # inside the circle
        if t < 3.5:
            return goal(t, 8.0, 0.0, AVOID, goal_id=3)
        if t < 4.5:
            return goal(t, 8.0, 0.0, APPROACH, target=99, goal_id=4)     # nobody has id 99
        if t < 6.0:
            return goal(t, 6.0, 5.0, AVOID, goal_id=5)                    # free but walled in
        return goal(t, 8.0, 0.0, AVOID, goal_id=6)

    def goal_at_half_seconds(sc_, t):
        g = goal_at(t)
        sc_.add(t, "NAV_GOAL", g)

    fill(sc, [(0, 0), (1, 0)], 0.0, lambda t: [(1, 4.0, 0.2, math.pi, 0.0, 0.0)], goal_at,
         obst=lambda t: obstacles(t, [circle], room), skip_pose=lambda t: 6.5 <= t < 8.0 - 1e-9)
    # Goal changes that fall between the 1 Hz re-sends.
    for t in (3.5, 4.5):
        goal_at_half_seconds(sc, t)

    sc.add(1.05, "PEOPLE", bytes(range(7, 57)))                                  # garbage bytes
    sc.expect(R.REJECT_DECODE, 1)
    sc.add(1.15, "PEOPLE", people(1.15, [(1, 4.0, 0.2, 0.0, 0.0, 0.0)]).encode()[:30])  # truncated
    sc.expect(R.REJECT_DECODE, 1)
    over = people(1.25, [(1, 4.0, 0.2, 0.0, 0.0, 0.0)])
    over.num_people = people_t.MAX_PEOPLE + 8                                    # count over bound
    sc.add(1.25, "PEOPLE", over)
    sc.expect(R.REJECT_COUNT_OVER_BOUND, 1)
    sc.add(1.35, "ROBOT_POSE", pose(1.35, float("nan"), 0.0, 0.0))               # NaN
    sc.expect(R.REJECT_NOT_FINITE, 1)
    sc.add(1.45, "OBSTACLES", obstacles(1.45, [(4.0, -2.0, -1.0)]))              # radius <= 0
    sc.expect(R.REJECT_BAD_VALUE, 1)
    sc.add(1.55, "ROBOT_POSE", pose(1.55, 0.0, 0.0, 0.0, utime=us(0.55)))       # time going backwards
    sc.expect(R.REJECT_TIME_BACKWARDS, 1)
    sc.add(1.65, "NAV_GOAL", pose(1.65, 8.0, 0.0, 0.0))                          # wrong type on a channel
    sc.expect(R.REJECT_DECODE, 1)
    sc.expect(R.REJECT_GOAL_IN_COLLISION, 1)   # goal inside the circle, 2.0-3.0 s, counted once per goal
    sc.expect(R.REJECT_UNKNOWN_TARGET, 1)      # approach person 99, 3.5-4.5 s
    sc.expect(R.REJECT_GOAL_UNREACHABLE, 1)    # walled-in goal, 4.5-6.0 s
    sc.expect(R.REJECT_POSE_STALE, 1)          # no pose 6.5-8.0 s (limit 0.5 s), counted once per gap
    return sc


REASON_NAMES = {getattr(R, n): n for n in dir(R) if n.startswith("REJECT_")}


def write_all(out_dir):
    os.makedirs(out_dir, exist_ok=True)
    index = {}
    for sc in build_all():
        sc.write(os.path.join(out_dir, sc.name + ".lcmlog"))
        index[sc.name] = {
            "log": sc.name + ".lcmlog",
            "what": sc.what,
            "duration_s": sc.duration_s,
            "expected_rejected": {REASON_NAMES[k]: v for k, v in sorted(sc.expected.items())},
        }
        if sc.daemon_args:
            index[sc.name]["daemon_args"] = sc.daemon_args
    with open(os.path.join(out_dir, "scenarios.json.tmp"), "w") as f:
        json.dump(index, f, indent=2, sort_keys=True)
        f.write("\n")
    os.replace(os.path.join(out_dir, "scenarios.json.tmp"), os.path.join(out_dir, "scenarios.json"))
    return index


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=os.path.join(ROOT, "logs", "scenarios"), help="output folder")
    ap.add_argument("--check", action="store_true", help="exit 1 if the folder differs from what would be written")
    args = ap.parse_args()
    if args.check:
        with tempfile.TemporaryDirectory() as tmp:
            write_all(tmp)
            stale = [n for n in sorted(os.listdir(tmp))
                     if not os.path.exists(os.path.join(args.out, n))
                     or open(os.path.join(tmp, n), "rb").read() != open(os.path.join(args.out, n), "rb").read()]
        if stale:
            print("stale in %s: %s (run tools/make_scenarios.py)" % (args.out, ", ".join(stale)), file=sys.stderr)
            return 1
        print("%s is up to date" % args.out)
        return 0
    index = write_all(args.out)
    for name, e in index.items():
        size = os.path.getsize(os.path.join(args.out, e["log"]))
        print("%-22s %6.1f kB  %s" % (e["log"], size / 1024, e["what"]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
