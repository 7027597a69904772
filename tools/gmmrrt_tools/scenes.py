"""Episodes (one mover passing or approaching one standing person) and the planning scenes made from them.

Episodes (gmmrrt_tools.episodes.Episode, the one episode type) come from the learner's reader,
for the episode CSVs of ../shared/data/real/README.md and the demonstration logs of logs/demos/
alike; index files add each episode's split and metadata columns.

Canonical frame: the person's frame of the paper's features (person at the origin facing +x, +y on
the person's left), computed with the C core (gmmrrt_tools.core.world_to_person). Demonstrations
recorded with different person poses are compared and planned in this frame, so one scene per
(task, homotopy) stands for all its demonstrations, as in the paper's Fig. 2.
"""
from __future__ import annotations

import csv
import sys
from dataclasses import replace
from pathlib import Path
from typing import Dict, Iterable, List, Optional, Sequence, Tuple

import numpy as np

from gmmrrt_tools import episodes
from gmmrrt_tools.episodes import Episode
from gmmrrt_tools.runner import Scene


def read_index(path: str) -> Dict[str, Dict[str, str]]:
    """episode_id -> the index row (all columns as strings): the metadata columns of an index file
    (e.g. upo_task). The split column is read with the episodes, by the learner's reader."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows or "episode_id" not in rows[0]:
        raise ValueError(f"{path}: not an episode index (no episode_id column)")
    return {r["episode_id"]: r for r in rows}


def read_episodes(path: str, index: Optional[str] = None, split: Optional[str] = None,
                  task: Optional[str] = None, warnings: Optional[List[str]] = None) -> List[Episode]:
    """Episodes of an episode CSV (or demonstration log), in file order, read by the learner's reader
    (gmmrrt_tools.episodes.read_episodes; an event listed twice is read once, with a warning); with
    `index`, each gets its split and index row and `split` filters. The reader's warnings are appended
    to `warnings` when given, else printed on stderr: never dropped. Raises EpisodeError (a ValueError)
    naming the file and line on a malformed row."""
    eps, said = episodes.read_episodes(path, index=index)
    if warnings is not None:
        warnings.extend(said)
    else:
        for w in said:
            print(f"warning: {w}", file=sys.stderr)
    idx = read_index(index) if index else {}
    out = []
    for e in eps:
        if split and e.split != split:
            continue
        if task and e.task != task:
            continue
        e.meta = idx.get(e.id)
        out.append(e)
    return out


def to_person_frame(ep: Episode) -> Episode:
    """The episode in its person's frame (person at (0, 0) facing +x): see module doc."""
    from gmmrrt_tools import core

    person = ep.person
    pts = np.array([core.world_to_person(person, x, y) for x, y in ep.xy])
    zero = np.zeros(len(ep))
    return replace(ep, robot_x=pts[:, 0], robot_y=pts[:, 1],
                   robot_yaw=np.array([core.wrap_angle(a - person[2]) for a in ep.robot_yaw]),
                   person_x=zero, person_y=zero.copy(), person_yaw=zero.copy())


def bounds_of(points: Iterable[Sequence[float]], margin_m: float) -> Tuple[float, float, float, float]:
    arr = np.asarray(list(points), dtype=float)[:, :2]
    lo, hi = arr.min(axis=0) - margin_m, arr.max(axis=0) + margin_m
    return (float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))


def canonical_scene(demos: Sequence[Episode], margin_m: float = 1.0,
                    bounds_from: Optional[Sequence[Episode]] = None) -> Scene:
    """One planning problem for a set of demonstrations already in the person frame: start and goal
    are the means of their first and last points, the person at the origin facing +x, bounds the box
    around `bounds_from` (default: the demos) and the person, widened by margin_m."""
    if not demos:
        raise ValueError("no demonstrations for this scene")
    start = np.mean([d.xy[0] for d in demos], axis=0)
    goal = np.mean([d.xy[-1] for d in demos], axis=0)
    pts = np.vstack([d.xy for d in (bounds_from or demos)] + [np.zeros((1, 2))])
    return Scene(start=(float(start[0]), float(start[1])), goal=(float(goal[0]), float(goal[1])),
                 people=[(0.0, 0.0, 0.0)], bounds=bounds_of(pts, margin_m))


def _push_out(p: np.ndarray, centre: np.ndarray, min_dist_m: float) -> np.ndarray:
    v = p - centre
    n = float(np.linalg.norm(v))
    if n >= min_dist_m:
        return p
    if n == 0.0:
        v, n = np.array([1.0, 0.0]), 1.0
    return centre + v / n * min_dist_m


def episode_scene(ep: Episode, margin_m: float = 1.5, clearance_m: float = 0.0) -> Scene:
    """Plan what the mover of `ep` did: from its first to its last point around its person (world frame).
    A start or goal closer than clearance_m to the person (people stop closer than a robot disc plus a
    person disc allow) is pushed out radially to clearance_m, so the problem is valid."""
    c = np.asarray(ep.person[:2], dtype=float)
    start, goal = _push_out(ep.xy[0], c, clearance_m), _push_out(ep.xy[-1], c, clearance_m)
    pts = np.vstack([ep.xy, c[None], start[None], goal[None]])
    return Scene(start=tuple(map(float, start)), goal=tuple(map(float, goal)),
                 people=[tuple(map(float, ep.person))], bounds=bounds_of(pts, margin_m))


def load_demo_logs(demos_dir: str) -> List[Episode]:
    """The demonstrations of logs/demos/ as Episodes (read by the learner's reader). Raises
    RuntimeError naming what is missing when the logs are not there."""
    d = Path(demos_dir)
    logs = sorted(d.glob("*.lcmlog"))
    if not logs:
        raise RuntimeError(f"no demonstration logs (*.lcmlog) in {d} "
                           f"(logs/README.md says how they are recorded or synthesized)")
    out, warnings = episodes.read_episodes([str(p) for p in logs])
    for w in warnings:
        print(f"warning: {w}")
    return out


__all__ = ["Episode", "read_index", "read_episodes", "to_person_frame", "bounds_of", "canonical_scene",
           "episode_scene", "load_demo_logs"]
