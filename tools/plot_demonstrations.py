#!/usr/bin/env python3
"""plot_demonstrations.py - demonstrations (paper Sect. 2 tasks, as in its Fig. 2) in the person's frame
(x', y'; the person at the origin facing +x, theta > 0 on their left; ../shared/data/real/README.md),
one row per task, synthetic
(logs/demos) and real side by side: UPO avoid (a random sample of the frontal encounters, where
the person faces the oncoming robot as in the paper's avoid task) and UCY approach (all). The frame
transform is the C core's (gmmrrt_tools.core.world_to_person), as the learner and planner use it.

  plot_demonstrations.py [--demos logs/demos] [--real-data DIR] [--real-sample 40] [--seed 1]
                [--out docs/img/demonstrations.png]
"""
from __future__ import annotations

import argparse
import glob
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from gmmrrt_tools import core  # noqa: E402
from gmmrrt_tools.episodes import EpisodeError, read_episodes  # noqa: E402
from gmmrrt_tools.runner import MissingTool  # noqa: E402
from gmmrrt_tools.realdata import select_upo  # noqa: E402

COLORS = {"left": "tab:blue", "right": "tab:orange", "frontal": "tab:green"}


def person_frame(ep):
    pts = [core.world_to_person((ep.person_x[i], ep.person_y[i], ep.person_yaw[i]), ep.robot_x[i], ep.robot_y[i])
           for i in range(len(ep))]
    a = np.array(pts)
    return a[:, 0], a[:, 1]


def extent(episodes, cap_m: float = 7.0) -> float:
    """Half-width [m] of a square view holding every path (rounded up to 0.5 m, at most cap_m)."""
    m = max(float(np.max(np.abs(np.concatenate(person_frame(e))))) for e in episodes)
    return min(math.ceil((m + 0.2) * 2.0) / 2.0, cap_m)


def draw(ax, episodes, title, lim):
    seen = set()
    order = {"left": 0, "right": 1, "frontal": 2}
    for ep in sorted(episodes, key=lambda e: order.get(e.homotopy, 3)):
        x, y = person_frame(ep)
        label = ep.homotopy if ep.homotopy not in seen else None
        seen.add(ep.homotopy)
        ax.plot(x, y, "-", color=COLORS.get(ep.homotopy, "gray"), lw=1.0, alpha=0.75, label=label)
        ax.plot(x[0], y[0], "o", color=COLORS.get(ep.homotopy, "gray"), ms=3, alpha=0.9)
        ax.plot(x[-1], y[-1], "s", color=COLORS.get(ep.homotopy, "gray"), ms=3, alpha=0.9)
    ax.add_patch(plt.Circle((0, 0), 0.25, color="black", fill=False, lw=1.5))
    ax.annotate("", xy=(0.6, 0), xytext=(0, 0), arrowprops=dict(arrowstyle="->", lw=1.5))
    ax.text(0.0, -0.45, "person", ha="center", va="top", fontsize=8)
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    ax.set_aspect("equal")
    ax.grid(True, lw=0.3)
    ax.set_title(title, fontsize=10)
    ax.set_xlabel("x' [m] (person's front)")
    ax.set_ylabel("y' [m] (person's left)")
    ax.legend(loc="lower left", fontsize=8, title="homotopy", title_fontsize=8)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    ap.add_argument("--demos", default="logs/demos", help="folder of the synthetic logs")
    ap.add_argument("--real-data", default=os.environ.get("GMMRRT_REAL_DATA"),
                    help="folder of the real data (default $GMMRRT_REAL_DATA)")
    ap.add_argument("--real-sample", type=int, default=40, help="UPO avoid episodes drawn (default 40)")
    ap.add_argument("--seed", type=int, default=1, help="seed of the UPO sample (default 1)")
    ap.add_argument("--out", default="docs/img/demonstrations.png", help="PNG to write")
    args = ap.parse_args(argv)
    if args.real_sample < 1:
        ap.error("--real-sample must be >= 1")
    if not args.real_data or not os.path.isdir(args.real_data):
        print(f"plot_demonstrations: error: real data folder not found ({args.real_data!r}): pass --real-data or set "
              "GMMRRT_REAL_DATA", file=sys.stderr)
        return 1
    try:
        synth = {}
        for task in ("avoid", "approach"):
            files = sorted(glob.glob(os.path.join(args.demos, f"{task}_*.lcmlog")))
            if not files:
                raise EpisodeError(f"no {task}_*.lcmlog in {args.demos}: run tools/synth_demonstrations.py")
            synth[task] = read_episodes(files)[0]
        upo = select_upo(args.real_data, "all", "frontal")
        ucy, _ = read_episodes(os.path.join(args.real_data, "ucy_approach_episodes.csv"))
    except (EpisodeError, core.CoreNotBuilt, MissingTool) as e:
        print(f"plot_demonstrations: error: {e}", file=sys.stderr)
        return 1
    rng = np.random.default_rng(args.seed)
    n_upo = len(upo)
    pick = sorted(rng.choice(len(upo), size=min(args.real_sample, len(upo)), replace=False))
    upo = [upo[i] for i in pick]

    fig, axes = plt.subplots(2, 2, figsize=(11, 11))
    lim_avoid = extent(synth["avoid"] + upo)
    lim_appr = extent(synth["approach"] + ucy)
    draw(axes[0, 0], synth["avoid"], f"avoid, synthetic ({len(synth['avoid'])}; logs/demos)", lim_avoid)
    draw(axes[0, 1], upo, f"avoid, real: UPO teleoperated robot, person facing it ({len(upo)} of {n_upo})", lim_avoid)
    draw(axes[1, 0], synth["approach"], f"approach, synthetic ({len(synth['approach'])}; logs/demos)", lim_appr)
    draw(axes[1, 1], ucy, f"approach, real: UCY pedestrians ({len(ucy)})", lim_appr)
    fig.suptitle("Demonstrations in the person's frame (person at the origin facing +x'; "
                 "o start, \u25a0 end)", fontsize=11)
    fig.tight_layout(rect=(0, 0, 1, 0.97))
    out_dir = os.path.dirname(os.path.abspath(args.out))
    os.makedirs(out_dir, exist_ok=True)
    tmp = os.path.join(out_dir, ".tmp-" + os.path.basename(args.out))
    fig.savefig(tmp, dpi=90, format="png")
    os.replace(tmp, args.out)
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
