#!/usr/bin/env python3
"""evaluate_segment.py - `gmmrrt-learn segment`'s rules (learner/src/segment.cpp, docs/learner.md
"Raw recordings in") against the labels of the shared real data.

  evaluate_segment.py REAL_DIR [--limit N]

Each UPO avoid episode (REAL_DIR/upo_avoid_episodes.csv with its index) is written as an
unlabelled continuous log (ROBOT_POSE and PEOPLE, no DEMO_INFO), all logs are segmented by one
`gmmrrt-learn segment` run, and the episodes found in each log are compared with the index: found
or not, the task, the homotopy, the share of the episode's samples covered. The segmenting itself is
the learner's (no second copy here). Exit status 0; 1 on bad input; 2 on bad usage.
"""
from __future__ import annotations

import argparse
import math
import subprocess
import sys
import tempfile
from collections import Counter, defaultdict
from pathlib import Path

from gmmrrt_tools.demonstration_log import write_demo_log
from gmmrrt_tools.episodes import EpisodeError, read_episodes
from gmmrrt_tools.runner import find_tool
from gmmrrt_tools.scenes import read_episodes as read_indexed_episodes


def evaluate(real_dir: str, limit: int = 0) -> str:
    real = Path(real_dir)
    episodes = read_indexed_episodes(str(real / "upo_avoid_episodes.csv"), index=str(real / "upo_avoid_index.csv"))
    if limit:
        episodes = episodes[:limit]
    with tempfile.TemporaryDirectory() as tmp:
        logs = []
        for n, ep in enumerate(episodes):
            logs.append(str(Path(tmp) / f"ep{n:05d}.lcmlog"))  # the stem names the episode in the ids
            write_demo_log(logs[-1], [ep], labelled=False)
        out = Path(tmp) / "found.csv"
        r = subprocess.run([find_tool("gmmrrt-learn"), "segment", "-q", "-o", str(out), "--"] + logs,
                           capture_output=True, text=True)
        if r.returncode != 0:
            raise EpisodeError(f"gmmrrt-learn segment failed: {r.stderr.strip()}")
        found_eps, _ = read_episodes(str(out))
    by_log = defaultdict(list)
    for f in found_eps:
        by_log[int(f.id.split("_seg")[0][2:])].append(f)
    found = agree = one = task_ok = 0
    cover = []
    confusion = Counter()
    for n, ep in enumerate(episodes):
        res = by_log.get(n, [])
        truth = ep.meta["homotopy"]
        if not res:
            confusion[(truth, "none")] += 1
            continue
        found += 1
        one += len(res) == 1
        best = max(res, key=len)
        cover.append(len(best) / len(ep))
        task_ok += best.task == "avoid"
        confusion[(truth, best.homotopy)] += 1
        agree += best.homotopy == truth
    total = len(episodes)
    return (f"UPO avoid episodes: {total}; found {found} ({100.0 * found / max(total, 1):.1f} %), exactly one "
            f"episode in {one}; labelled avoid {task_ok}; homotopy agrees with the index in {agree} of {found} "
            f"found ({100.0 * agree / max(found, 1):.1f} %); samples covered (largest found / index): median "
            f"{sorted(cover)[len(cover) // 2] if cover else math.nan:.2f}\n"
            "index homotopy -> segmented: " + ", ".join(f"{a}->{b}: {c}" for (a, b), c in sorted(confusion.items())))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    ap.add_argument("real_dir")
    ap.add_argument("--limit", type=int, default=0, help="only the first N episodes")
    args = ap.parse_args(argv)
    try:
        print(evaluate(args.real_dir, args.limit))
    except EpisodeError as err:
        print(f"evaluate_segment: error: {err}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
