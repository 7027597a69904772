#!/usr/bin/env python3
"""synth_demonstrations.py - synthetic demonstrations of the paper's social tasks, shaped like a careful
human teleoperator, written as demonstration logs (paper Sect. 2 tasks; Sect. 5.1: 9 demonstrations per task
and homotopy; layout in docs/demonstrations.md).

Tasks and homotopies (paper Sect. 2; the person stands; theta > 0 is the person's left, 0 their front):
  avoid    left | right       the person faces the oncoming robot; pass them on their left / right on
                              the way to a goal ~4.5 m on
  approach frontal           start in the person's front half-plane, stop in front of them
           left | right       start behind the person, curve round their left / right side, stop in front

Each demonstration: the person's pose, the start, the passing or via point and the goal are drawn
per trial; a smooth reference (cubic spline through them, end tangents fixed) is tracked by a
unicycle (pure pursuit) with bounded speed, acceleration and turn rate, simulated at 100 Hz; the
robot and the person are then "seen" by a motion-capture system (OptiTrack-like: ~1 mm position and
~0.2 deg heading noise) and logged at 5 Hz (ROBOT_POSE) and every 4 s (PEOPLE; the person stands). The spreads of the
passing distance and of the final approach distance are those of the real data
(../shared/data/real: UPO frontal-encounter avoid d_min and facing, UCY approach d_end; numbers
below and in docs/demonstrations.md). Deterministic: the same --seed gives byte-identical logs.

  synth_demonstrations.py --seed 1 --out-dir logs/demos
"""
from __future__ import annotations

import argparse
import math
import os
import sys
from dataclasses import dataclass
from typing import List, Optional, Tuple

import numpy as np
from scipy.interpolate import CubicSpline

from gmmrrt_tools import core
from gmmrrt_tools.demonstration_log import DEFAULT_START_UTIME, MAX_PERSON_AGE_S, write_demo_log
from gmmrrt_tools.episodes import Episode

# ---------------------------------------------------------------- distributions (from the real data)
# Avoid, as in the paper (Sect. 2: "the robot avoids a standing person that is facing it"), is
# compared with the UPO episodes flagged frontal_encounter (122 of 398: the person faces the
# oncoming robot). From upo_avoid_index.csv, rows with frontal_encounter == True:
# - passing distance (distance at the closest point), d_min deciles (0, 10, ..., 100 %), drawn by
#   inverse CDF: numpy.percentile(d_min, range(0, 101, 10)); mean 1.20 m, std 0.38 m, right-skewed;
UPO_DMIN_DECILES_M = (0.63, 0.85, 0.92, 0.96, 1.00, 1.06, 1.12, 1.27, 1.50, 1.79, 2.43)
# - how far the person's facing is off the robot's start, |theta_start| deciles [deg];
UPO_FACING_OFFSET_DECILES_DEG = (0.4, 3.0, 6.5, 9.9, 13.2, 15.8, 18.5, 24.9, 31.3, 38.9, 44.9)
# - start and goal distance: d_start 2.63 +- 0.61 m, d_end 2.29 +- 0.68 m.
AVOID_START_MEAN_M, AVOID_START_STD_M = 2.63, 0.61
AVOID_END_MEAN_M, AVOID_END_STD_M = 2.29, 0.68
# Final distance of approach: UCY approach d_end (30 episodes; mean 1.06 m, std 0.47 m), deciles
# as above from ucy_index.csv (task approach); a robot stops no closer than 0.50 m (UCY has
# pedestrians who stop shoulder to shoulder at 0.41 m).
UCY_DEND_DECILES_M = (0.41, 0.49, 0.62, 0.71, 0.82, 0.95, 1.19, 1.43, 1.60, 1.67, 1.91)
APPROACH_END_MIN_M = 0.50
# Start distance of approach: UCY d_start 4.68 +- 1.06 m; shortened to 3.0 +- 0.5 m to keep logs small.
APPROACH_START_MEAN_M, APPROACH_START_STD_M = 3.0, 0.5
# Speed: UPO's teleoperated robot averages 0.27 m/s (capped at 0.40 m/s by the platform); UCY
# walkers approaching someone 0.60 +- 0.18 m/s. A careful teleoperator of a faster platform:
# cruise 0.50 +- 0.06 m/s, never above 0.65 m/s.
CRUISE_MEAN, CRUISE_STD, V_MAX = 0.50, 0.06, 0.65
A_MAX = 0.35         # m/s^2, speeding up and braking
OMEGA_MAX = 0.9      # rad/s, turn rate bound
KAPPA_MAX = 2.0      # 1/m, curvature bound (turn radius >= 0.5 m)
# Motion capture (OptiTrack-like) noise, standard deviations.
POS_NOISE_M = 0.001
YAW_NOISE_RAD = math.radians(0.2)
PERSON_YAW_NOISE_RAD = math.radians(0.5)
PERSON_SWAY_M = 0.01  # standing people sway; slow random motion of ~1 cm
SIM_HZ = 100
# Log rates: the whole of logs/demos/ must stay well under 1 MB. A pose2d_t event is 103 bytes,
# a people_t event 1.7 kB (all 32 slots are encoded), 45 demonstrations last ~450 s.
POSE_HZ = 5           # ROBOT_POSE rate: between UCY (2.5 Hz) and UPO (10 Hz)
PEOPLE_EVERY = 20     # PEOPLE every 20 poses = every 4 s; the person stands (readers accept 5 s)

DEMOS_PER_HOMOTOPY = 9  # as in the paper
SETS = [("avoid", "left"), ("avoid", "right"), ("approach", "frontal"), ("approach", "left"),
        ("approach", "right")]


# Angle wrapping and the features (d, theta) are the C core's (planner/src/features.c, through
# gmmrrt_tools.core): the demonstrations are made with the planner's own conventions.
wrap = core.wrap_angle


def truncnorm(rng: np.random.Generator, mean: float, std: float, lo: float, hi: float) -> float:
    for _ in range(1000):
        v = rng.normal(mean, std)
        if lo <= v <= hi:
            return float(v)
    return float(min(max(mean, lo), hi))


def from_deciles(rng: np.random.Generator, deciles) -> float:
    """A draw from the distribution whose deciles (0, 10, ..., 100 %) are given (inverse CDF,
    linear between deciles)."""
    return float(np.interp(rng.uniform(0.0, 10.0), np.arange(11), deciles))


def from_person(person: Tuple[float, float, float], d: float, theta: float) -> np.ndarray:
    """World point at distance d, bearing theta in the person's frame (gmmrrt_features_to_xy)."""
    return np.array(core.features_to_xy(person, d, theta))


def features(person, x, y) -> Tuple[np.ndarray, np.ndarray]:
    """(d, theta) of each point (x[i], y[i]) (gmmrrt_features_from_xy)."""
    f = np.array([core.features_from_xy(person, xi, yi) for xi, yi in zip(np.ravel(x), np.ravel(y))])
    return f[:, 0], f[:, 1]


# ---------------------------------------------------------------- reference path and tracking

def spline_path(points: np.ndarray, start_dir: float, end_dir: float, step_m: float = 0.01) -> np.ndarray:
    """Dense points (every step_m) of a C2 cubic spline through `points`, chord-length parametrised,
    with the end tangents set to the given directions [rad]."""
    seg = np.hypot(*np.diff(points, axis=0).T)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    cs = CubicSpline(s, points, bc_type=((1, [math.cos(start_dir), math.sin(start_dir)]),
                                         (1, [math.cos(end_dir), math.sin(end_dir)])))
    u = np.linspace(0.0, s[-1], max(int(s[-1] / step_m), 2))
    return cs(u)


@dataclass
class Trace:
    t: np.ndarray
    x: np.ndarray
    y: np.ndarray
    yaw: np.ndarray


def track(path: np.ndarray, rng: np.random.Generator) -> Optional[Trace]:
    """A unicycle following `path` by pure pursuit, like a careful driver: speeds up to its cruise
    speed, slows for curves and to stop at the end; |v| <= V_MAX, |dv/dt| <= A_MAX,
    |omega| <= min(OMEGA_MAX, KAPPA_MAX v). None when it does not reach the end in time (the
    caller draws another trial)."""
    cruise = truncnorm(rng, CRUISE_MEAN, CRUISE_STD, 0.32, V_MAX)
    lookahead = 0.35 + rng.uniform(0.0, 0.15)
    dt = 1.0 / SIM_HZ
    seg = np.hypot(*np.diff(path, axis=0).T)
    arc = np.concatenate([[0.0], np.cumsum(seg)])
    total = arc[-1]
    heading = np.arctan2(np.gradient(path[:, 1]), np.gradient(path[:, 0]))
    curvature = np.abs(np.gradient(np.unwrap(heading))) / np.maximum(np.gradient(arc), 1e-9)
    x, y = path[0]
    yaw = heading[0] + rng.normal(0.0, math.radians(2.0))
    v = 0.0
    idx = 0
    out = [(0.0, x, y, yaw)]
    t = 0.0
    reached = False
    for _ in range(int((3.0 * total / cruise + 10.0) * SIM_HZ)):
        # Progress: the nearest path point ahead of the last one (never goes back).
        window = path[idx:idx + 200]
        idx += int(np.argmin(np.hypot(window[:, 0] - x, window[:, 1] - y)))
        remaining = total - arc[idx] + math.hypot(path[-1, 0] - x, path[-1, 1] - y) * (idx == len(path) - 1)
        if idx >= len(path) - 2 and math.hypot(path[-1, 0] - x, path[-1, 1] - y) < 0.03 or \
                (remaining < 0.03 and v < 0.02):
            reached = True
            break
        ahead = np.searchsorted(arc, arc[idx] + lookahead)
        ahead = min(ahead, len(path) - 1)
        gx, gy = path[ahead]
        alpha = wrap(math.atan2(gy - y, gx - x) - yaw)
        dist_goal = max(math.hypot(path[-1, 0] - x, path[-1, 1] - y), remaining)
        kappa_ahead = float(np.max(curvature[idx:min(ahead + 1, len(path))])) if ahead > idx else 0.0
        v_des = min(cruise, math.sqrt(2.0 * A_MAX * 0.8 * max(dist_goal - 0.02, 0.0)),
                    OMEGA_MAX / max(kappa_ahead, 1e-6))
        if abs(alpha) > 1.0:
            v_des = min(v_des, 0.1)  # turn mostly in place when far off the path direction
        v += float(np.clip(v_des - v, -A_MAX * dt, A_MAX * dt))
        v = min(max(v, 0.0), V_MAX)
        lk = max(math.hypot(gx - x, gy - y), 0.05)
        omega = 2.0 * max(v, 0.05) * math.sin(alpha) / lk
        omega = float(np.clip(omega, -min(OMEGA_MAX, KAPPA_MAX * max(v, 0.1)), min(OMEGA_MAX, KAPPA_MAX * max(v, 0.1))))
        x += v * math.cos(yaw) * dt
        y += v * math.sin(yaw) * dt
        yaw = wrap(yaw + omega * dt)
        t += dt
        out.append((t, x, y, yaw))
    if not reached:
        return None
    a = np.array(out)
    return Trace(a[:, 0], a[:, 1], a[:, 2], a[:, 3])


# ---------------------------------------------------------------- tasks

def person_pose(rng) -> Tuple[float, float, float]:
    return (float(rng.uniform(-1.0, 1.0)), float(rng.uniform(-1.0, 1.0)), float(rng.uniform(-math.pi, math.pi)))


def plan_avoid(rng, homotopy: str):
    """Start and goal on opposite sides of the person (about 4.5 m apart, as UPO's goals), the
    person facing the robot's start (off by UPO's frontal-encounter spread), passing point beside
    the person at the drawn passing distance, on the requested side."""
    px, py = (float(v) for v in rng.uniform(-1.0, 1.0, size=2))
    travel = float(rng.uniform(-math.pi, math.pi))  # world direction start -> goal
    d_pass = from_deciles(rng, UPO_DMIN_DECILES_M)
    # Start and goal farther than the passing point, so the closest approach is the pass itself
    # (the homotopy is read at the closest point, as in the real data's index).
    d_start = max(truncnorm(rng, AVOID_START_MEAN_M, AVOID_START_STD_M, 1.8, 3.8), d_pass + 0.8)
    d_end = max(truncnorm(rng, AVOID_END_MEAN_M, AVOID_END_STD_M, 1.6, 3.6), d_pass + 0.8)
    p = np.array([px, py])
    u = np.array([math.cos(travel), math.sin(travel)])
    n = np.array([-u[1], u[0]])
    lat_s, lat_g = rng.normal(0.0, 0.25, size=2)  # start/goal not exactly in line with the person
    start = p - u * math.sqrt(max(d_start ** 2 - lat_s ** 2, 1.0)) + n * lat_s
    goal = p + u * math.sqrt(max(d_end ** 2 - lat_g ** 2, 1.0)) + n * lat_g
    offset = math.radians(from_deciles(rng, UPO_FACING_OFFSET_DECILES_DEG)) * (1 if rng.uniform() < 0.5 else -1)
    yaw = wrap(math.atan2(start[1] - py, start[0] - px) + offset)
    person = (px, py, yaw)
    # Side of the travel direction that puts the passing point at theta > 0 (left) or < 0.
    theta_normal = wrap(travel + math.pi / 2 - yaw)  # bearing of the travel's left normal, person frame
    side = 1.0 if (theta_normal > 0) == (homotopy == "left") else -1.0
    along = rng.normal(0.0, 0.2)  # the driver passes a little before or after abeam
    via = p + side * n * d_pass + u * along
    # Hold the passing offset over ~1.2 m (a driver lines up beside the person, then passes):
    # without it the tracker cuts the corner and narrows the spread of passing distances.
    half = 0.6 * min(1.0, d_start / 2.5, d_end / 2.5)
    pts = np.array([start, via - u * half, via + u * half, goal])
    return person, pts, travel + rng.normal(0, 0.1), travel + rng.normal(0, 0.1), d_pass


def plan_approach(rng, homotopy: str):
    """Stop in front of the person, facing them; frontal starts in their front half-plane, left /
    right start behind and go round that side (via a point abeam at a safe distance)."""
    person = person_pose(rng)
    d_end = max(from_deciles(rng, UCY_DEND_DECILES_M), APPROACH_END_MIN_M)
    theta_end = truncnorm(rng, 0.0, math.radians(12.0), -math.radians(30), math.radians(30))
    d_start = truncnorm(rng, APPROACH_START_MEAN_M, APPROACH_START_STD_M, 2.2, 4.0)
    goal = from_person(person, d_end, theta_end)
    if homotopy == "frontal":
        theta_start = float(rng.uniform(-math.radians(75), math.radians(75)))
        start = from_person(person, d_start, theta_start)
        mid_theta = 0.5 * (theta_start + theta_end) + rng.normal(0, math.radians(8))
        mid_d = 0.5 * (d_start + d_end) + rng.normal(0, 0.15)
        pts = np.array([start, from_person(person, mid_d, mid_theta), goal])
    else:
        s = 1.0 if homotopy == "left" else -1.0
        # Behind the person, up to 20 deg across the back (the theta = +-pi seam) on the other side.
        theta_start = wrap(s * float(rng.uniform(math.radians(125), math.radians(200))))
        start = from_person(person, d_start, theta_start)
        d_via = truncnorm(rng, 1.5, 0.25, 1.1, 2.1)
        via1 = from_person(person, d_via, s * (math.radians(95) + rng.normal(0, math.radians(8))))
        via2 = from_person(person, 0.5 * (d_via + d_end) + 0.15, s * math.radians(50 + rng.normal(0, 6)))
        pts = np.array([start, via1, via2, goal])
    first = math.atan2(*(pts[1] - pts[0])[::-1])
    # Arrive half turned towards the person: the direction of the last leg, rotated halfway to
    # facing them (forcing the full facing direction makes the spline hook past the goal).
    last_leg = math.atan2(*(pts[-1] - pts[-2])[::-1])
    face = math.atan2(person[1] - goal[1], person[0] - goal[0])
    end_dir = last_leg + 0.5 * wrap(face - last_leg)
    return person, pts, first + rng.normal(0, 0.1), end_dir, d_end


def side_ok(task: str, homotopy: str, person, tr: Trace) -> bool:
    d, th = features(person, tr.x, tr.y)
    if d.min() < 0.45:
        return False
    if task == "avoid":
        # The side at the closest point, clear of the person's front/back axis by 20 deg so that
        # noise cannot flip it.
        th_min = th[int(np.argmin(d))]
        margin = math.radians(20)
        return (th_min > 0) == (homotopy == "left") and margin < abs(th_min) < math.pi - margin
    if homotopy == "frontal":
        return abs(th[0]) < math.pi / 2
    # Round the requested side: abeam (|theta| near 90 deg) on that side, never on the other.
    mid = (np.abs(np.abs(th) - math.pi / 2) < math.radians(20))
    want = th > 0 if homotopy == "left" else th < 0
    return bool(mid.any() and np.all(want[mid]))


def observe(task, homotopy, idx, person, tr: Trace, rng) -> Episode:
    """Motion-capture view of a simulated run: POSE_HZ samples with noise; the person sways slowly."""
    step = SIM_HZ // POSE_HZ
    keep = np.arange(0, len(tr.t), step)
    n = len(keep)
    t = np.round(tr.t[keep], 6)
    rx = tr.x[keep] + rng.normal(0, POS_NOISE_M, n)
    ry = tr.y[keep] + rng.normal(0, POS_NOISE_M, n)
    ryaw = np.array([wrap(a) for a in tr.yaw[keep] + rng.normal(0, YAW_NOISE_RAD, n)])
    # Sway: an Ornstein-Uhlenbeck walk (time constant 2 s, stationary std PERSON_SWAY_M).
    sway = np.zeros((n, 2))
    k = math.exp(-1.0 / (POSE_HZ * 2.0))
    for i in range(1, n):
        sway[i] = k * sway[i - 1] + math.sqrt(1 - k * k) * rng.normal(0, PERSON_SWAY_M, 2)
    px = person[0] + sway[:, 0] + rng.normal(0, POS_NOISE_M, n)
    py = person[1] + sway[:, 1] + rng.normal(0, POS_NOISE_M, n)
    pyaw = np.array([wrap(person[2] + e) for e in rng.normal(0, PERSON_YAW_NOISE_RAD, n)])
    return Episode(f"{task}_{homotopy}_{idx}", task, homotopy, t, rx, ry, ryaw, px, py, pyaw, person_id=1)


def synthesize(task: str, homotopy: str, count: int, rng: np.random.Generator) -> List[Episode]:
    episodes = []
    while len(episodes) < count:
        if task == "avoid":
            person, pts, d0, d1, _ = plan_avoid(rng, homotopy)
        else:
            person, pts, d0, d1, _ = plan_approach(rng, homotopy)
        tr = track(spline_path(pts, d0, d1), rng)
        if tr is None or not side_ok(task, homotopy, person, tr):
            continue  # the drawn geometry did not give the asked homotopy: draw again
        episodes.append(observe(task, homotopy, len(episodes), person, tr, rng))
    return episodes


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    ap.add_argument("--seed", type=int, default=1, help="random seed (default 1); same seed, same logs")
    ap.add_argument("--out-dir", default="logs/demos", help="folder for the logs (default logs/demos)")
    ap.add_argument("--count", type=int, default=DEMOS_PER_HOMOTOPY,
                    help=f"demonstrations per task and homotopy (default {DEMOS_PER_HOMOTOPY}, as in the paper)")
    args = ap.parse_args(argv)
    if args.count < 1:
        ap.error("--count must be >= 1")
    if (PEOPLE_EVERY - 1) / POSE_HZ > MAX_PERSON_AGE_S:
        ap.error("PEOPLE rate too low for the readers' MAX_PERSON_AGE_S")
    try:
        os.makedirs(args.out_dir, exist_ok=True)
    except OSError as e:
        print(f"synth_demonstrations: error: cannot create {args.out_dir}: {e.strerror}", file=sys.stderr)
        return 1
    for k, (task, homotopy) in enumerate(SETS):
        # One stream per set, derived from the seed: each file is reproducible on its own.
        rng = np.random.default_rng([args.seed, k])
        eps = synthesize(task, homotopy, args.count, rng)
        path = os.path.join(args.out_dir, f"{task}_{homotopy}.lcmlog")
        write_demo_log(path, eps, start_utime=DEFAULT_START_UTIME + k * 3_600_000_000, people_every=PEOPLE_EVERY)
        size = os.path.getsize(path)
        print(f"wrote {path}: {task} {homotopy}, {len(eps)} demonstrations, "
              f"{sum(len(e) for e in eps)} poses, {size} bytes")
    return 0


if __name__ == "__main__":
    sys.exit(main())
