"""Checks gmmrrtd's output against the input it was given.

Reads an input log (a scenario of logs/scenarios/) and the daemon's output log (PLAN and
PLANNER_STATUS, written by gmmrrtd's file:// output or recorded by lcm-logger), rebuilds what
the daemon knew at each cycle from the valid inputs, and checks that

  * every non-empty plan starts at the robot pose it names (waypoints_t.utime),
  * ends within the goal's tolerance of the goal in force and was made for its task,
  * is collision-free: robot disc against circles, oriented boxes and people (discs), with no
    tolerance beyond floating-point rounding (CLEARANCE_SLACK_M): the planner refuses any tree
    edge that comes within 1 mm of an obstacle or person, and every published chord passes the
    same check (planner/src/path.c), so a plan's clearance is >= 0 exactly. The checker samples
    each chord every 2 cm, so it can miss a violation between samples but never invent one. A
    people list the daemon reports stale (planner_status_t.stale_inputs) was dropped: the plan
    is checked without people then,
  * every empty plan (a stop) carries a non-zero status saying why,
  * cycles come at the promised rate (log clock: one per period of input time; live: the
    median interval between status messages within 15 % of the period),
  * the last status's rejected[] counters equal the planted faults (scenarios.json).

It also makes a summary (counts, mean path length and cost) for golden comparisons.

    python -m gmmrrt_tools.replay_check IN.lcmlog OUT.lcmlog [--expected scenarios.json --scenario NAME]
"""
import argparse
import bisect
import json
import math
import statistics
import sys

import gmmrrt_constants  # generated beside the message package (tools/constants/)
import lcm
from gmmrrt import nav_goal_t, obstacles_t, people_t, planner_status_t, pose2d_t, waypoints_t

from gmmrrt_tools import core

REASONS = {getattr(planner_status_t, n): n for n in dir(planner_status_t) if n.startswith("REJECT_")}
# Rounding between this Python and the planner's C, m; not a safety margin (module comment).
CLEARANCE_SLACK_M = 1e-6
# waypoints_t.status of an escape: GMMRRT_ESCAPE of planner/include/gmmrrt/status.h, a wire-stable code.
ESCAPE_STATUS = gmmrrt_constants.GMMRRT_ESCAPE
# How much an escape's sampled clearance may dip (the core keeps the exact clearance from falling
# along its straight exit; samples of the smoothed path near the exit's end may differ by rounding).
ESCAPE_SLACK_M = 1e-3
# Walking people as gmmrrtd predicts them with its defaults (planner.h, read by the compiler into
# gmmrrt_constants), which the replays do not override.
STANDING_SPEED_M_S = gmmrrt_constants.GMMRRT_STANDING_SPEED_M_S
NOMINAL_SPEED_M_S = gmmrrt_constants.GMMRRT_DEFAULT_NOMINAL_SPEED_M_S
PREDICTION_HORIZON_S = gmmrrt_constants.GMMRRT_DEFAULT_PREDICTION_HORIZON_S
LIVE_INPUTS = ("ROBOT_POSE", "PEOPLE", "NAV_GOAL", "OBSTACLES")


def read_events(path):
    log = lcm.EventLog(path, "r")
    out = [(e.timestamp, e.channel, e.data) for e in log]
    log.close()
    return out


FRAME = "map"  # gmmrrtd's default [world] frame (docs/daemon.md): a message in another is refused
MAX_UTIME = gmmrrt_constants.GMMRRTD_MAX_UTIME  # gmmrrtd takes utimes in 0..this only (planner/daemon/clock.h)

# Input channel -> (validating decoder of lcmtypes/msg_decode.c, generated Python decoder).
INPUTS = {"ROBOT_POSE": ("pose2d", pose2d_t), "PEOPLE": ("people", people_t),
          "NAV_GOAL": ("nav_goal", nav_goal_t), "OBSTACLES": ("obstacles", obstacles_t)}


def _valid(channel, data):
    """The message decoded when gmmrrtd would accept it on its own, else None. The message rules are
    the daemon's own (gmmrrt_msg_decode_* through gmmrrt_tools.core), never a copy of them."""
    kind = INPUTS.get(channel)
    if kind is None or core.validate_message(kind[0], data, frame=FRAME)[0] != 0:
        return None
    m = kind[1].decode(data)
    if channel == "NAV_GOAL" and m.command != nav_goal_t.COMMAND_NEW:
        return None  # a cancel names a goal, it is none
    return m if 0 <= m.utime <= MAX_UTIME else None


class Timeline:
    """The valid inputs of one channel in utime order (older-than-last messages dropped, as gmmrrtd does)."""

    def __init__(self):
        self.utimes, self.msgs = [], []

    def add(self, m):
        if self.utimes and m.utime < self.utimes[-1]:
            return
        self.utimes.append(m.utime)
        self.msgs.append(m)

    def latest_before(self, utime, inclusive=False):
        i = (bisect.bisect_right if inclusive else bisect.bisect_left)(self.utimes, utime)
        return self.msgs[i - 1] if i > 0 else None

    def by_utime(self, utime):
        i = bisect.bisect_left(self.utimes, utime)
        return self.msgs[i] if i < len(self.utimes) and self.utimes[i] == utime else None


def read_inputs(path):
    lines = {c: Timeline() for c in ("ROBOT_POSE", "PEOPLE", "NAV_GOAL", "OBSTACLES")}
    first = last = None
    for _, channel, data in read_events(path):
        if channel not in lines:
            continue
        m = _valid(channel, data)
        if m is None:
            continue
        lines[channel].add(m)
        first = m.utime if first is None else min(first, m.utime)
        last = m.utime if last is None else max(last, m.utime)
    return lines, first, last


def read_outputs(path, plan_channel="PLAN", status_channel="PLANNER_STATUS"):
    """Cycles as (status_event_timestamp, status, plan or None): a plan belongs to the status after it."""
    cycles, pending = [], None
    for ts, channel, data in read_events(path):
        if channel == plan_channel:
            pending = waypoints_t.decode(data)
        elif channel == status_channel:
            cycles.append((ts, planner_status_t.decode(data), pending))
            pending = None
    return cycles


def _dist_point_box(px, py, b):
    x, y, w, h, yaw = b
    c, s = math.cos(yaw), math.sin(yaw)
    dx, dy = px - x, py - y
    lx, ly = c * dx + s * dy, -s * dx + c * dy
    ex, ey = max(abs(lx) - w / 2, 0.0), max(abs(ly) - h / 2, 0.0)
    if ex == 0.0 and ey == 0.0:
        return -min(w / 2 - abs(lx), h / 2 - abs(ly))
    return math.hypot(ex, ey)


def _person_gap(px, py, q, t):
    """Centre distance from (px, py) to person q = (x, y, vx, vy) when the robot is there at t s: a
    standing person where they are; a walker where constant velocity takes them (gmmrrtd plans
    against that, planner.h "Walking people"), not judged beyond the prediction horizon."""
    qx, qy, vx, vy = q
    if math.hypot(vx, vy) < STANDING_SPEED_M_S:
        return math.hypot(px - qx, py - qy)
    if t > PREDICTION_HORIZON_S:
        return math.inf
    return math.hypot(px - (qx + vx * t), py - (qy + vy * t))


def plan_clearance(plan, obstacles, people, robot_radius, person_radius, step=0.02, escape=False):
    """Smallest clearance (m) of the robot disc along the plan: (static, people).

    An escape (waypoints_t.status == ESCAPE_STATUS: the robot starts inside a person's disc or an
    inflated obstacle) is judged from where it is out: before that, the clearance may only grow
    (a sample lower than the one before is returned as the worst, so it fails like a collision)."""
    circles = [(obstacles.circle_x[i], obstacles.circle_y[i], obstacles.circle_radius[i])
               for i in range(obstacles.num_circles)] if obstacles else []
    boxes = [(obstacles.box_x[i], obstacles.box_y[i], obstacles.box_width[i], obstacles.box_height[i],
              obstacles.box_yaw[i]) for i in range(obstacles.num_boxes)] if obstacles else []
    persons = [(p.x, p.y, p.vx, p.vy) for p in people.people[:people.num_people]] if people else []
    samples = []
    s_m = 0.0  # arc length of the sample along the plan
    n = plan.num_waypoints
    for i in range(max(n - 1, 1)):
        x0, y0 = plan.x[i], plan.y[i]
        x1, y1 = (plan.x[i + 1], plan.y[i + 1]) if n > 1 else (x0, y0)
        k = max(1, int(math.ceil(math.hypot(x1 - x0, y1 - y0) / step)))
        for j in range(k + 1):
            px, py = x0 + (x1 - x0) * j / k, y0 + (y1 - y0) * j / k
            s_j = s_m + math.hypot(x1 - x0, y1 - y0) * j / k
            cs = min([math.hypot(px - cx, py - cy) - r - robot_radius for cx, cy, r in circles] +
                     [_dist_point_box(px, py, b) - robot_radius for b in boxes] + [math.inf])
            cp = min([_person_gap(px, py, q, s_j / NOMINAL_SPEED_M_S) - person_radius - robot_radius
                      for q in persons] + [math.inf])
            samples.append((cs, cp))
        s_m += math.hypot(x1 - x0, y1 - y0)
    worst_static, worst_people = math.inf, math.inf
    first = 0
    if escape:
        prev = -math.inf
        while first < len(samples) and min(samples[first]) < 0.0:
            c = min(samples[first])
            if c < prev - ESCAPE_SLACK_M:  # the way out went deeper: report that depth
                return (c, math.inf) if samples[first][0] <= samples[first][1] else (math.inf, c)
            prev = max(prev, c)
            first += 1
    for cs, cp in samples[first:]:
        worst_static, worst_people = min(worst_static, cs), min(worst_people, cp)
    return worst_static, worst_people


def _live_candidates(recorded):
    """Live: for each plan (by its position in the recording), the inputs the daemon may have
    planned with. The recording (lcm-logger on the same multicast group) holds the inputs and the
    outputs in the order they reached one socket: the daemon had received the pose its plan
    names before planning and published the plan after, so the goal, people and obstacles in
    force were among those valid ones recorded from the last one before that pose up to the plan.
    Order, not time: nothing here races a stalled player."""
    out = {}
    latest = {c: None for c in LIVE_INPUTS}
    since = {c: [] for c in LIVE_INPUTS}
    pose_pos = {}  # pose utime -> snapshot of the latest inputs when it was recorded
    for _, channel, data in recorded:
        if channel in LIVE_INPUTS:
            m = _valid(channel, data)
            if m is None:
                continue
            if channel == "ROBOT_POSE":
                pose_pos[m.utime] = {c: len(since[c]) - 1 for c in LIVE_INPUTS}
            since[channel].append(m)
        elif channel == "PLAN":
            plan = waypoints_t.decode(data)
            snap = pose_pos.get(plan.utime)
            out[plan.seq] = {c: (since[c][max(snap[c], 0):] if snap is not None else since[c][-1:]) or [None]
                             for c in LIVE_INPUTS}
    return out


def check(in_log, out_log, rate_hz=10.0, robot_radius=0.3, person_radius=0.25, expected_rejected=None,
          live=False, static_slack=CLEARANCE_SLACK_M, people_slack=CLEARANCE_SLACK_M):
    """Returns (summary, failures). failures is a list of one-line reasons; empty = all checks pass.
    live: out_log was recorded by lcm-logger with the input channels too (see _live_candidates)."""
    lines, first, last = read_inputs(in_log)
    cycles = read_outputs(out_log)
    live_sets = _live_candidates(read_events(out_log)) if live else {}
    failures = []
    period_us = 1e6 / rate_hz
    plans = [c for c in cycles if c[2] is not None]
    nonempty = [c for c in plans if c[2].num_waypoints > 0]
    lengths, costs = [], []
    worst_static, worst_people = math.inf, math.inf
    for ts, status, plan in plans:
        if plan.num_waypoints == 0:
            if plan.status == 0:
                failures.append("plan seq %d is a stop with status 0 (no reason)" % plan.seq)
            continue
        tick = status.utime
        pose = lines["ROBOT_POSE"].by_utime(plan.utime)
        if pose is None:
            failures.append("plan seq %d names pose utime %d, which is not a valid input" % (plan.seq, plan.utime))
        elif math.hypot(plan.x[0] - pose.x, plan.y[0] - pose.y) > 1e-3:
            failures.append("plan seq %d starts at (%.3f, %.3f), the robot was at (%.3f, %.3f)"
                            % (plan.seq, plan.x[0], plan.y[0], pose.x, pose.y))
        if live:
            cand = live_sets.get(plan.seq, {c: [None] for c in LIVE_INPUTS})
            goals = [g for g in cand["NAV_GOAL"] if g is not None]
            obst_c, ppl_c = cand["OBSTACLES"], cand["PEOPLE"]
        else:
            goal = lines["NAV_GOAL"].latest_before(tick)
            goals = [goal] if goal is not None else []
            obst_c, ppl_c = [lines["OBSTACLES"].latest_before(tick)], [lines["PEOPLE"].latest_before(tick)]
        if status.stale_inputs & planner_status_t.STALE_PEOPLE:
            ppl_c = [None]  # the daemon dropped a stale people list
        if not goals:
            failures.append("plan seq %d made before any goal" % plan.seq)
        else:
            n = plan.num_waypoints
            ends = [(math.hypot(plan.x[n - 1] - g.x, plan.y[n - 1] - g.y) - g.tolerance_m, g) for g in goals]
            margin, goal = min(ends, key=lambda e: e[0])
            d = margin + goal.tolerance_m
            if plan.task != goal.task:
                failures.append("plan seq %d made for task %d, the goal's task is %d" % (plan.seq, plan.task, goal.task))
            if d > goal.tolerance_m + 1e-6:
                failures.append("plan seq %d ends %.3f m from the goal (%.2f, %.2f), tolerance %.2f"
                                % (plan.seq, d, goal.x, goal.y, goal.tolerance_m))
        # The plan must be clear of the inputs it was made with: of one candidate each (one only, log).
        esc = plan.status == ESCAPE_STATUS
        cs = max(plan_clearance(plan, o, None, robot_radius, person_radius, escape=esc)[0] for o in obst_c)
        cp = max(plan_clearance(plan, None, q, robot_radius, person_radius, escape=esc)[1] for q in ppl_c)
        worst_static, worst_people = min(worst_static, cs), min(worst_people, cp)
        if cs < -static_slack:
            failures.append("plan seq %d goes %.4f m into an obstacle" % (plan.seq, -cs))
        if cp < -people_slack:
            failures.append("plan seq %d goes %.4f m into a person" % (plan.seq, -cp))
        lengths.append(plan.length_m)
        costs.append(plan.total_cost)

    # Rate.
    if live:
        stamps = [c[0] for c in cycles]
        gaps = [b - a for a, b in zip(stamps, stamps[1:])]
        if len(gaps) < 5:
            failures.append("only %d status messages recorded" % len(cycles))
        else:
            med = statistics.median(gaps)
            if abs(med - period_us) > 0.15 * period_us:
                failures.append("median status interval %.1f ms, promised %.1f ms" % (med / 1e3, period_us / 1e3))
    elif first is not None:
        want = int((last - first) // period_us)
        if abs(len(cycles) - want) > 1:
            failures.append("%d cycles for %.2f s of input at %.1f Hz (want %d)"
                            % (len(cycles), (last - first) / 1e6, rate_hz, want))

    final = cycles[-1][1] if cycles else None
    rejected = {REASONS[i]: int(final.rejected[i]) for i in sorted(REASONS)} if final else {}
    if expected_rejected is not None and final is not None:
        for i, name in sorted(REASONS.items()):
            want = expected_rejected.get(name, 0)
            if rejected[name] != want:
                failures.append("rejected[%s] = %d, the log plants %d" % (name, rejected[name], want))
    if not cycles:
        failures.append("no output at all")

    summary = {
        "cycles": len(cycles),
        "plans": len(plans),
        "plans_nonempty": len(nonempty),
        "stops": len(plans) - len(nonempty),
        "mean_length_m": round(statistics.mean(lengths), 4) if lengths else None,
        "mean_cost": round(statistics.mean(costs), 4) if costs else None,
        "min_clearance_static_m": round(worst_static, 4) if math.isfinite(worst_static) else None,
        "min_clearance_people_m": round(worst_people, 4) if math.isfinite(worst_people) else None,
        "rejected": rejected,
        "states": {s: sum(1 for c in cycles if c[1].state == s) for s in range(4)},
    }
    return summary, failures


def compare_golden(summary, golden, rel_tol=0.05, count_tol=2):
    """Differences between a summary and its golden copy beyond tolerance (list of reasons)."""
    diffs = []
    for key in ("cycles", "plans"):
        if summary[key] != golden[key]:
            diffs.append("%s: %s, golden %s" % (key, summary[key], golden[key]))
    for key in ("plans_nonempty", "stops"):
        if abs(summary[key] - golden[key]) > count_tol:
            diffs.append("%s: %s, golden %s (tolerance %d)" % (key, summary[key], golden[key], count_tol))
    for key in ("mean_length_m", "mean_cost"):
        a, b = summary[key], golden[key]
        if (a is None) != (b is None) or (a is not None and abs(a - b) > rel_tol * abs(b)):
            diffs.append("%s: %s, golden %s (tolerance %g%%)" % (key, a, b, rel_tol * 100))
    # A reason newer than the golden file (e.g. REJECT_TIME_FUTURE) counts as 0 there, so adding
    # a reason does not invalidate the goldens; a count that differs always does.
    names = set(summary["rejected"]) | set(golden["rejected"])
    if any(summary["rejected"].get(n, 0) != golden["rejected"].get(n, 0) for n in names):
        diffs.append("rejected: %s, golden %s" % (summary["rejected"], golden["rejected"]))
    return diffs


def main(argv=None):
    ap = argparse.ArgumentParser(description="Check gmmrrtd's output log against its input log.")
    ap.add_argument("input")
    ap.add_argument("output")
    ap.add_argument("--rate-hz", type=float, default=10.0)
    ap.add_argument("--robot-radius", type=float, default=0.3)
    ap.add_argument("--person-radius", type=float, default=0.25)
    ap.add_argument("--live", action="store_true",
                    help="output recorded live by lcm-logger with the input channels too, not by the log clock")
    ap.add_argument("--expected", help="scenarios.json with expected_rejected per scenario")
    ap.add_argument("--scenario", help="scenario name in --expected")
    args = ap.parse_args(argv)
    expected = None
    if args.expected:
        with open(args.expected) as f:
            expected = json.load(f)[args.scenario]["expected_rejected"]
    summary, failures = check(args.input, args.output, args.rate_hz, args.robot_radius, args.person_radius,
                              expected, args.live)
    print(json.dumps(summary, indent=2, sort_keys=True))
    for f in failures:
        print("FAIL:", f, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
