#!/usr/bin/env python3
"""Does making paths drivable (gmmrrt-plan's default output) make them less human-like?

The protocol of `tools/experiments.py real` (UPO avoid: model fitted on the train split, every test
episode planned from the mover's first to last position around its person, seed = base + episode,
4000 iterations, robot radius 0.3 m), each episode planned once and printed twice: the tree's path
(--raw-path) and the drivable path (shortcut, arcs of --min-turn-radius, yaw = tangent). Both are
scored against what the human drove: TDM (paper eq. 2), l_e, closest distance to the person, the
largest turn within 0.1 m and the summed heading change (tools/gmmrrt_tools/metrics.py).

    GMMRRT_BIN_DIR=build/bin .venv/bin/python tools/drivable_tdm.py [--real-data DIR] [--radius 0.3 ...]
"""
from __future__ import annotations

import argparse
import math
import os
import sys
from pathlib import Path

import numpy as np

from gmmrrt_tools import metrics as M
from gmmrrt_tools import runner as R
from gmmrrt_tools import scenes as S

ROOT = Path(__file__).resolve().parent.parent

ROBOT_RADIUS_M = 0.3
CLEARANCE_M = ROBOT_RADIUS_M + 0.25 + 0.05  # as tools/experiments.py
ITERATIONS = 4000
SEED = 1


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--real-data", default=os.environ.get("GMMRRT_REAL_DATA", str(ROOT.parent / "shared" / "data" / "real")))
    ap.add_argument("--work", default=str(ROOT / "out" / "experiments"), help="scratch folder for the model")
    ap.add_argument("--radius", type=float, action="append", help="--min-turn-radius values (default 0.3 and 0.6)")
    a = ap.parse_args(argv)
    real = Path(a.real_data)
    ep_csv, idx = real / "upo_avoid_episodes.csv", real / "upo_avoid_index.csv"
    if not ep_csv.exists():
        sys.exit(f"drivable_tdm: real data not found at {real} (set GMMRRT_REAL_DATA or --real-data)")
    bin_dir = os.environ.get("GMMRRT_BIN_DIR")
    mdl = R.fit_model(Path(a.work) / "models" / "upo_avoid_train_all.gmm", "avoid", [str(ep_csv)], homotopy="all",
                      seed=SEED, index=str(idx), split="train", bin_dir=bin_dir)
    eps = S.read_episodes(str(ep_csv), index=str(idx), split="test")
    variants = [("tree path (--raw-path)", ["--raw-path"])]
    for r in a.radius or [0.3, 0.6]:
        variants.append((f"drivable, R = {r:g} m", ["--min-turn-radius", repr(r)]))
    rows = {label: [] for label, _ in variants}
    for k, e in enumerate(eps):
        scene = S.episode_scene(e, clearance_m=CLEARANCE_M)
        for label, extra in variants:
            argv = R.plan_argv(scene, "gmm-rrt-star", SEED + k, model=str(mdl), iterations=ITERATIONS,
                               robot_radius_m=ROBOT_RADIUS_M, extra=extra, bin_dir=bin_dir)
            res = R.run_plan(argv, SEED + k)
            if len(res.path) < 2:
                rows[label].append(None)
                continue
            rows[label].append((M.tdm_pair(e.xy, res.path), M.length_error_pair(e.xy, res.path),
                                M.min_distance_to_people(res.path, [e.person]), M.max_turn_per_step(res.path, 0.1),
                                M.summed_heading_change(res.path)))
    ok = [k for k in range(len(eps)) if all(rows[l][k] is not None for l in rows)]
    print(f"UPO avoid test split: {len(eps)} episodes, {len(ok)} planned by every variant; GMM-RRT*, model fitted on "
          f"the train split, {ITERATIONS} iterations, seed {SEED} + episode\n")
    print("| output | TDM vs human (m) | l_e (%) | closest to person (m) | max turn in 0.1 m (deg) | summed heading change (rad) |")
    print("|---|---|---|---|---|---|")
    human_turn = [M.max_turn_per_step(eps[k].xy, 0.1) for k in ok]
    for label, _ in variants:
        v = np.array([rows[label][k] for k in ok])
        print(f"| {label} | {v[:, 0].mean():.3f} ± {v[:, 0].std():.3f} | {100 * v[:, 1].mean():.1f} | "
              f"{v[:, 2].mean():.2f} | {math.degrees(np.median(v[:, 3])):.1f} median, {math.degrees(v[:, 3].max()):.1f} max | "
              f"{v[:, 4].mean():.2f} |")
    print(f"| human | – | – | {np.mean([M.min_distance_to_people(eps[k].xy, [eps[k].person]) for k in ok]):.2f} | "
          f"{math.degrees(np.median(human_turn)):.1f} median, {math.degrees(np.max(human_turn)):.1f} max | "
          f"{np.mean([M.summed_heading_change(eps[k].xy) for k in ok]):.2f} |")


if __name__ == "__main__":
    main()
