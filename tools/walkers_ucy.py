#!/usr/bin/env python3
"""Walking people on the UCY data: does predicting them (gmmrrt-plan --person x,y,yaw,vx,vy) keep the
robot further from real pedestrians than planning them as standing?

For each UCY avoid episode of the shared index (ucy_index.csv; groups walking together left out,
since the robot cannot take one member's place beside the others), the robot replaces the walker
(robot_track): it starts where the walker was at the episode's first step and goes where the walker
was at its last. Everyone else tracked in the scene at that moment (ucy_tracks.csv) is a person at
their position, facing their direction of motion, with the velocity of their next 0.4 s step
(prediction), or the same people without velocities (prediction-free). Both plans (plain RRT*,
drivable path, same seed) are then followed at the walker's own mean speed against where the
pedestrians REALLY were at each moment (their recorded tracks, interpolated; a track that has ended
is gone), and scored by the closest centre distance and by collisions (closer than robot radius +
person radius = 0.55 m). Uses tools/gmmrrt_tools.metrics for nothing it would write twice.

    GMMRRT_BIN_DIR=build/bin .venv/bin/python tools/walkers_ucy.py [--real-data DIR] [--max-episodes N]
"""
from __future__ import annotations

import argparse
import csv
import json
import math
import os
import statistics
import subprocess
import sys
from collections import defaultdict
from pathlib import Path

import numpy as np

from gmmrrt_tools import metrics
from gmmrrt_tools.runner import find_tool

ROOT = Path(__file__).resolve().parent.parent

STEP_S = 0.4
CONTACT_M = 0.55        # robot 0.3 + person 0.25 (the planner's defaults)
CROWD_RADIUS_M = 8.0    # people further from the start-goal segment cannot matter in an episode
MAX_PEOPLE = 32         # GMMRRT_MAX_PEOPLE


def load_tracks(path):
    tracks = defaultdict(dict)  # (scene, track) -> {k: (x, y)}
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            k = int(round(float(r["t"]) / STEP_S))
            tracks[(r["scene"], int(r["track"]))][k] = (float(r["x"]), float(r["y"]))
    return tracks


def position(track, t_steps):
    """Interpolated position at fractional step t_steps; None outside the track."""
    k0 = math.floor(t_steps)
    if k0 in track and k0 + 1 in track:
        a, b = np.array(track[k0]), np.array(track[k0 + 1])
        return a + (t_steps - k0) * (b - a)
    if k0 in track and abs(t_steps - k0) < 1e-9:
        return np.array(track[k0])
    return None


def seg_dist(p, a, b):
    a, b, p = map(np.asarray, (a, b, p))
    v = b - a
    t = 0.0 if v @ v == 0 else min(max((p - a) @ v / (v @ v), 0.0), 1.0)
    return float(np.linalg.norm(p - (a + t * v)))


def plan(bin_path, start, goal, people, seed, speed, with_velocity):
    argv = [bin_path, "--start", f"{start[0]!r},{start[1]!r}", "--goal", f"{goal[0]!r},{goal[1]!r}",
            "--iterations", "3000", "--seed", str(seed), "--nominal-speed", f"{speed!r}", "--json"]
    for x, y, yaw, vx, vy in people:
        argv += ["--person", f"{x!r},{y!r},{yaw!r}" + (f",{vx!r},{vy!r}" if with_velocity else "")]
    r = subprocess.run(argv, capture_output=True, text=True, timeout=120)
    if not r.stdout.strip():
        return None, r.stderr.strip().splitlines()[-1] if r.stderr.strip() else f"exit {r.returncode}"
    out = json.loads(r.stdout)
    return out, out["status"]


def replay(path, speed, t0_steps, crowd_tracks):
    """Closest centre distance to the real pedestrians while following path at speed."""
    pts = metrics.resample_by_arc_length(path, 0.05)
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
    closest = math.inf
    for q, si in zip(pts, s):
        ts = t0_steps + si / speed / STEP_S
        for tr in crowd_tracks:
            p = position(tr, ts)
            if p is not None:
                closest = min(closest, float(np.linalg.norm(q - p)))
    return closest


def crowd_at(crowd_tracks, t_steps, start, goal):
    """People (x, y, yaw, vx, vy) tracked at fractional step t_steps near the segment start-goal,
    velocity from the next 0.4 s of their track (the last one when it ends), the nearest MAX_PEOPLE."""
    crowd = []
    for tr in crowd_tracks:
        p = position(tr, t_steps)
        if p is None:
            continue
        x, y = float(p[0]), float(p[1])
        d = seg_dist((x, y), start, goal)
        if d > CROWD_RADIUS_M:
            continue
        q = position(tr, t_steps + 1.0)
        if q is None:
            q0 = position(tr, t_steps - 1.0)
            v = (p - q0) / STEP_S if q0 is not None else np.zeros(2)
        else:
            v = (q - p) / STEP_S
        vx, vy = float(v[0]), float(v[1])
        sp = math.hypot(vx, vy)
        if sp > 3.0:  # a tracking jump, not a walk (the planner refuses > 3 m/s)
            vx, vy = vx * 3.0 / sp, vy * 3.0 / sp
        crowd.append((d, (x, y, math.atan2(vy, vx) if sp > 0.05 else 0.0, vx, vy)))
    crowd.sort(key=lambda c: c[0])
    return [c[1] for c in crowd[:MAX_PEOPLE]]


def closed_loop(bin_path, start, goal, speed, k0, crowd_tracks, seed, with_velocity, period_s=0.4, max_s=40.0):
    """The robot replans every period_s from where it is (as gmmrrtd does) and drives its plan at
    speed in between; returns (closest distance to the real pedestrians, last status)."""
    pos = np.array(start, dtype=float)
    t, closest, status = 0.0, math.inf, "ok"
    while t < max_s and np.linalg.norm(pos - goal) > 0.3:
        ts = k0 + t / STEP_S
        people = crowd_at(crowd_tracks, ts, tuple(pos), goal)
        out, status = plan(bin_path, tuple(pos), goal, people, seed, speed, with_velocity)
        if out is None or not out["path"]:
            step = np.zeros((1, 2)) + pos  # no plan: the robot stands (a stop) for one period
            pts, s = step, np.zeros(1)
        else:
            pts = metrics.resample_by_arc_length(out["path"], 0.05)
            s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
        horizon = speed * period_s
        keep = s <= horizon + 1e-9
        for q, si in zip(pts[keep], s[keep]):
            tq = k0 + (t + si / speed) / STEP_S
            for tr in crowd_tracks:
                p = position(tr, tq)
                if p is not None:
                    closest = min(closest, float(np.linalg.norm(q - p)))
        pos = pts[keep][-1]
        t += period_s
    return closest, status


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--real-data", default=os.environ.get("GMMRRT_REAL_DATA", str(ROOT.parent / "shared" / "data" / "real")))
    ap.add_argument("--max-episodes", type=int, default=0, help="every n-th episode so that at most N run (0: all)")
    ap.add_argument("--json-out", help="write per-episode records here")
    ap.add_argument("--replan", action="store_true",
                    help="closed loop: replan every 0.4 s from where the robot is, with the crowd of that moment")
    a = ap.parse_args(argv)
    real = Path(a.real_data)
    if not (real / "ucy_index.csv").exists():
        sys.exit(f"walkers_ucy: real data not found at {real} (set GMMRRT_REAL_DATA or --real-data)")
    bin_path = find_tool("gmmrrt-plan", os.environ.get("GMMRRT_BIN_DIR"))
    tracks = load_tracks(real / "ucy_tracks.csv")
    with open(real / "ucy_index.csv", newline="") as f:
        index = [r for r in csv.DictReader(f) if r["task"] == "avoid" and r["same_group"] != "True"]
    if a.max_episodes and len(index) > a.max_episodes:
        index = index[:: max(1, len(index) // a.max_episodes)][: a.max_episodes]

    records = []
    for n, e in enumerate(index):
        scene, walker, k0, k1 = e["scene"], int(e["robot_track"]), int(e["k0"]), int(e["k1"])
        wt = tracks[(scene, walker)]
        if k0 not in wt or k1 not in wt:
            continue
        start, goal = wt[k0], wt[k1]
        speed = min(max(float(e["walker_mean_speed"]), 0.3), 1.5)
        crowd_tracks = [tr for (sc, tid), tr in tracks.items() if sc == scene and tid != walker]
        people = crowd_at(crowd_tracks, k0, start, goal)
        rec = {"episode": e["episode_id"], "people": len(people),
               "walking": sum(math.hypot(p[3], p[4]) >= 0.2 for p in people)}
        for label, vel in (("predicted", True), ("prediction-free", False)):
            if a.replan:
                closest, status = closed_loop(bin_path, start, goal, speed, k0, crowd_tracks, n + 1, vel)
                rec[label + "_status"] = status
                rec[label + "_closest_m"] = closest
                continue
            out, status = plan(bin_path, start, goal, people, n + 1, speed, vel)
            rec[label + "_status"] = status
            if out is None or not out["path"]:
                rec[label + "_closest_m"] = None
                continue
            rec[label + "_closest_m"] = replay(out["path"], speed, k0, crowd_tracks)
        records.append(rec)

    def summary(label):
        d = [r[label + "_closest_m"] for r in records if r[label + "_closest_m"] is not None]
        fails = sum(r[label + "_closest_m"] is None for r in records)
        esc = sum(str(r[label + "_status"]).startswith("escaping") for r in records)
        coll = sum(x < CONTACT_M for x in d)
        return (f"| {label} | {len(d)} | {fails} | {esc} | {coll} ({100.0 * coll / max(len(d), 1):.1f} %) | "
                f"{statistics.median(d):.2f} | {np.percentile(d, 10):.2f} | {min(d):.2f} |")

    both = [r for r in records if r["predicted_closest_m"] is not None and r["prediction-free_closest_m"] is not None]
    better = sum(r["predicted_closest_m"] > r["prediction-free_closest_m"] + 1e-6 for r in both)
    worse = sum(r["predicted_closest_m"] < r["prediction-free_closest_m"] - 1e-6 for r in both)
    print(f"{len(records)} UCY avoid episodes (groups left out), {sum(r['walking'] for r in records)} walking people "
          f"in them at the start (>= 0.2 m/s), robot at the walker's mean speed, plain RRT* 3000 iterations, drivable "
          f"path, {'replanned every 0.4 s' if a.replan else 'one plan'}\n")
    print("| planner | plans | no plan | escapes | collisions (< 0.55 m) | median closest (m) | 10th pct (m) | min (m) |")
    print("|---|---|---|---|---|---|---|---|")
    print(summary("predicted"))
    print(summary("prediction-free"))
    print(f"\nper episode (both planned, {len(both)}): predicted further from the real pedestrians in {better}, "
          f"closer in {worse}")
    if a.json_out:
        Path(a.json_out).write_text(json.dumps(records, indent=1))


if __name__ == "__main__":
    main()
