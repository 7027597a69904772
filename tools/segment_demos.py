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
import csv
import math
import sys
import tempfile
from collections import Counter
from pathlib import Path

import lcm

from gmmrrt_tools.demolog import CH_PEOPLE, CH_POSE, people_t, pose2d_t
from gmmrrt_tools.episodes import EpisodeError, read_episode_csv, write_episode_csv
from gmmrrt_tools.segment import SegmentError, segment_log

T0_UTIME = 1_700_000_000_000_000


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


def write_unlabelled_log(path: Path, ep) -> None:
    """The episode as a recorder would have logged it: ROBOT_POSE and PEOPLE, no DEMO_INFO."""
    log = lcm.EventLog(str(path), "w", overwrite=True)
    for i in range(len(ep)):
        utime = T0_UTIME + int(round(ep.t[i] * 1e6))
        pe = people_t()
        pe.utime, pe.num_people = utime, 1
        q = pe.people[0]
        q.utime, q.id, q.x, q.y, q.yaw, q.vx, q.vy = utime, 1, ep.person_x[i], ep.person_y[i], ep.person_yaw[i], 0.0, 0.0
        log.write_event(utime, CH_PEOPLE, pe.encode())
        po = pose2d_t()
        po.utime, po.x, po.y, po.yaw = utime, ep.robot_x[i], ep.robot_y[i], 0.0
        log.write_event(utime, CH_POSE, po.encode())
    log.close()


def cmd_evaluate(args) -> int:
    real = Path(args.real_dir)
    with open(real / "upo_avoid_index.csv", newline="") as f:
        index = {r["episode_id"]: r for r in csv.DictReader(f)}
    episodes = read_episode_csv(str(real / "upo_avoid_episodes.csv"))
    if args.limit:
        episodes = episodes[:args.limit]
    found = agree = one = 0
    task_ok = 0
    cover = []
    confusion = Counter()
    with tempfile.TemporaryDirectory() as tmp:
        for ep in episodes:
            p = Path(tmp) / f"{ep.id}.lcmlog"
            write_unlabelled_log(p, ep)
            res = segment_log(str(p))
            if not res.episodes:
                confusion[(index[ep.id]["homotopy"], "none")] += 1
                continue
            found += 1
            one += len(res.episodes) == 1
            best = max(res.episodes, key=len)
            cover.append(len(best) / len(ep))
            task_ok += best.task == "avoid"
            confusion[(index[ep.id]["homotopy"], best.homotopy)] += 1
            agree += best.homotopy == index[ep.id]["homotopy"]
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
