#!/usr/bin/env python3
"""Writes the seed corpora of the libFuzzer targets into tests/fuzz/corpus/<target>/.

Seeds are real inputs, small: model files (the scenario models and the shared test
vectors), encoded LCM messages taken from logs/scenarios/ (one of each type per scenario,
plus the plan/status/demo_info types), short cuts of logs/demos/ and small episode CSVs,
and record sequences for the daemon target (tests/fuzz/fuzz_daemon_inputs.c: channel byte,
16-bit LE length, payload) cut from the scenario logs. Deterministic: the same command
writes the same files; names are the content's sha1 (libFuzzer's convention).

    .venv/bin/python tools/fuzz_corpus.py            # (re)writes tests/fuzz/corpus/
    .venv/bin/python tools/fuzz_corpus.py --check    # exit 1 if the corpus is stale
"""
import argparse
import hashlib
import os
import shutil
import struct
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, ".."))
import lcm  # noqa: E402
from gmmrrt import demo_info_t, occupancy_grid_t, planar_scan_t, planner_status_t, waypoints_t  # noqa: E402
from gmmrrt_tools.scenario_logs import cancel  # noqa: E402
from gmmrrt_tools.scenario_models import APPROACH, AVOID, TASK_APPROACH, TASK_AVOID, encode_features_model  # noqa: E402

SCENARIOS = os.path.join(ROOT, "logs", "scenarios")
DEMOS = os.path.join(ROOT, "logs", "demos")
VECTORS = os.path.join(ROOT, "tests", "data", "model_vectors")
INPUTS = {"ROBOT_POSE": 0, "PEOPLE": 1, "NAV_GOAL": 2, "OBSTACLES": 3, "SCAN": 4}  # GMMRRTD_IN_*; a grid (64 KiB)
# does not fit the target's 16-bit record length


def events(path):
    log = lcm.EventLog(path, "r")
    out = [(e.timestamp, e.channel, e.data) for e in log]
    log.close()
    return out


def model_seeds():
    from gmmrrt_tools import core

    seeds = [encode_features_model(TASK_AVOID, AVOID), encode_features_model(TASK_APPROACH, APPROACH)]
    # A file with every optional part: a background section (here the approach mixture's numbers as an
    # avoid model) and a provenance trailer after it.
    avoid = core.decode_model(seeds[0])
    f = core.model_fields(core.decode_model(seeds[1]))
    bg = core.model_from_arrays(f["kind"], TASK_AVOID, 0, f["weights"], f["means"], f["chols"], f["angle_mask"],
                                f["delta"])
    seeds.append(core.encode_model(avoid, provenance='{"seed":1}', background=bg))
    for name in sorted(os.listdir(VECTORS)):
        if name.endswith(".gmm"):
            with open(os.path.join(VECTORS, name), "rb") as f:
                seeds.append(f.read())
    return seeds


def msg_seeds():
    seeds = []
    for name in sorted(os.listdir(SCENARIOS)):
        if not name.endswith(".lcmlog"):
            continue
        seen = set()
        for _, channel, data in events(os.path.join(SCENARIOS, name)):
            if channel not in seen:
                seen.add(channel)
                seeds.append(data)
    wp = waypoints_t()
    wp.utime, wp.frame, wp.seq, wp.num_waypoints = 1, "map", 1, 3
    wp.x[:3], wp.y[:3], wp.yaw[:3] = [0.0, 1.0, 2.0], [0.0, 0.5, 0.0], [0.0, 0.3, -0.3]
    wp.planner, wp.task = waypoints_t.PLANNER_GMM_RRT_STAR, 1
    seeds.append(wp.encode())
    st = planner_status_t()
    st.utime, st.state, st.rejected[0] = 1, planner_status_t.STATE_PLANNING, 2
    st.goal_id, st.goal_state, st.remaining_m = 3, planner_status_t.GOAL_PLANNING, 4.5
    seeds.append(st.encode())
    for name in sorted(os.listdir(DEMOS)):
        if name.endswith(".lcmlog"):
            for _, channel, data in events(os.path.join(DEMOS, name)):
                if channel == "DEMO_INFO":
                    seeds.append(data)
                    break
    di = demo_info_t()
    seeds.append(di.encode())
    seeds.append(cancel(0.0, 7).encode())  # a CANCEL: only its id and frame are judged
    sc = planar_scan_t()  # a 270-degree scan of 541 beams, one NaN and one beyond range_max_m
    sc.utime, sc.rad0, sc.radstep, sc.range_min_m, sc.range_max_m = 1, -2.356194, 0.00872665, 0.05, 30.0
    sc.sensor_x, sc.num_ranges = 0.2, 541
    sc.ranges[:541] = [2.0 + 0.01 * k for k in range(541)]
    sc.ranges[7], sc.ranges[8] = float("nan"), 100.0
    seeds.append(sc.encode())
    og = occupancy_grid_t()  # a 3 x 2 local grid: unknown, free, scale values and one occupied cell
    og.utime, og.frame, og.resolution_m, og.origin_x, og.origin_y = 1, "map", 0.05, -1.0, 2.0
    og.width, og.height, og.num_cells = 3, 2, 6
    og.data[:6] = [-1, 0, 30, 65, 100, 0]
    seeds.append(og.encode())
    return seeds


def write_log(path, evs):
    log = lcm.EventLog(path, "w", overwrite=True)
    for utime, channel, data in evs:
        log.write_event(utime, channel, data)
    log.close()


def demo_log_seeds(tmp):
    """Each demo log's first episode, cut short (about 40 events), and the same with a torn tail."""
    seeds = []
    for name in sorted(os.listdir(DEMOS)):
        if not name.endswith(".lcmlog"):
            continue
        evs = events(os.path.join(DEMOS, name))
        starts = [i for i, e in enumerate(evs) if e[1] == "DEMO_INFO"]
        cut = evs[starts[0]:starts[0] + 40] if starts else evs[:40]
        path = os.path.join(tmp, name)
        write_log(path, cut)
        with open(path, "rb") as f:
            data = f.read()
        seeds += [data, data[:len(data) - 7]]
    return seeds


def csv_seeds():
    head = "episode_id,task,homotopy,t,robot_x,robot_y,person_x,person_y,person_yaw\n"
    rows = []
    for ep, task, hom in (("avoid_0001", "avoid", "left"), ("approach_0002", "approach", "frontal")):
        for k in range(6):
            rows.append("%s,%s,%s,%.1f,%.4f,%.4f,2.9645,-0.1506,-3.1312\n" % (ep, task, hom, 0.1 * k, 5.0 + 0.04 * k,
                                                                               -0.1 + 0.01 * k))
    index = ("episode_id,task,split\navoid_0001,avoid,train\napproach_0002,approach,test\n")
    return [(head + "".join(rows)).encode(), (head + "".join(rows[:3])).encode(), index.encode(),
            (head + "".join(rows[:2]) + "avoid_0001,avoid,left,0.05,nan,0,0,0,0\n").encode()]


def records(evs):
    out = b""
    for _, channel, data in evs:
        if channel in INPUTS:
            out += struct.pack("<BH", INPUTS[channel], len(data)) + data
    return out


def daemon_seeds():
    seeds = []
    for name in sorted(os.listdir(SCENARIOS)):
        if not name.endswith(".lcmlog"):
            continue
        evs = events(os.path.join(SCENARIOS, name))
        seeds.append(records(evs[:30]))                      # start-up: goal, obstacles, people, poses
        if name == "faults.lcmlog":                          # around the planted faults (1.0-1.7 s)
            t0 = evs[0][0]
            seeds.append(records([e for e in evs if 0.9e6 <= e[0] - t0 <= 1.7e6]))
    return seeds


def write_all(out_dir):
    with tempfile.TemporaryDirectory() as tmp:
        corpora = {"model": model_seeds(), "msg_decode": msg_seeds(), "demo_log": demo_log_seeds(tmp),
                   "episode_csv": csv_seeds(), "daemon_inputs": daemon_seeds()}
    for target, seeds in corpora.items():
        d = os.path.join(out_dir, target)
        if os.path.isdir(d):
            shutil.rmtree(d)
        os.makedirs(d)
        for data in seeds:
            with open(os.path.join(d, hashlib.sha1(data).hexdigest()), "wb") as f:
                f.write(data)
    return corpora


def listing(d):
    return {os.path.relpath(os.path.join(r, f), d): open(os.path.join(r, f), "rb").read()
            for r, _, fs in os.walk(d) for f in fs}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=os.path.join(ROOT, "tests", "fuzz", "corpus"), help="output folder")
    ap.add_argument("--check", action="store_true", help="exit 1 if the folder differs from what would be written")
    args = ap.parse_args()
    if args.check:
        with tempfile.TemporaryDirectory() as tmp:
            # Only the targets written here: other folders of the corpus (map, daemon_clock) hold
            # hand-made seeds this script does not own.
            targets = write_all(tmp)
            if any(listing(os.path.join(tmp, t)) != listing(os.path.join(args.out, t)) for t in targets):
                print("%s is stale (run tools/fuzz_corpus.py)" % args.out, file=sys.stderr)
                return 1
        print("%s is up to date" % args.out)
        return 0
    for target, seeds in write_all(args.out).items():
        print("%-14s %3d seeds, %7.1f kB" % (target, len(seeds), sum(map(len, seeds)) / 1024))
    return 0


if __name__ == "__main__":
    sys.exit(main())
