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

    python -m gmmrrt_tools.bench.daemon                       # 10 Hz and 20 Hz, 20 s each
    python -m gmmrrt_tools.bench.daemon --rate-hz 10 --seconds 60 --json out.json
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

from gmmrrt_tools.scenario_logs import goal, obstacles, people, pose
from gmmrrt_tools.scenario_models import write_models

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))


def percentile(values, q):
    s = sorted(values)
    return s[min(len(s) - 1, int(round(q / 100.0 * (len(s) - 1))))]


EVENT_FLAGS = ["--trigger", "event", "--min-period-ms", "5", "--anytime-max-plans", "3",
               "--anytime-improvement", "0.05"]


def bench(gmmrrtd, rate_hz, budget_ms, seconds, pose_hz, port, models, trigger="tick"):
    url = "udpm://239.255.76.67:%d?ttl=0" % port
    err = tempfile.TemporaryFile(mode="w+")
    daemon = subprocess.Popen([gmmrrtd, "--lcm-url", url, "--rate-hz", str(rate_hz), "--budget-ms", str(budget_ms),
                               "--model-avoid", models["avoid"], "--model-approach", models["approach"],
                               "--log-level", "warn", *(EVENT_FLAGS if trigger == "event" else [])], stderr=err)
    lc = lcm.LCM(url)
    sent = {}      # pose utime -> monotonic send time
    arrivals = []  # (pose utime, monotonic arrival)
    status = [None]
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
    lc.subscribe("PLANNER_STATUS", lambda c, d: status.__setitem__(0, planner_status_t.decode(d)))
    try:
        time.sleep(0.5)
        t_start = time.monotonic()
        next_pose = t_start
        next_world = t_start
        while time.monotonic() - t_start < seconds:
            now = time.monotonic()
            wall_us = int(time.time() * 1e6)
            if now >= next_world:  # the world once a second, as a tracker and a map would send it
                for ch, m in (("PEOPLE", people(0, [(1, 4.0, 0.1, 3.1416, 0.0, 0.0)])),
                              ("OBSTACLES", obstacles(0, [(4.0, -1.7, 0.5)])),
                              ("NAV_GOAL", goal(0, 8.0, 0.0, nav_goal_t.TASK_AVOID))):
                    m.utime = wall_us
                    lc.publish(ch, m.encode())
                next_world += 1.0
            if now >= next_pose:
                p = pose(0, 0.0, 0.0, 0.0, utime=wall_us)
                sent[wall_us] = time.monotonic()
                lc.publish("ROBOT_POSE", p.encode())
                next_pose += 1.0 / pose_hz
            timeout = max(0.0, min(next_pose, next_world) - time.monotonic())
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
    lat_ms = [(t - sent[u]) * 1e3 for u, t in arrivals if u in sent]
    if not lat_ms or status[0] is None:
        err.seek(0)
        raise SystemExit("no plans at %g Hz; gmmrrtd said:\n%s" % (rate_hz, err.read()))
    st = status[0]
    return {
        "trigger": trigger, "rate_hz": rate_hz, "budget_ms": budget_ms, "seconds": seconds, "pose_hz": pose_hz,
        "plans": plans[0], "plans_nonempty": plans[1], "plans_per_s": round(plans[0] / seconds, 2),
        "latency_ms": {"p50": round(percentile(lat_ms, 50), 1), "p90": round(percentile(lat_ms, 90), 1),
                       "p99": round(percentile(lat_ms, 99), 1), "max": round(max(lat_ms), 1),
                       "mean": round(statistics.mean(lat_ms), 1), "n": len(lat_ms)},
        "missed_deadlines": int(st.missed_deadlines),
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
    ap.add_argument("--json", help="also write the results here")
    args = ap.parse_args()
    if not os.access(args.gmmrrtd, os.X_OK):
        sys.exit("gmmrrtd not found at %s (tools/run build)" % args.gmmrrtd)
    with tempfile.TemporaryDirectory() as tmp:
        models = write_models(tmp)
        results = [bench(args.gmmrrtd, r, round(1000.0 / r * args.budget_fraction, 1), args.seconds,
                         args.pose_hz if trig == "tick" else r, args.port, models, trig)
                   for trig in (args.trigger or ["tick", "event"]) for r in (args.rate_hz or [10.0, 20.0])]
    print("%-8s %-8s %-10s %-8s %-8s %-8s %-8s %-8s %-8s" % ("trigger", "rate", "budget", "plans/s", "p50 ms",
                                                           "p90 ms", "p99 ms", "max ms", "missed"))
    for r in results:
        lat = r["latency_ms"]
        print("%-8s %-8g %-10s %-8g %-8g %-8g %-8g %-8g %-8d" % (r["trigger"], r["rate_hz"], "%g ms" % r["budget_ms"],
                                                               r["plans_per_s"], lat["p50"], lat["p90"], lat["p99"],
                                                               lat["max"], r["missed_deadlines"]))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=2)
    return 0


if __name__ == "__main__":
    sys.exit(main())
