"""Episodes (one mover passing or approaching one standing person) and the planning scenes made from them.

Reads the episode CSV format of ../shared/data/real/README.md
(`episode_id,task,homotopy,t,robot_x,robot_y,person_x,person_y,person_yaw`) and its index files
(`split` column). The synthetic demonstrations of logs/demos/ are read with the demos branch's
reader (gmmrrt_tools.demolog / episodes) and land in the same Episode type.

Canonical frame: the person's frame of the paper's features (person at the origin facing +x, +y on
the person's left), computed with the C core (gmmrrt_tools.core.world_to_person). Demonstrations
recorded with different person poses are compared and planned in this frame, so one scene per
(task, homotopy) stands for all its demonstrations, as in the paper's Fig. 2.
"""
from __future__ import annotations

import csv
import math
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Dict, Iterable, List, Optional, Sequence, Tuple

import numpy as np

from gmmrrt_tools.runner import Scene


@dataclass
class Episode:
    episode_id: str
    task: str                      # avoid | approach
    homotopy: str                  # left | right | frontal
    person: Tuple[float, float, float]   # x, y [m], yaw [rad] (constant within an episode)
    xy: np.ndarray                 # (N, 2) mover positions [m]
    split: str = ""                # train | test | "" (unknown)
    meta: Optional[Dict[str, str]] = None


EPISODE_COLUMNS = ["episode_id", "task", "homotopy", "t", "robot_x", "robot_y", "person_x", "person_y",
                   "person_yaw"]


def read_index(path: str) -> Dict[str, Dict[str, str]]:
    """episode_id -> the index row (all columns as strings)."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows or "episode_id" not in rows[0]:
        raise ValueError(f"{path}: not an episode index (no episode_id column)")
    return {r["episode_id"]: r for r in rows}


def read_episodes(path: str, index: Optional[str] = None, split: Optional[str] = None,
                  task: Optional[str] = None) -> List[Episode]:
    """Episodes of an episode CSV, in file order; with `index`, each gets its split and index row and
    `split` filters. Raises ValueError naming the file and line on a malformed row."""
    idx = read_index(index) if index else {}
    eps: Dict[str, dict] = {}
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        if reader.fieldnames is None or any(c not in reader.fieldnames for c in EPISODE_COLUMNS):
            raise ValueError(f"{path}: expected columns {','.join(EPISODE_COLUMNS)}")
        for line, row in enumerate(reader, start=2):
            try:
                x, y = float(row["robot_x"]), float(row["robot_y"])
                person = (float(row["person_x"]), float(row["person_y"]), float(row["person_yaw"]))
            except (TypeError, ValueError) as exc:
                raise ValueError(f"{path}:{line}: bad number ({exc})") from None
            if not all(math.isfinite(v) for v in (x, y, *person)):
                raise ValueError(f"{path}:{line}: NaN or Inf")
            e = eps.setdefault(row["episode_id"], {"task": row["task"], "homotopy": row["homotopy"],
                                                    "person": person, "xy": []})
            e["xy"].append((x, y))
    out = []
    for eid, e in eps.items():
        meta = idx.get(eid)
        sp = meta.get("split", "") if meta else ""
        if split and sp != split:
            continue
        if task and e["task"] != task:
            continue
        out.append(Episode(eid, e["task"], e["homotopy"], e["person"], np.asarray(e["xy"], dtype=float), sp,
                           meta))
    return out


def to_person_frame(ep: Episode) -> Episode:
    """The episode in its person's frame (person at (0, 0) facing +x): see module doc."""
    from gmmrrt_tools import core

    pts = np.array([core.world_to_person(ep.person, x, y) for x, y in ep.xy])
    return replace(ep, person=(0.0, 0.0, 0.0), xy=pts)


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
    """The synthetic demonstrations of logs/demos/ as Episodes, through the demos branch's reader.
    Raises RuntimeError naming what is missing when the reader or the logs are not there."""
    d = Path(demos_dir)
    logs = sorted(d.glob("*.lcmlog"))
    if not logs:
        raise RuntimeError(f"no demonstration logs (*.lcmlog) in {d} "
                           f"(logs/README.md says how they are recorded or synthesized)")
    try:
        from gmmrrt_tools import demolog  # type: ignore
    except ImportError as exc:
        raise RuntimeError(f"the demonstration log reader gmmrrt_tools.demolog is missing ({exc}): "
                           f"is this an incomplete checkout?") from None
    out: List[Episode] = []
    for log in logs:
        eps, warnings = demolog.read_demo_log(str(log))
        for w in warnings:
            print(f"warning: {w}")
        for demo in eps:
            # The standing person's pose is constant in a demonstration; its first sample stands for it.
            person = (float(demo.person_x[0]), float(demo.person_y[0]), float(demo.person_yaw[0]))
            xy = np.column_stack((demo.robot_x, demo.robot_y)).astype(float)
            out.append(Episode(demo.id, demo.task, demo.homotopy, person, xy, ""))
    return out


__all__ = ["Episode", "read_index", "read_episodes", "to_person_frame", "bounds_of", "canonical_scene",
           "episode_scene", "load_demo_logs"]
