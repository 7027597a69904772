#!/usr/bin/env python3
"""Soak test of gmmrrtd: the scenario logs replayed at ten times real speed, in a
loop, into a live daemon for --minutes (default 10); its RSS and its pose-to-plan latency are
sampled all along and must stay flat.

The daemon runs with its defaults (live clock, 10 Hz, 60 ms budget) on a private UDP
multicast port with ttl=0. The inputs are the fault-free scenarios of logs/scenarios/, one
after another, sent at --speed times their recorded pace and stamped with the sender's clock
when sent (each message decoded, given its new utime, encoded again), as a real sender does:
stamps that ran --speed times faster than the clock would be a dragged clock, which the
daemon refuses (docs/daemon.md, "Clock"). Samples:
  * RSS: VmRSS of the daemon from /proc every second;
  * latency: a plan's waypoints_t.utime names the pose it started from; latency = arrival of
    the plan - sending of that pose (tick wait + planning + transport).
Flat means, after a warm-up (the first --warmup-frac of the run: the planner's node pool
and LCM's buffers are touched for the first time there):
  * RSS: least-squares slope <= --rss-slope-kb-min (default 64 kB/min; a leak of one 100-byte
    allocation per cycle is 60 kB/min) plus --rss-step-kb (default 256 kB) spread over the
    judged window (a one-off step, e.g. a page touched late, is not a trend; in a 20 s run
    this allows ~1 MB/min, in a 10 min run ~100 kB/min), and the last sample within 1 MiB
    of the first;
  * latency: median of the last third <= 1.5 x median of the first third + 5 ms, and the
    least-squares slope of all samples reported (ms/min);
  * the daemon is alive at the end, published a status every period (median interval within
    15 %), rejected no message (decode, count, not finite, backwards, bad value, reload, reused
    goal id, unknown command, wrong frame: the inputs are clean), and exits 0 on SIGINT. Planning counts (unknown target, ...) are only
    reported: where one scenario hands over to the next, a cycle can fall between the new
    PEOPLE and the new NAV_GOAL, and the old approach goal's target is then rightly missing.
Exit 0 when all hold, 1 otherwise; --json writes the samples' summary.

    .venv/bin/python tools/soak.py                       # 10 minutes, 10x speed
    .venv/bin/python tools/soak.py --minutes 0.33        # the CTest version (fault.soak_short)
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

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, ".."))
import lcm  # noqa: E402
from gmmrrt import nav_goal_t, obstacles_t, people_t, planner_status_t, pose2d_t, waypoints_t  # noqa: E402
from gmmrrt_tools.lcm_url import private_url  # noqa: E402
from gmmrrt_tools.scenario_models import write_models  # noqa: E402

TYPES = {"ROBOT_POSE": pose2d_t, "PEOPLE": people_t, "NAV_GOAL": nav_goal_t, "OBSTACLES": obstacles_t}


def load_inputs(scenario_dir):
    """Events (offset_us from the scenario's start, channel, message object) of every fault-free scenario."""
    with open(os.path.join(scenario_dir, "scenarios.json")) as f:
        index = json.load(f)
    scenarios = []
    for name in sorted(index):
        if index[name]["expected_rejected"]:
            continue  # planted faults: would be counted, and a soak wants clean input
        log = lcm.EventLog(os.path.join(scenario_dir, index[name]["log"]), "r")
        evs = [(e.timestamp, e.channel, e.data) for e in log]
        log.close()
        t0 = evs[0][0]
        scenarios.append((name, [(ts - t0, ch, TYPES[ch].decode(data)) for ts, ch, data in evs if ch in TYPES]))
    if not scenarios:
        raise SystemExit("soak: no fault-free scenario in %s" % scenario_dir)
    return scenarios


def slope_per_min(ts, ys):
    """Least-squares slope of ys over ts [s], per minute."""
    n = len(ts)
    if n < 2:
        return 0.0
    mt, my = sum(ts) / n, sum(ys) / n
    den = sum((t - mt) ** 2 for t in ts)
    return 60.0 * sum((t - mt) * (y - my) for t, y in zip(ts, ys)) / den if den > 0 else 0.0


def rss_kb(pid):
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return None


def soak(args):
    scenarios = load_inputs(args.scenarios)
    url = private_url()  # a port no socket of this host holds: another run's daemon cannot mix in
    tmp = tempfile.mkdtemp(prefix="gmmrrt-soak-")
    models = write_models(tmp)
    err_path = os.path.join(tmp, "gmmrrtd.stderr")
    cmd = [args.gmmrrtd, "--lcm-url", url, "--model-avoid", models["avoid"], "--model-approach", models["approach"],
           "--log-level", "warn", *args.daemon_arg]
    lc = lcm.LCM(url)
    plans, statuses = [], []
    sent = {}  # pose utime -> monotonic time sent
    latency = []  # (t since start, ms)

    def on_plan(channel, data):
        now = time.monotonic()
        m = waypoints_t.decode(data)
        if m.num_waypoints > 0 and m.utime in sent:
            latency.append((now - start, (now - sent[m.utime]) * 1e3))
        plans.append(m.num_waypoints)

    lc.subscribe("PLAN", on_plan)
    lc.subscribe("PLANNER_STATUS", lambda c, d: statuses.append((time.monotonic(), planner_status_t.decode(d))))
    with open(err_path, "w") as err:
        proc = subprocess.Popen(cmd, stderr=err)
    time.sleep(0.5)
    if proc.poll() is not None:
        raise SystemExit("soak: gmmrrtd did not start:\n" + open(err_path).read())

    start = time.monotonic()
    end = start + args.minutes * 60.0
    last_utime = 0
    rss = []  # (t since start, kB)
    next_rss = start
    loops = 0
    sent_msgs = 0
    goal_id = 0
    try:
        while time.monotonic() < end and proc.poll() is None:
            for name, evs in scenarios:
                scen_start_wall = time.monotonic()
                goal_id += 1  # every pass of a scenario is a new goal: a finished goal's id is refused
                for off_us, ch, msg in evs:
                    due = scen_start_wall + off_us * 1e-6 / args.speed
                    while True:
                        now = time.monotonic()
                        if now >= next_rss:
                            r = rss_kb(proc.pid)
                            if r is not None:
                                rss.append((now - start, r))
                            next_rss += 1.0
                        if now >= due:
                            break
                        ready, _, _ = select.select([lc.fileno()], [], [], min(due - now, 0.005))
                        if ready:
                            lc.handle()
                    last_utime = max(last_utime + 1, int(time.time() * 1e6))
                    msg.utime = last_utime
                    if ch == "NAV_GOAL":
                        msg.goal_id = goal_id
                    if ch == "PEOPLE":
                        for i in range(msg.num_people):
                            msg.people[i].utime = msg.utime
                    lc.publish(ch, msg.encode())
                    sent_msgs += 1
                    if ch == "ROBOT_POSE":
                        sent[msg.utime] = time.monotonic()
                    if time.monotonic() >= end:
                        break
                if time.monotonic() >= end:
                    break
            loops += 1
        # Drain the last outputs.
        t_drain = time.monotonic() + 0.3
        while time.monotonic() < t_drain:
            ready, _, _ = select.select([lc.fileno()], [], [], 0.05)
            if ready:
                lc.handle()
    finally:
        alive = proc.poll() is None
        if alive:
            proc.send_signal(signal.SIGINT)
            try:
                rc = proc.wait(timeout=30)
            except subprocess.TimeoutExpired:
                proc.kill()
                rc = proc.wait()
        else:
            rc = proc.returncode

    failures = []
    duration = time.monotonic() - start
    if not alive:
        failures.append("gmmrrtd died during the soak (exit %s)" % rc)
    elif rc != 0:
        failures.append("gmmrrtd exited %d on SIGINT" % rc)
    warm = args.warmup_frac * duration
    rss_w = [(t, r) for t, r in rss if t >= warm]
    lat_w = [(t, ms) for t, ms in latency if t >= warm]
    summary = {"minutes": round(duration / 60.0, 3), "speed": args.speed, "scenario_loops": loops,
               "messages_sent": sent_msgs, "plans": len(plans), "plans_nonempty": sum(1 for n in plans if n > 0),
               "rss_samples": len(rss_w), "latency_samples": len(lat_w)}
    if len(rss_w) < 5 or len(lat_w) < 20:
        failures.append("too few samples after the warm-up (%d RSS, %d latency)" % (len(rss_w), len(lat_w)))
    else:
        rs = slope_per_min([t for t, _ in rss_w], [r for _, r in rss_w])
        summary.update(rss_first_kb=rss_w[0][1], rss_last_kb=rss_w[-1][1], rss_max_kb=max(r for _, r in rss_w),
                       rss_slope_kb_per_min=round(rs, 2))
        window_min = max((rss_w[-1][0] - rss_w[0][0]) / 60.0, 1e-6)
        bound = args.rss_slope_kb_min + args.rss_step_kb / window_min
        summary["rss_slope_bound_kb_per_min"] = round(bound, 1)
        if rs > bound:
            failures.append("RSS grows %.1f kB/min (bound %.1f)" % (rs, bound))
        if rss_w[-1][1] - rss_w[0][1] > 1024:
            failures.append("RSS grew %d kB after the warm-up" % (rss_w[-1][1] - rss_w[0][1]))
        third = len(lat_w) // 3
        first = statistics.median(ms for _, ms in lat_w[:third])
        last = statistics.median(ms for _, ms in lat_w[-third:])
        ls = slope_per_min([t for t, _ in lat_w], [ms for _, ms in lat_w])
        allms = sorted(ms for _, ms in lat_w)
        summary.update(latency_p50_ms=round(allms[len(allms) // 2], 2),
                       latency_p99_ms=round(allms[min(len(allms) - 1, int(0.99 * len(allms)))], 2),
                       latency_first_third_p50_ms=round(first, 2), latency_last_third_p50_ms=round(last, 2),
                       latency_slope_ms_per_min=round(ls, 3))
        if last > 1.5 * first + 5.0:
            failures.append("latency drifts: median %.1f ms in the last third, %.1f ms in the first" % (last, first))
    if statuses:
        gaps = [b[0] - a[0] for a, b in zip(statuses, statuses[1:])]
        final = statuses[-1][1]
        summary.update(status_median_interval_ms=round(statistics.median(gaps) * 1e3, 2) if gaps else None,
                       missed_deadlines=int(final.missed_deadlines))
        if gaps and abs(statistics.median(gaps) - 0.1) > 0.015:
            failures.append("median status interval %.1f ms, promised 100 ms" % (statistics.median(gaps) * 1e3))
        message_level = [planner_status_t.REJECT_DECODE, planner_status_t.REJECT_COUNT_OVER_BOUND,
                         planner_status_t.REJECT_NOT_FINITE, planner_status_t.REJECT_TIME_BACKWARDS,
                         planner_status_t.REJECT_BAD_VALUE, planner_status_t.REJECT_MODEL_RELOAD,
                         planner_status_t.REJECT_TIME_FUTURE, planner_status_t.REJECT_CLOCK_RESYNC,
                         planner_status_t.REJECT_GOAL_ID_REUSED, planner_status_t.REJECT_UNKNOWN_COMMAND,
                         planner_status_t.REJECT_WRONG_FRAME]
        summary["rejected_nonzero"] = {i: int(v) for i, v in enumerate(final.rejected) if v}
        if any(final.rejected[i] for i in message_level):
            failures.append("the daemon rejected clean input: %s" % list(final.rejected))
    else:
        failures.append("no PLANNER_STATUS received")
    return summary, failures, err_path


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--minutes", type=float, default=10.0, help="length of the soak (default 10)")
    ap.add_argument("--speed", type=float, default=10.0, help="replay speed factor (default 10)")
    ap.add_argument("--gmmrrtd", default=os.path.join(os.environ.get("GMMRRT_BIN_DIR", os.path.join(ROOT, "build", "bin")),
                                                      "gmmrrtd"), help="daemon executable")
    ap.add_argument("--scenarios", default=os.path.join(ROOT, "logs", "scenarios"), help="scenario folder")
    ap.add_argument("--warmup-frac", type=float, default=0.2, help="first fraction of the run not judged (0.2)")
    ap.add_argument("--rss-slope-kb-min", type=float, default=64.0, help="largest RSS slope after warm-up, kB/min")
    ap.add_argument("--rss-step-kb", type=float, default=256.0, help="one-off RSS step tolerated in the window, kB")
    ap.add_argument("--json", help="write the summary here")
    ap.add_argument("--daemon-arg", action="append", default=[], help="extra gmmrrtd argument (repeatable)")
    args = ap.parse_args()
    if not (args.minutes > 0 and args.speed > 0 and 0 <= args.warmup_frac < 1):
        ap.error("--minutes and --speed must be > 0, --warmup-frac in [0, 1)")
    if not os.access(args.gmmrrtd, os.X_OK):
        ap.error("no gmmrrtd at %s (build first: tools/run build)" % args.gmmrrtd)
    summary, failures, err_path = soak(args)
    print(json.dumps(summary, indent=2))
    if args.json:
        with open(args.json + ".tmp", "w") as f:
            json.dump({"summary": summary, "failures": failures}, f, indent=2)
        os.replace(args.json + ".tmp", args.json)
    if failures:
        for f in failures:
            print("soak: FAIL: " + f, file=sys.stderr)
        print("soak: daemon log: " + err_path, file=sys.stderr)
        return 1
    print("soak: flat (RSS and latency), rate kept, no message rejected")
    return 0


if __name__ == "__main__":
    sys.exit(main())
