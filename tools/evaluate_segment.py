#!/usr/bin/env python3
"""segment_demos.py - raw teleoperation recordings in, labelled episodes out (rules:
tools/gmmrrt_tools/segment.py and docs/learner.md, "Raw recordings in").

  segment_demos.py segment LOG... -o EPISODES.csv     continuous LCM logs of ROBOT_POSE and PEOPLE
                                                      (no DEMO_INFO) -> an episode CSV for
                                                      `gmmrrt-learn fit --input EPISODES.csv`
  segment_demos.py evaluate REAL_DIR [--limit N]      the rules against the labels of the shared real
                                                      data: each UPO avoid episode written as an
                                                      unlabelled continuous log, segmented, and
                                                      compared with the index (found, task, homotopy)

Notes (a person never still, an encounter that is not a pass, a cut log) go to stderr naming the
file and the person. Exit status 0; 1 on bad input (no file is written); 2 on bad usage.
"""
from __future__ import annotations

import argparse
import math
import sys
import tempfile
from collections import Counter
from pathlib import Path

from gmmrrt_tools.demonstration_log import write_demo_log
from gmmrrt_tools.episodes import EpisodeError, write_episode_csv
from gmmrrt_tools.scenes import read_episodes
from gmmrrt_tools.segment import SegmentError, segment_log


def cmd_segment(args) -> int:
    episodes = []
    for log in args.logs:
        res = segment_log(log)
        for n in res.notes:
            print(f"segment_demos: note: {n}", file=sys.stderr)
        print(f"segment_demos: {log}: {len(res.episodes)} episodes ("
              + ", ".join(f"{k[0]} {k[1]}: {v}" for k, v in sorted(Counter((e.task, e.homotopy)
                                                                           for e in res.episodes).items())) + ")",
              file=sys.stderr)
        episodes += res.episodes
    if not episodes:
        raise SegmentError(f"no episode found in {', '.join(args.logs)}: nothing written")
    write_episode_csv(args.output, episodes)
    print(f"segment_demos: wrote {len(episodes)} episodes to {args.output}", file=sys.stderr)
    return 0


def cmd_evaluate(args) -> int:
    real = Path(args.real_dir)
    # The learner's reader (gmmrrt-learn dump), each episode with its index row in ep.meta.
    episodes = read_episodes(str(real / "upo_avoid_episodes.csv"), index=str(real / "upo_avoid_index.csv"))
    if args.limit:
        episodes = episodes[:args.limit]
    found = agree = one = 0
    task_ok = 0
    cover = []
    confusion = Counter()
    with tempfile.TemporaryDirectory() as tmp:
        for ep in episodes:
            p = Path(tmp) / f"{ep.id}.lcmlog"
            write_demo_log(str(p), [ep], labelled=False)
            res = segment_log(str(p))
            if not res.episodes:
                confusion[(ep.meta["homotopy"], "none")] += 1
                continue
            found += 1
            one += len(res.episodes) == 1
            best = max(res.episodes, key=len)
            cover.append(len(best) / len(ep))
            task_ok += best.task == "avoid"
            confusion[(ep.meta["homotopy"], best.homotopy)] += 1
            agree += best.homotopy == ep.meta["homotopy"]
    n = len(episodes)
    print(f"UPO avoid episodes: {n}; found {found} ({100.0 * found / n:.1f} %), exactly one episode in "
          f"{one}; labelled avoid {task_ok}; homotopy agrees with the index in {agree} of {found} found "
          f"({100.0 * agree / max(found, 1):.1f} %); samples covered (largest found / index): median "
          f"{sorted(cover)[len(cover) // 2] if cover else math.nan:.2f}")
    print("index homotopy -> segmented: " + ", ".join(f"{a}->{b}: {c}" for (a, b), c in sorted(confusion.items())))
    return 0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    sub = ap.add_subparsers(dest="cmd", required=True)
    s = sub.add_parser("segment", help="continuous logs -> labelled episode CSV")
    s.add_argument("logs", nargs="+")
    s.add_argument("-o", "--output", required=True)
    e = sub.add_parser("evaluate", help="the rules against the shared real data's labels")
    e.add_argument("real_dir")
    e.add_argument("--limit", type=int, default=0, help="only the first N episodes")
    args = ap.parse_args(argv)
    try:
        return cmd_segment(args) if args.cmd == "segment" else cmd_evaluate(args)
    except EpisodeError as err:
        print(f"segment_demos: error: {err}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
