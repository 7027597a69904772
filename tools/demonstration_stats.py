#!/usr/bin/env python3
"""demonstration_stats.py - statistics of demonstrations, synthetic against real (paper Sect. 5.1 uses
9 demonstrations per homotopy): per episode the minimum distance to the person, the mean speed
(path length / duration) and the path length over the straight start-goal distance; per set the
mean, std and 5/25/50/75/95 % quantiles, and the two-sample Kolmogorov-Smirnov distance between
the synthetic and the real episodes (0 = same distribution, 1 = disjoint).

  demonstration_stats.py [--demos logs/demos] [--real-data DIR] [--split all|train|test]
                [--encounter frontal|all] [--markdown]

Avoid: logs/demos/avoid_*.lcmlog against UPO avoid (upo_avoid_episodes.csv), by default only the
episodes flagged frontal_encounter in upo_avoid_index.csv (the person faces the oncoming robot, as
in the paper's avoid task and the synthesizer). Approach:
logs/demos/approach_*.lcmlog against UCY approach (ucy_approach_episodes.csv), with the final
distance instead of the minimum one. Distances use the C core's features (gmmrrt_tools.core).
"""
from __future__ import annotations

import argparse
import glob
import os
import sys
from typing import Dict, List

import numpy as np
from scipy.stats import ks_2samp

from gmmrrt_tools import core
from gmmrrt_tools.episodes import Episode, EpisodeError, read_episodes
from gmmrrt_tools.runner import MissingTool
from gmmrrt_tools.realdata import select_upo

QUANTILES = (5, 25, 50, 75, 95)


def distances(ep: Episode) -> np.ndarray:
    return np.array([core.features_from_xy((ep.person_x[i], ep.person_y[i], ep.person_yaw[i]),
                                           ep.robot_x[i], ep.robot_y[i])[0] for i in range(len(ep))])


def episode_metrics(ep: Episode) -> Dict[str, float]:
    d = distances(ep)
    step = np.hypot(np.diff(ep.robot_x), np.diff(ep.robot_y))
    length = float(step.sum())
    straight = float(np.hypot(ep.robot_x[-1] - ep.robot_x[0], ep.robot_y[-1] - ep.robot_y[0]))
    duration = float(ep.t[-1] - ep.t[0])
    return {
        "d_min_m": float(d.min()),
        "d_end_m": float(d[-1]),
        "speed_mps": length / duration if duration > 0 else float("nan"),
        "path_ratio": length / straight if straight > 0.5 else float("nan"),
        "duration_s": duration,
    }


def collect(episodes: List[Episode]) -> Dict[str, np.ndarray]:
    rows = [episode_metrics(e) for e in episodes if len(e) >= 2]
    return {k: np.array([r[k] for r in rows]) for k in rows[0]}


def summary(v: np.ndarray) -> List[float]:
    v = v[np.isfinite(v)]
    return [float(v.mean()), float(v.std(ddof=1)) if len(v) > 1 else 0.0] + \
        [float(q) for q in np.percentile(v, QUANTILES)]


LABELS = {"d_min_m": "min distance to the person [m]", "d_end_m": "final distance to the person [m]",
          "speed_mps": "mean speed [m/s]", "path_ratio": "path length / straight line",
          "duration_s": "duration [s]"}


def table(title: str, synth: Dict[str, np.ndarray], real: Dict[str, np.ndarray], n_s: int, n_r: int,
          real_name: str, metrics: List[str]) -> str:
    head = "| metric | set | n | mean | std | " + " | ".join(f"q{q}" for q in QUANTILES) + " | KS |"
    lines = [f"**{title}**", "", head, "|" + "---|" * (head.count("|") - 1)]
    for m in metrics:
        a, b = synth[m][np.isfinite(synth[m])], real[m][np.isfinite(real[m])]
        ks = ks_2samp(a, b).statistic
        for name, v, n in (("synthetic", a, n_s), (real_name, b, n_r)):
            s = summary(v)
            lines.append(f"| {LABELS[m]} | {name} | {len(v)} | " + " | ".join(f"{x:.2f}" for x in s) +
                         (f" | {ks:.2f} |" if name == "synthetic" else " | |"))
    return "\n".join(lines)


def read_logs(pattern: str) -> List[Episode]:
    files = sorted(glob.glob(pattern))
    if not files:
        raise EpisodeError(f"no demonstration log matches {pattern}")
    eps, warnings = read_episodes(files)
    for w in warnings:
        print(f"warning: {w}", file=sys.stderr)
    return eps


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    ap.add_argument("--demos", default="logs/demos", help="folder of the synthetic logs (default logs/demos)")
    ap.add_argument("--real-data", default=os.environ.get("GMMRRT_REAL_DATA"),
                    help="folder of the real data (default $GMMRRT_REAL_DATA)")
    ap.add_argument("--split", choices=("all", "train", "test"), default="all",
                    help="real UPO episodes to compare with (index split; default all)")
    ap.add_argument("--encounter", choices=("frontal", "all"), default="frontal",
                    help="UPO episodes where the person faces the robot (default), or all")
    ap.add_argument("--markdown", action="store_true", help="print Markdown tables (for docs)")
    args = ap.parse_args(argv)
    if not args.real_data or not os.path.isdir(args.real_data):
        print(f"demonstration_stats: error: real data folder not found ({args.real_data!r}): pass --real-data or set "
              "GMMRRT_REAL_DATA", file=sys.stderr)
        return 1
    try:
        s_avoid = read_logs(os.path.join(args.demos, "avoid_*.lcmlog"))
        s_appr = read_logs(os.path.join(args.demos, "approach_*.lcmlog"))
        upo = select_upo(args.real_data, args.split, args.encounter)
        ucy, _ = read_episodes(os.path.join(args.real_data, "ucy_approach_episodes.csv"))
    except (EpisodeError, core.CoreNotBuilt, MissingTool) as e:
        print(f"demonstration_stats: error: {e}", file=sys.stderr)
        return 1
    what = f"{args.split}, {'frontal encounters' if args.encounter == 'frontal' else 'all encounters'}"
    t1 = table(f"avoid: synthetic ({len(s_avoid)} episodes) vs UPO avoid ({what}, {len(upo)} episodes)",
               collect(s_avoid), collect(upo), len(s_avoid), len(upo), f"UPO {args.split}",
               ["d_min_m", "speed_mps", "path_ratio", "duration_s"])
    t2 = table(f"approach: synthetic ({len(s_appr)} episodes) vs UCY approach ({len(ucy)} episodes)",
               collect(s_appr), collect(ucy), len(s_appr), len(ucy), "UCY",
               ["d_end_m", "d_min_m", "speed_mps", "path_ratio", "duration_s"])
    text = t1 + "\n\n" + t2 + "\n"
    if not args.markdown:
        text = text.replace("**", "")
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
