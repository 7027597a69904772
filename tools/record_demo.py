#!/usr/bin/env python3
"""record_demo.py - label demonstrations live: an operator's key presses become DEMO_INFO
messages on LCM (the labels of docs/demonstrations.md), so that an lcm-logger recording of
ROBOT_POSE and PEOPLE becomes a demonstration log that `gmmrrt-learn fit` reads as it is.

  record_demo.py [--lcm-url URL] [--task avoid|approach] [--person-id N] [--first-episode N]

Keys (one key press on a terminal; one key per line when stdin is a pipe or file):
  l, r, f   start an episode now: DEMO_INFO with the current task, homotopy left / right /
            frontal (frontal: approach only), the next episode number, utime = now, and the
            person: --person-id, or else the person nearest the robot in the last PEOPLE and
            ROBOT_POSE messages seen on the bus
  a, p      current task: avoid / approach (the start is --task, default avoid)
  q         quit (end of input too)
Run lcm-logger beside it; every DEMO_INFO is printed on stdout as it is published. A key that
cannot start an episode (no person known yet, frontal while avoiding, an unknown key) publishes
nothing and says why on stderr. Exit status 0; 2 on bad usage.
"""
from __future__ import annotations

import argparse
import math
import os
import select
import sys
import time
from typing import Iterator, List, Optional, Tuple

import lcm

from gmmrrt_tools.demolog import demo_info_t, people_t, pose2d_t  # the generated messages
from gmmrrt_tools.episodes import HOMOTOPIES, TASKS

CH_INFO, CH_POSE, CH_PEOPLE = "DEMO_INFO", "ROBOT_POSE", "PEOPLE"
HOMOTOPY_KEYS = {"l": "left", "r": "right", "f": "frontal"}
TASK_KEYS = {"a": "avoid", "p": "approach"}


def nearest_person(robot_xy: Tuple[float, float], people: List[Tuple[int, float, float]]) -> Optional[int]:
    """Id of the person nearest the robot (ties: the first listed), None when nobody is seen."""
    best, best_d = None, math.inf
    for pid, x, y in people:
        d = math.hypot(x - robot_xy[0], y - robot_xy[1])
        if d < best_d:
            best, best_d = pid, d
    return best


class Recorder:
    """Holds what the bus said last and publishes DEMO_INFO for the operator's keys."""

    def __init__(self, lc: lcm.LCM, task: str, person_id: Optional[int], first_episode: int):
        self.lc, self.task, self.person_id, self.episode = lc, task, person_id, first_episode
        self.robot: Optional[Tuple[float, float]] = None
        self.people: List[Tuple[int, float, float]] = []

    def on_pose(self, _channel: str, data: bytes) -> None:
        try:
            m = pose2d_t.decode(data)
        except Exception:  # a foreign message on the channel: not ours to judge here
            return
        if math.isfinite(m.x) and math.isfinite(m.y):
            self.robot = (m.x, m.y)

    def on_people(self, _channel: str, data: bytes) -> None:
        try:
            m = people_t.decode(data)
        except Exception:
            return
        n = max(0, min(m.num_people, people_t.MAX_PEOPLE))
        self.people = [(p.id, p.x, p.y) for p in m.people[:n] if math.isfinite(p.x) and math.isfinite(p.y)]

    def key(self, k: str) -> Optional[str]:
        """Acts on one key; returns an error text when nothing could be done."""
        if k in TASK_KEYS:
            self.task = TASK_KEYS[k]
            print(f"task {self.task}", flush=True)
            return None
        if k not in HOMOTOPY_KEYS:
            return f"unknown key {k!r} (l, r, f start an episode; a, p set the task; q quits)"
        homotopy = HOMOTOPY_KEYS[k]
        if homotopy == "frontal" and self.task != "approach":
            return "frontal is an approach homotopy: press p first"
        pid = self.person_id
        if pid is None:
            if self.robot is None or not self.people:
                return "no person known yet (no ROBOT_POSE and PEOPLE seen): give --person-id or wait"
            pid = nearest_person(self.robot, self.people)
        msg = demo_info_t()
        msg.utime = int(time.time() * 1e6)
        msg.episode = self.episode
        msg.task = TASKS[self.task]
        msg.homotopy = HOMOTOPIES[homotopy]
        msg.person_id = pid
        self.lc.publish(CH_INFO, msg.encode())
        print(f"episode {self.episode}: {self.task} {homotopy}, person {pid}, utime {msg.utime}", flush=True)
        self.episode += 1
        return None


def keys_from(stream, lc: Optional[lcm.LCM]) -> Iterator[str]:
    """Keys from stream: single presses on a terminal (raw mode), else one per line. While
    waiting, LCM messages are handled (when lc can receive)."""
    fd = stream.fileno()
    tty_state = None
    if os.isatty(fd):
        import termios
        import tty
        tty_state = termios.tcgetattr(fd)
        tty.setcbreak(fd)
    try:
        while True:
            fds = [fd] + ([lc.fileno()] if lc is not None else [])
            ready, _, _ = select.select(fds, [], [], 0.5)
            if lc is not None and lc.fileno() in ready:
                lc.handle()
            if fd not in ready:
                continue
            if tty_state is not None:
                ch = os.read(fd, 1).decode(errors="replace")
                if not ch:
                    return
                if not ch.isspace():
                    yield ch
            else:
                line = stream.readline()
                if not line:
                    return
                if line.strip():
                    yield line.strip()
    finally:
        if tty_state is not None:
            import termios
            termios.tcsetattr(fd, termios.TCSADRAIN, tty_state)


def main(argv: Optional[List[str]] = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    ap.add_argument("--lcm-url", default=None, help="LCM provider (default: LCM's, i.e. $LCM_DEFAULT_URL or udpm)")
    ap.add_argument("--task", choices=sorted(TASKS), default="avoid", help="task at the start (default avoid)")
    ap.add_argument("--person-id", type=int, default=None,
                    help="person_t.id of the person every episode is about (default: the nearest person)")
    ap.add_argument("--first-episode", type=int, default=0, help="number of the first episode (default 0)")
    args = ap.parse_args(argv)
    if args.first_episode < 0:
        ap.error("--first-episode must be >= 0")
    lc = lcm.LCM(args.lcm_url) if args.lcm_url else lcm.LCM()
    rec = Recorder(lc, args.task, args.person_id, args.first_episode)
    # A write-only provider (file://...?mode=w) cannot receive: then only --person-id works.
    listening = args.person_id is None
    if listening:
        lc.subscribe(CH_POSE, rec.on_pose)
        lc.subscribe(CH_PEOPLE, rec.on_people)
    for k in keys_from(sys.stdin, lc if listening else None):
        if k == "q":
            break
        err = rec.key(k)
        if err:
            print(f"record_demo: {err}", file=sys.stderr, flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
