"""Latency benchmark of gmmrrtd: from a pose message to the plan it caused.

Starts gmmrrtd (live clock) on a private UDP multicast port with ttl=0, sends one avoid
scenario (a goal 8 m ahead, a person in the way, a circle obstacle) and robot poses at
--pose-hz stamped with the wall clock, and records every PLAN. waypoints_t.utime names the pose
a plan started from, so latency = time the plan arrived - time that pose was sent. It includes
the wait for the next tick (up to one period), the planning budget and LCM transport. Prints
p50/p90/p99/max, the plans per second and the daemon's missed deadlines, for each --rate-hz.

Two triggers (--trigger, both by default): "tick", cycles at rate_hz with poses at --pose-hz and one
plan at the end of each budget; "event", poses at rate_hz each starting a cycle at once
(min_period_ms 5) with anytime plans (the first path at once, up to 3 per cycle on a 5 %
improvement). Latency is to the first plan made from a pose.

Two worlds (--world, both by default, each measured right after the other as its peer): "plain",
the scene above in open space; "map_scan", the same avoid task in the corridor of
logs/maps/floor.yaml (--map) with a 541-beam laser scan (ray-cast by gmmrrt_tools.scan_sim, a
box in the way that only the scans show) sent at 10 Hz, so every cycle integrates scans and
computes the field over its bounds (docs/world.md, "Scans in gmmrrtd"). Reported per world: the
latencies, and the median set-up time per cycle (planner_status_t.setup_time_ms: world update,
field, warm start); the map+scan rows are also given as ratios to the plain rows of the same run.

    python -m gmmrrt_tools.bench.daemon                       # 10 Hz and 20 Hz, 20 s each
    python -m gmmrrt_tools.bench.daemon --rate-hz 10 --seconds 60 --json out.json
    python -m gmmrrt_tools.bench.daemon --world map_scan --trigger event
"""
import argparse
import json
import os
import select
import signal
import statistics
import subprocess
import sys
import tempfile
import time

import lcm
from gmmrrt import nav_goal_t, planner_status_t, waypoints_t  # generated; on PYTHONPATH (tools/run env)

from gmmrrt_tools.scenario_logs import SCAN_BOX, SCAN_MAP, goal, obstacles, people, pose
from gmmrrt_tools.scenario_models import write_models

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))


def percentile(values, q):
    s = sorted(values)
    return s[min(len(s) - 1, int(round(q / 100.0 * (len(s) - 1))))]


EVENT_FLAGS = ["--trigger", "event", "--min-period-ms", "5", "--anytime-max-plans", "3",
               "--anytime-improvement", "0.05"]


# map_scan: the robot in the floor plan's corridor, the goal 10 m along it, the box 2 m ahead.
SCAN_ROBOT, SCAN_GOAL_XY, SCAN_HZ = (-4.0, 0.0), (6.0, 0.0), 10.0


def scan_ranges():
    from gmmrrt_tools.scan_sim import Caster  # numpy: only this world needs it
    caster = Caster(os.path.join(ROOT, SCAN_MAP))
    box = (SCAN_BOX[0] - 2.0, SCAN_BOX[1], SCAN_BOX[2] - 2.0, SCAN_BOX[3])
    return caster, caster.ranges(SCAN_ROBOT[0], SCAN_ROBOT[1], 0.0, [box])


def bench(gmmrrtd, rate_hz, budget_ms, seconds, pose_hz, port, models, trigger="tick", world="plain"):
    url = "udpm://239.255.76.67:%d?ttl=0" % port
    err = tempfile.TemporaryFile(mode="w+")
    world_flags = ["--map", os.path.join(ROOT, SCAN_MAP), "--bounds-margin", "2"] if world == "map_scan" else []
    daemon = subprocess.Popen([gmmrrtd, "--lcm-url", url, "--rate-hz", str(rate_hz), "--budget-ms", str(budget_ms),
                               "--model-avoid", models["avoid"], "--model-approach", models["approach"],
                               "--log-level", "info", *world_flags, *(EVENT_FLAGS if trigger == "event" else [])],
                              stderr=err)
    if world == "map_scan":
        caster, ranges = scan_ranges()
        rx, ry = SCAN_ROBOT
        gx, gy = SCAN_GOAL_XY
        person = (1, 3.0, 0.3, 3.1416, 0.0, 0.0)
        world_msgs = (("PEOPLE", people(0, [person])), ("NAV_GOAL", goal(0, gx, gy, nav_goal_t.TASK_AVOID)))
    else:
        rx, ry = 0.0, 0.0
        world_msgs = (("PEOPLE", people(0, [(1, 4.0, 0.1, 3.1416, 0.0, 0.0)])),
                      ("OBSTACLES", obstacles(0, [(4.0, -1.7, 0.5)])),
                      ("NAV_GOAL", goal(0, 8.0, 0.0, nav_goal_t.TASK_AVOID)))
    lc = lcm.LCM(url)
    sent = {}      # pose utime -> monotonic send time
    arrivals = []  # (pose utime, monotonic arrival)
    status = [None]
    setup_ms = []
    plans = [0, 0]
    first_plan = set()

    def on_plan(channel, data):
        now = time.monotonic()
        m = waypoints_t.decode(data)
        plans[0] += 1
        if m.num_waypoints > 0:
            plans[1] += 1
            if m.utime not in first_plan:  # anytime: later plans from the same pose are not latency
                first_plan.add(m.utime)
                arrivals.append((m.utime, now))

    lc.subscribe("PLAN", on_plan)
    def on_status(channel, data):
        st = planner_status_t.decode(data)
        status[0] = st
        if st.state == planner_status_t.STATE_PLANNING:
            setup_ms.append(st.setup_time_ms)

    lc.subscribe("PLANNER_STATUS", on_status)
    try:
        time.sleep(0.5)
        t_start = time.monotonic()
        next_pose = t_start
        next_world = t_start
        next_scan = t_start + 0.01 if world == "map_scan" else float("inf")
        while time.monotonic() - t_start < seconds:
            now = time.monotonic()
            wall_us = int(time.time() * 1e6)
            if now >= next_world:  # the world once a second, as a tracker and a map would send it
                for ch, m in world_msgs:
                    m.utime = wall_us
                    lc.publish(ch, m.encode())
                next_world += 1.0
            if now >= next_scan:  # stamped now: placed at the newest pose (within scan_pose_gap_ms)
                lc.publish("SCAN", caster.message(wall_us, ranges).encode())
                next_scan += 1.0 / SCAN_HZ
            if now >= next_pose:
                p = pose(0, rx, ry, 0.0, utime=wall_us)
                sent[wall_us] = time.monotonic()
                lc.publish("ROBOT_POSE", p.encode())
                next_pose += 1.0 / pose_hz
            timeout = max(0.0, min(next_pose, next_world, next_scan) - time.monotonic())
            r, _, _ = select.select([lc.fileno()], [], [], timeout)
            if r:
                lc.handle()
        end = time.monotonic() + 0.3
        while time.monotonic() < end:
            r, _, _ = select.select([lc.fileno()], [], [], 0.05)
            if r:
                lc.handle()
    finally:
        daemon.send_signal(signal.SIGTERM)
        daemon.wait(timeout=10)
    err.seek(0)
    scans_line = [ln for ln in err.read().splitlines() if "scans:" in ln]
    lat_ms = [(t - sent[u]) * 1e3 for u, t in arrivals if u in sent]
    if not lat_ms or status[0] is None:
        err.seek(0)
        raise SystemExit("no plans at %g Hz; gmmrrtd said:\n%s" % (rate_hz, err.read()))
    st = status[0]
    return {
        "world": world, "trigger": trigger, "rate_hz": rate_hz, "budget_ms": budget_ms, "seconds": seconds, "pose_hz": pose_hz,
        "plans": plans[0], "plans_nonempty": plans[1], "plans_per_s": round(plans[0] / seconds, 2),
        "latency_ms": {"p50": round(percentile(lat_ms, 50), 1), "p90": round(percentile(lat_ms, 90), 1),
                       "p99": round(percentile(lat_ms, 99), 1), "max": round(max(lat_ms), 1),
                       "mean": round(statistics.mean(lat_ms), 1), "n": len(lat_ms)},
        "setup_ms_p50": round(percentile(setup_ms, 50), 3) if setup_ms else None,
        "setup_ms_p99": round(percentile(setup_ms, 99), 3) if setup_ms else None,
        "missed_deadlines": int(st.missed_deadlines),
        "rejected_total": int(sum(st.rejected)), "stale_inputs": int(st.stale_inputs),
        "daemon_scans_line": scans_line[-1] if scans_line else None,
        "cycles_by_status": int(st.plans_published),
        "last_plan_time_ms": round(st.plan_time_ms, 1), "last_iterations": int(st.iterations),
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--gmmrrtd", default=os.path.join(os.environ.get("GMMRRT_BIN_DIR", os.path.join(ROOT, "build", "bin")), "gmmrrtd"))
    ap.add_argument("--rate-hz", type=float, action="append", help="cycle rate(s) to measure (default 10 and 20)")
    ap.add_argument("--budget-fraction", type=float, default=0.6, help="planning budget as a fraction of the period")
    ap.add_argument("--seconds", type=float, default=20.0)
    ap.add_argument("--pose-hz", type=float, default=50.0)
    ap.add_argument("--port", type=int, default=7600 + os.getpid() % 50)
    ap.add_argument("--trigger", action="append", choices=["tick", "event"],
                    help="tick (poses at --pose-hz) and/or event (poses at the rate); default both")
    ap.add_argument("--world", action="append", choices=["plain", "map_scan"],
                    help="plain (open space) and/or map_scan (map + 10 Hz laser scans); default both")
    ap.add_argument("--json", help="also write the results here")
    args = ap.parse_args()
    if not os.access(args.gmmrrtd, os.X_OK):
        sys.exit("gmmrrtd not found at %s (tools/run build)" % args.gmmrrtd)
    with tempfile.TemporaryDirectory() as tmp:
        models = write_models(tmp)
        # Each world right after its peer, so both see the same machine load.
        results = [bench(args.gmmrrtd, r, round(1000.0 / r * args.budget_fraction, 1), args.seconds,
                         args.pose_hz if trig == "tick" else r, args.port, models, trig, w)
                   for trig in (args.trigger or ["tick", "event"]) for r in (args.rate_hz or [10.0, 20.0])
                   for w in (args.world or ["plain", "map_scan"])]
    print("%-9s %-8s %-6s %-8s %-8s %-8s %-8s %-8s %-8s %-9s %-6s" % (
        "world", "trigger", "rate", "budget", "plans/s", "p50 ms", "p90 ms", "p99 ms", "max ms", "setup p50", "missed"))
    for r in results:
        lat = r["latency_ms"]
        print("%-9s %-8s %-6g %-8s %-8g %-8g %-8g %-8g %-8g %-9s %-6d" % (
            r["world"], r["trigger"], r["rate_hz"], "%g ms" % r["budget_ms"], r["plans_per_s"], lat["p50"], lat["p90"],
            lat["p99"], lat["max"], "%.3f ms" % r["setup_ms_p50"] if r["setup_ms_p50"] is not None else "-",
            r["missed_deadlines"]))
    peers = {(r["trigger"], r["rate_hz"]): r for r in results if r["world"] == "plain"}
    for r in results:
        p = peers.get((r["trigger"], r["rate_hz"]))
        if r["world"] != "map_scan" or p is None:
            continue
        ratio = {q: r["latency_ms"][q] / p["latency_ms"][q] if p["latency_ms"][q] > 0 else float("nan")
                 for q in ("p50", "p99")}
        r["vs_plain"] = {"p50_ratio": round(ratio["p50"], 3), "p99_ratio": round(ratio["p99"], 3)}
        print("map_scan / plain, %s %g Hz (same run): p50 x%.2f, p99 x%.2f; set-up p50 %s vs %s" % (
            r["trigger"], r["rate_hz"], ratio["p50"], ratio["p99"],
            "%.3f ms" % r["setup_ms_p50"] if r["setup_ms_p50"] is not None else "-",
            "%.3f ms" % p["setup_ms_p50"] if p["setup_ms_p50"] is not None else "-"))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=2)
    return 0


if __name__ == "__main__":
    sys.exit(main())
