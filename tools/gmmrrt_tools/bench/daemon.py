"""Latency benchmark of gmmrrtd: from a pose message to the plan it caused.

Starts gmmrrtd (live clock) on a private UDP multicast port with ttl=0 with the models `tools/run
demo` plans with (learned by gmmrrt-learn fit from logs/demos/, the demo's seed), and plays the
demo scenarios (logs/scenarios/avoid_obstacles and approach_obstacles, tools/demo.py's defaults):
their people, obstacles and goal once a second and their robot poses at --pose-hz, all stamped
with the wall clock, and records every PLAN. waypoints_t.utime names the pose a plan started
from (stamped with the wall clock just before it is sent), so latency = time the plan arrived -
that stamp. "Arrived" is the kernel's receive time of the PLAN datagram, as lcm-logger records it
(LCM stamps each datagram with SO_TIMESTAMP): the time the plan exists for any consumer on the
host, whenever this script's own process is next scheduled. The time this script's handler saw
it is kept as the client's latency (latency_client_ms, the "client p99" column): on a loaded
machine it adds the benchmark's own wake-up, up to ~12 ms (docs/daemon.md, "Where a slow plan's
time goes"). Latency includes the wait for the
next tick (up to one period), the planning budget and LCM transport. Prints p50/p90/p99/max,
the plans per second, the daemon's missed deadlines, the median set-up time per cycle
(planner_status_t.setup_time_ms: world update, field, warm start) and the machine's load
(1-minute load average before and after each run, and the CPUs), for each scenario, trigger and
--rate-hz.

Two triggers (--trigger, both by default): "tick", cycles at rate_hz with poses at --pose-hz and one
plan at the end of each budget; "event", poses at rate_hz each starting a cycle at once
(min_period_ms 5) with anytime plans (the first path at once, up to 3 per cycle on a 5 %
improvement). Latency is to the first plan made from a pose.

Two worlds (--world, both by default): "plain", the scenarios above, in open space with their
obstacle messages; "map_scan", an avoid task in the corridor of logs/maps/floor.yaml (--map)
with a 541-beam laser scan (ray-cast by gmmrrt_tools.scan_sim, a box in the way that only the
scans show) sent at 10 Hz, so every cycle integrates scans and computes the field over its bounds
(docs/world.md, "Scans in gmmrrtd"). Each map_scan run comes right after the plain runs of the
same trigger and rate, and is also given as ratios to the first scenario's plain row (its peer,
measured under the same machine load). map_scan runs log at info (the exit line with the scan
counts); plain runs at warn.

    python -m gmmrrt_tools.bench.daemon                       # 10 Hz and 20 Hz, 20 s each
    python -m gmmrrt_tools.bench.daemon --rate-hz 10 --seconds 60 --json out.json
    python -m gmmrrt_tools.bench.daemon --scenario logs/scenarios/avoid_crowd.lcmlog --world plain
    python -m gmmrrt_tools.bench.daemon --world map_scan --trigger event
"""
import argparse
import json
import os
import shutil
import select
import signal
import statistics
import subprocess
import sys
import tempfile
import time

import lcm
from gmmrrt import nav_goal_t, obstacles_t, people_t, planner_status_t, pose2d_t, waypoints_t  # generated

from gmmrrt_tools import runner
from gmmrrt_tools.lcm_url import private_url
from gmmrrt_tools.scenario_logs import SCAN_BOX, SCAN_MAP, goal, people, pose

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
DEMO_SCENARIOS = ("avoid_obstacles", "approach_obstacles")  # tools/demo.py's DEFAULT_SCENARIOS
DEMO_SEED = 1                                               # tools/demo.py's --seed default


def learned_models(out_dir, bin_dir=None):
    """The demo's models: gmmrrt-learn fit on every log of logs/demos/ (runner.fit_model, as tools/demo.py)."""
    logs = sorted(os.path.join(ROOT, "logs", "demos", n) for n in os.listdir(os.path.join(ROOT, "logs", "demos"))
                  if n.endswith(".lcmlog"))
    if not logs:
        raise SystemExit("no demonstration logs in logs/demos/")
    return {task: str(runner.fit_model(os.path.join(out_dir, task + ".gmm"), task, logs, homotopy="all",
                                       kind="features", seed=DEMO_SEED, bin_dir=bin_dir))
            for task in ("avoid", "approach")}


def scenario_inputs(path):
    """(world, poses) of a scenario log: the first PEOPLE, OBSTACLES and NAV_GOAL (the world a
    tracker and a map would re-send), and the ROBOT_POSE messages in order."""
    types = {"PEOPLE": people_t, "OBSTACLES": obstacles_t, "NAV_GOAL": nav_goal_t}
    world, poses = {}, []
    log = lcm.EventLog(path, "r")
    for e in log:
        if e.channel == "ROBOT_POSE":
            poses.append(pose2d_t.decode(e.data))
        elif e.channel in types and e.channel not in world:
            world[e.channel] = types[e.channel].decode(e.data)
    log.close()
    if not poses or "NAV_GOAL" not in world:
        raise SystemExit("%s: no ROBOT_POSE or NAV_GOAL to play" % path)
    return world, poses


# map_scan: the robot in the floor plan's corridor, the goal 10 m along it, the box 2 m ahead.
SCAN_ROBOT, SCAN_GOAL_XY, SCAN_HZ = (-4.0, 0.0), (6.0, 0.0), 10.0


def map_scan_inputs():
    """(world, poses, caster, ranges) of the map_scan world: a person and the goal re-sent, the robot
    standing at SCAN_ROBOT, and the one scan it sees (the box 2 m ahead of it)."""
    from gmmrrt_tools.scan_sim import Caster  # numpy: only this world needs it
    caster = Caster(os.path.join(ROOT, SCAN_MAP))
    box = (SCAN_BOX[0] - 2.0, SCAN_BOX[1], SCAN_BOX[2] - 2.0, SCAN_BOX[3])
    ranges = caster.ranges(SCAN_ROBOT[0], SCAN_ROBOT[1], 0.0, [box])
    world = {"PEOPLE": people(0, [(1, 3.0, 0.3, 3.1416, 0.0, 0.0)]),
             "NAV_GOAL": goal(0, SCAN_GOAL_XY[0], SCAN_GOAL_XY[1], nav_goal_t.TASK_AVOID)}
    return world, [pose(0, SCAN_ROBOT[0], SCAN_ROBOT[1], 0.0)], caster, ranges


def lcm_logger():
    """lcm-logger of the LCM installation this script runs with (the venv's, else PATH's)."""
    here = os.path.join(os.path.dirname(sys.executable), "lcm-logger")
    found = here if os.access(here, os.X_OK) else shutil.which("lcm-logger")
    if not found:
        raise SystemExit("lcm-logger not found next to %s or on PATH (tools/run setup installs LCM)" % sys.executable)
    return found


def kernel_arrivals(log_path):
    """{pose utime: kernel receive time (wall clock, us)} of the first non-empty PLAN made from
    each pose, from lcm-logger's log (an event's timestamp is its datagram's receive time)."""
    first = {}
    log = lcm.EventLog(log_path, "r")
    for e in log:
        if e.channel != "PLAN":
            continue
        m = waypoints_t.decode(e.data)
        if m.num_waypoints > 0 and m.utime not in first:
            first[m.utime] = e.timestamp
    log.close()
    return first


def latency_stats(lat_ms):
    return {"p50": round(percentile(lat_ms, 50), 1), "p90": round(percentile(lat_ms, 90), 1),
            "p99": round(percentile(lat_ms, 99), 1), "max": round(max(lat_ms), 1),
            "mean": round(statistics.mean(lat_ms), 1), "n": len(lat_ms)}


def percentile(values, q):
    s = sorted(values)
    return s[min(len(s) - 1, int(round(q / 100.0 * (len(s) - 1))))]


EVENT_FLAGS = ["--trigger", "event", "--min-period-ms", "5", "--anytime-max-plans", "3",
               "--anytime-improvement", "0.05"]


def bench(gmmrrtd, rate_hz, budget_ms, seconds, pose_hz, url, models, scenario, trigger="tick", world="plain"):
    """One run on LCM `url` (None: a private one). `scenario` is the log played in the plain world (None for map_scan)."""
    url = url or private_url()
    err = tempfile.TemporaryFile(mode="w+")
    if world == "map_scan":
        world_flags, log_level = ["--map", os.path.join(ROOT, SCAN_MAP), "--bounds-margin", "2"], "info"
        inputs, poses, caster, ranges = map_scan_inputs()
    else:
        world_flags, log_level = [], "warn"
        (inputs, poses), caster, ranges = scenario_inputs(scenario), None, None
    plan_log = tempfile.NamedTemporaryFile(suffix=".lcmlog", delete=False)
    plan_log.close()
    logger = subprocess.Popen([lcm_logger(), "-q", "-f", "--flush-interval=100", "--lcm-url", url, "-c", "PLAN",
                               plan_log.name],
                              stderr=subprocess.DEVNULL,
                              # A background shell (nohup, CI) starts us with SIGINT ignored, which
                              # exec keeps: lcm-logger would then never see the SIGINT that ends it.
                              preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    daemon = subprocess.Popen([gmmrrtd, "--lcm-url", url, "--rate-hz", str(rate_hz), "--budget-ms", str(budget_ms),
                               "--model-avoid", models["avoid"], "--model-approach", models["approach"],
                               "--log-level", log_level, *world_flags, *(EVENT_FLAGS if trigger == "event" else [])],
                              stderr=err)
    lc = lcm.LCM(url)
    sent = {}      # pose utime (wall clock, us, taken just before it is sent) -> monotonic send time
    arrivals = []  # (pose utime, monotonic arrival at this script's handler)
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

    def on_status(channel, data):
        st = planner_status_t.decode(data)
        status[0] = st
        if st.state == planner_status_t.STATE_PLANNING:
            setup_ms.append(st.setup_time_ms)

    lc.subscribe("PLAN", on_plan)
    lc.subscribe("PLANNER_STATUS", on_status)
    load_before = os.getloadavg()[0]
    try:
        time.sleep(0.5)
        t_start = time.monotonic()
        next_pose = t_start
        next_world = t_start
        next_scan = t_start + 0.01 if caster is not None else float("inf")
        while time.monotonic() - t_start < seconds:
            now = time.monotonic()
            wall_us = int(time.time() * 1e6)
            if now >= next_world:  # the world once a second, as a tracker and a map would send it
                for ch, m in sorted(inputs.items()):
                    m.utime = wall_us
                    if ch == "PEOPLE":
                        for i in range(m.num_people):
                            m.people[i].utime = wall_us
                    lc.publish(ch, m.encode())
                next_world += 1.0
            if now >= next_scan:  # stamped now: placed at the newest pose (within scan_pose_gap_ms)
                lc.publish("SCAN", caster.message(wall_us, ranges).encode())
                next_scan += 1.0 / SCAN_HZ
            if now >= next_pose:
                # The scenario's robot path at its own pace (10 Hz poses), looped.
                p = poses[int((now - t_start) * 10.0) % len(poses)]
                p.utime = int(time.time() * 1e6)  # after the world's messages of this round
                sent[p.utime] = time.monotonic()
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
        # The logger first, while the daemon still sends: lcm-logger acts on SIGINT once its
        # next datagram wakes it (a status within a period).
        logger.send_signal(signal.SIGINT)
        try:
            logger.wait(timeout=3)
        except subprocess.TimeoutExpired:  # flushed every 100 ms: the plans of the run are on disk
            logger.kill()
            logger.wait()
        daemon.send_signal(signal.SIGTERM)
        daemon.wait(timeout=10)
    received = kernel_arrivals(plan_log.name)
    os.unlink(plan_log.name)
    client_ms = [(t - sent[u]) * 1e3 for u, t in arrivals if u in sent]
    lat_ms = [(received[u] - u) * 1e-3 for u, _ in arrivals if u in sent and u in received]
    err.seek(0)
    said = err.read()
    if not lat_ms or status[0] is None:
        raise SystemExit("no plans at %g Hz (%d seen by this script, %d recorded by lcm-logger); gmmrrtd said:\n%s"
                         % (rate_hz, len(client_ms), len(received), said))
    if len(lat_ms) < len(client_ms):  # the logger must see every plan the script saw
        raise SystemExit("lcm-logger recorded %d of the %d first plans this script received at %g Hz"
                         % (len(lat_ms), len(client_ms), rate_hz))
    scans_line = [ln for ln in said.splitlines() if "scans:" in ln]
    st = status[0]
    row = {"world": world}
    if scenario is not None:  # judged against the reaction-time targets (bench/report.py)
        row["scenario"] = os.path.splitext(os.path.basename(scenario))[0]
    row.update({
        "load_1min": [round(load_before, 2), round(os.getloadavg()[0], 2)], "cpus": os.cpu_count(),
        "trigger": trigger, "rate_hz": rate_hz, "budget_ms": budget_ms, "seconds": seconds, "pose_hz": pose_hz,
        "plans": plans[0], "plans_nonempty": plans[1], "plans_per_s": round(plans[0] / seconds, 2),
        "latency_ms": latency_stats(lat_ms),
        "latency_client_ms": latency_stats(client_ms),
        "setup_ms_p50": round(percentile(setup_ms, 50), 3) if setup_ms else None,
        "setup_ms_p99": round(percentile(setup_ms, 99), 3) if setup_ms else None,
        "missed_deadlines": int(st.missed_deadlines),
        "cycles_by_status": int(st.plans_published),
        "last_plan_time_ms": round(st.plan_time_ms, 1), "last_iterations": int(st.iterations),
        "rejected_total": int(sum(st.rejected)), "stale_inputs": int(st.stale_inputs),
        "daemon_scans_line": scans_line[-1] if scans_line else None,
    })
    return row


def _ms(v):
    return "%.3f ms" % v if v is not None else "-"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--gmmrrtd", default=os.path.join(os.environ.get("GMMRRT_BIN_DIR", os.path.join(ROOT, "build", "bin")), "gmmrrtd"))
    ap.add_argument("--rate-hz", type=float, action="append", help="cycle rate(s) to measure (default 10 and 20)")
    ap.add_argument("--budget-fraction", type=float, default=0.6, help="planning budget as a fraction of the period")
    ap.add_argument("--seconds", type=float, default=20.0)
    ap.add_argument("--pose-hz", type=float, default=50.0)
    ap.add_argument("--lcm-url", help="LCM URL of the runs (default: udpm on a port no socket of this host is bound "
                    "to, drawn for each run: gmmrrt_tools.lcm_url)")
    ap.add_argument("--trigger", action="append", choices=["tick", "event"],
                    help="tick (poses at --pose-hz) and/or event (poses at the rate); default both")
    ap.add_argument("--scenario", action="append",
                    help="scenario log(s) to play in the plain world (default: the demo's, logs/scenarios/%s)"
                    % " and ".join(DEMO_SCENARIOS))
    ap.add_argument("--world", action="append", choices=["plain", "map_scan"],
                    help="plain (the scenarios) and/or map_scan (map + 10 Hz laser scans); default both")
    ap.add_argument("--json", help="also write the results here")
    args = ap.parse_args()
    if not os.access(args.gmmrrtd, os.X_OK):
        sys.exit("gmmrrtd not found at %s (tools/run build)" % args.gmmrrtd)
    scenarios = args.scenario or [os.path.join(ROOT, "logs", "scenarios", n + ".lcmlog") for n in DEMO_SCENARIOS]
    worlds = args.world or ["plain", "map_scan"]
    runs = []  # (world, scenario): the plain runs, then map_scan right after them (its peer's load)
    if "plain" in worlds:
        runs += [("plain", sc) for sc in scenarios]
    if "map_scan" in worlds:
        runs.append(("map_scan", None))
    with tempfile.TemporaryDirectory() as tmp:
        models = learned_models(tmp, bin_dir=os.path.dirname(args.gmmrrtd))
        results = [bench(args.gmmrrtd, r, round(1000.0 / r * args.budget_fraction, 1), args.seconds,
                         args.pose_hz if trig == "tick" else r, args.lcm_url, models, sc, trig, w)
                   for trig in (args.trigger or ["tick", "event"]) for r in (args.rate_hz or [10.0, 20.0])
                   for w, sc in runs]
    print("models learned from logs/demos/ (gmmrrt-learn fit, seed %d); %d CPUs" % (DEMO_SEED, os.cpu_count()))
    print("latency: pose stamp to the PLAN datagram's kernel receive time; client p99: to this script's handler")
    print("%-19s %-7s %-5s %-7s %-8s %-7s %-7s %-7s %-7s %-10s %-9s %-7s %-11s" % (
        "scenario / world", "trigger", "rate", "budget", "plans/s", "p50 ms", "p90 ms", "p99 ms", "max ms",
        "client p99", "setup p50", "missed", "load 1 min"))
    for r in results:
        lat = r["latency_ms"]
        print("%-19s %-7s %-5g %-7s %-8g %-7g %-7g %-7g %-7g %-10g %-9s %-7d %-11s" % (
            r.get("scenario", r["world"]), r["trigger"], r["rate_hz"], "%g ms" % r["budget_ms"], r["plans_per_s"],
            lat["p50"], lat["p90"], lat["p99"], lat["max"], r["latency_client_ms"]["p99"], _ms(r["setup_ms_p50"]),
            r["missed_deadlines"], "%.2f -> %.2f" % tuple(r["load_1min"])))
    peers = {}
    for r in results:  # the first plain scenario of each trigger and rate
        if r["world"] == "plain":
            peers.setdefault((r["trigger"], r["rate_hz"]), r)
    for r in results:
        p = peers.get((r["trigger"], r["rate_hz"]))
        if r["world"] != "map_scan" or p is None:
            continue
        ratio = {q: r["latency_ms"][q] / p["latency_ms"][q] if p["latency_ms"][q] > 0 else float("nan")
                 for q in ("p50", "p99")}
        r["vs_plain"] = {"peer": p["scenario"], "p50_ratio": round(ratio["p50"], 3),
                         "p99_ratio": round(ratio["p99"], 3)}
        print("map_scan / %s, %s %g Hz (same run): p50 x%.2f, p99 x%.2f; set-up p50 %s vs %s" % (
            p["scenario"], r["trigger"], r["rate_hz"], ratio["p50"], ratio["p99"], _ms(r["setup_ms_p50"]),
            _ms(p["setup_ms_p50"])))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=2)
    return 0


if __name__ == "__main__":
    sys.exit(main())
