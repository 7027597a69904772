#!/usr/bin/env python3
"""convert_demonstrations.py - episode CSV <-> demonstration log (paper Sect. 2 / 5.1 demonstrations; layout in
docs/demonstrations.md).

  convert_demonstrations.py csv2log IN.csv OUT.lcmlog [--index INDEX.csv --split train] [--task avoid]
                                            [--homotopy left] [--max-episodes N]
  convert_demonstrations.py log2csv IN.lcmlog OUT.csv

Labels (task, homotopy) are kept both ways. A CSV with many episodes becomes one log with one
DEMO_INFO per episode (episode numbers 0, 1, ... in CSV order); csv2log prints the mapping from
episode number to the CSV's episode_id. log2csv names episodes '<log stem>_<number, 4 digits>'.
Exit status 0 on success, 1 on bad input (the message names the file and line or event; no output
file is left behind), 2 on bad usage.
"""
from __future__ import annotations

import argparse
import sys

from gmmrrt_tools.demonstration_log import write_demo_log
from gmmrrt_tools.episodes import HOMOTOPIES, TASKS, EpisodeError, read_episodes, write_episode_csv


def csv2log(args) -> int:
    if args.split and not args.index:
        raise EpisodeError("--split needs --index (the index CSV with episode_id and split columns)")
    episodes, warnings = read_episodes(args.input, index=args.index)
    for w in warnings:  # e.g. an event listed twice, read once
        print(f"warning: {w}", file=sys.stderr)
    if args.index:
        missing = [e.id for e in episodes if not e.split]
        if missing:
            raise EpisodeError(f"{args.index}: no split for episode '{missing[0]}' of {args.input} "
                               f"({len(missing)} episodes missing)")
        if args.split:
            episodes = [e for e in episodes if e.split == args.split]
    if args.task:
        episodes = [e for e in episodes if e.task == args.task]
    if args.homotopy:
        episodes = [e for e in episodes if e.homotopy == args.homotopy]
    if args.max_episodes is not None:
        episodes = episodes[:args.max_episodes]
    if not episodes:
        raise EpisodeError(f"{args.input}: no episode left after the selection")
    for ep in episodes:
        ep.person_id = args.person_id
    write_demo_log(args.output, episodes)
    if not args.quiet:
        print(f"wrote {args.output}: {len(episodes)} episodes, {sum(len(e) for e in episodes)} samples")
        for n, ep in enumerate(episodes):
            print(f"  episode {n}: {ep.id} {ep.task} {ep.homotopy}")
    return 0


def log2csv(args) -> int:
    episodes, warnings = read_episodes(args.input)
    for w in warnings:
        print(f"warning: {w}", file=sys.stderr)
    write_episode_csv(args.output, episodes)
    if not args.quiet:
        print(f"wrote {args.output}: {len(episodes)} episodes, {sum(len(e) for e in episodes)} samples")
    return 0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    sub = ap.add_subparsers(dest="command", required=True)
    c = sub.add_parser("csv2log", help="episode CSV -> demonstration log")
    c.add_argument("input", help="episode CSV (../shared/data/real/README.md format)")
    c.add_argument("output", help="LCM log to write")
    c.add_argument("--index", help="index CSV with episode_id and split columns")
    c.add_argument("--split", help="keep only episodes of this split (needs --index), e.g. train")
    c.add_argument("--task", choices=sorted(TASKS), help="keep only this task")
    c.add_argument("--homotopy", choices=sorted(HOMOTOPIES), help="keep only this homotopy")
    c.add_argument("--max-episodes", type=int, help="keep at most this many (after the other filters)")
    c.add_argument("--person-id", type=int, default=1, help="people_t id of the person (default 1)")
    c.add_argument("-q", "--quiet", action="store_true")
    c.set_defaults(func=csv2log)
    l2c = sub.add_parser("log2csv", help="demonstration log -> episode CSV")
    l2c.add_argument("input", help="demonstration log (LCM event log)")
    l2c.add_argument("output", help="episode CSV to write")
    l2c.add_argument("-q", "--quiet", action="store_true")
    l2c.set_defaults(func=log2csv)
    args = ap.parse_args(argv)
    if getattr(args, "max_episodes", None) is not None and args.max_episodes < 1:
        ap.error("--max-episodes must be >= 1")
    if getattr(args, "person_id", 0) < 0:
        ap.error("--person-id must be >= 0")
    try:
        return args.func(args)
    except EpisodeError as e:
        print(f"convert_demonstrations: error: {e}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
