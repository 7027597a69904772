"""Demonstration episodes and the episode CSV format (paper Sect. 2 and 5.1: models are learned from
demonstrations of each task and homotopy).

Episodes are read only by the learner's C++ reader (learner/src/demo_io.cpp), for demonstration
logs and episode CSVs alike: read_episodes runs `gmmrrt-learn dump --json`, so the reading rules
(pairing, skipped events, CSV checks, headings estimated from the motion) exist once. Python writes
episodes: write_episode_csv here, write_demo_log in demonstration_log.py.

The CSV format is the one of ../shared/data/real/README.md:
    episode_id,task,homotopy,t,robot_x,robot_y,person_x,person_y,person_yaw
(metres, radians, seconds from the episode's start). Layout and rules: docs/demonstrations.md.
"""
from __future__ import annotations

import contextlib
import json
import os
import subprocess
import tempfile
from dataclasses import dataclass, field
from typing import Dict, Iterable, List, Optional, Tuple

import gmmrrt_constants  # generated beside the message package (tools/constants/)
import numpy as np

CSV_COLUMNS = ("episode_id", "task", "homotopy", "t", "robot_x", "robot_y", "person_x", "person_y",
               "person_yaw")

# Wire values: nav_goal_t.TASK_* / demo_info_t.HOMOTOPY_* (= gmmrrt_task_t / gmmrrt_homotopy_t), with
# the learner's words for them (labels.hpp), generated at build time so the two cannot drift apart.
TASKS = dict(gmmrrt_constants.TASKS)
HOMOTOPIES = dict(gmmrrt_constants.HOMOTOPIES)
TASK_NAMES = {v: k for k, v in TASKS.items()}
HOMOTOPY_NAMES = {v: k for k, v in HOMOTOPIES.items()}

SAMPLE_FIELDS = ("t", "robot_x", "robot_y", "robot_yaw", "person_x", "person_y", "person_yaw")


class EpisodeError(ValueError):
    """A file could not be read or written; the message names the file and the line or event."""


@dataclass
class Episode:
    """One demonstration. Arrays have one entry per sample; t in seconds from the episode's start,
    positions in metres (world frame of the recording), angles in radians.

    task: 'avoid' | 'approach'; homotopy: 'left' | 'right' | 'frontal'; person_id: the id of the
    person the task is about in the log's PEOPLE messages; split: 'train' | 'test' | '' (from an
    index); meta: the episode's row of an index file (all columns as strings), when read with one;
    source: the file it was read from."""

    id: str
    task: str
    homotopy: str
    t: np.ndarray
    robot_x: np.ndarray
    robot_y: np.ndarray
    robot_yaw: np.ndarray
    person_x: np.ndarray
    person_y: np.ndarray
    person_yaw: np.ndarray
    person_id: int = 1
    extra: Dict[str, object] = field(default_factory=dict)
    split: str = ""
    meta: Optional[Dict[str, str]] = None
    source: str = ""

    def __len__(self) -> int:
        return int(self.t.shape[0])

    @property
    def episode_id(self) -> str:
        return self.id

    @property
    def person(self) -> Tuple[float, float, float]:
        """The person's pose (x, y, yaw) at the first sample: the person of a demonstration stands."""
        return (float(self.person_x[0]), float(self.person_y[0]), float(self.person_yaw[0]))

    @property
    def xy(self) -> np.ndarray:
        """(N, 2) robot positions [m]."""
        return np.column_stack((self.robot_x, self.robot_y)).astype(float)

    @staticmethod
    def from_path(episode_id: str, task: str, homotopy: str, person: Iterable[float], xy,
                  split: str = "", meta: Optional[Dict[str, str]] = None) -> "Episode":
        """An episode of a mover path xy (N x 2) around a standing person (x, y, yaw); t = 0, 1, ...
        and the robot heading unknown (NaN)."""
        p = np.asarray(xy, dtype=float).reshape(-1, 2)
        n = len(p)
        px, py, pyaw = (float(v) for v in person)
        return Episode(episode_id, task, homotopy, np.arange(n, dtype=float), p[:, 0].copy(), p[:, 1].copy(),
                       np.full(n, np.nan), np.full(n, px), np.full(n, py), np.full(n, pyaw), split=split, meta=meta)

    @staticmethod
    def from_rows(episode_id: str, task: str, homotopy: str, rows: Iterable[Iterable[float]],
                  person_id: int = 1) -> "Episode":
        """rows: (t, robot_x, robot_y, robot_yaw, person_x, person_y, person_yaw) per sample."""
        a = np.asarray(list(rows), dtype=float).reshape(-1, 7)
        return Episode(episode_id, task, homotopy, *(a[:, i].copy() for i in range(7)), person_id=person_id)


def read_episodes(paths, index: Optional[str] = None, bin_dir: Optional[str] = None
                  ) -> Tuple[List[Episode], List[str]]:
    """(episodes, warnings) of one or more demonstration logs / episode CSVs (a path or a list),
    read by the learner's reader (learner/src/demo_io.cpp through `gmmrrt-learn dump --json`), the
    only reader of both formats. With `index` (an index CSV with episode_id and split columns) each
    episode gets its split. Raises EpisodeError with the reader's message (it names the file and
    the line or event), MissingTool when gmmrrt-learn is not built."""
    from gmmrrt_tools.runner import find_tool

    paths = [os.fspath(paths)] if isinstance(paths, (str, os.PathLike)) else [os.fspath(p) for p in paths]
    argv = [find_tool("gmmrrt-learn", bin_dir), "dump", "--json"] + (["--index", os.fspath(index)] if index else [])
    r = subprocess.run(argv + ["--"] + paths, capture_output=True, text=True)
    if r.returncode != 0:
        msg = r.stderr.strip().splitlines()
        raise EpisodeError(msg[-1].split("error: ", 1)[-1] if msg else f"gmmrrt-learn dump exited {r.returncode}")
    out = json.loads(r.stdout)
    episodes = []
    for e in out["episodes"]:
        cols = [np.asarray(e[k], dtype=float) for k in SAMPLE_FIELDS]  # null (no heading) -> NaN
        episodes.append(Episode(e["id"], TASK_NAMES.get(e["task"], str(e["task"])),
                                HOMOTOPY_NAMES.get(e["homotopy"], str(e["homotopy"])), *cols,
                                split=e["split"], source=e["source"]))
    return episodes, list(out["warnings"])


@contextlib.contextmanager
def atomic_output(path: str, suffix: str):
    """Yields a temporary file name in path's folder; when the block ends without an exception the
    file is renamed over path, otherwise removed: the file appears whole or not at all. An OSError
    becomes EpisodeError naming path."""
    directory = os.path.dirname(os.path.abspath(path))
    try:
        fd, tmp = tempfile.mkstemp(prefix=".tmp-", suffix=suffix, dir=directory)
    except OSError as e:
        raise EpisodeError(f"{path}: cannot write: {e.strerror}") from None
    os.close(fd)
    try:
        yield tmp
        os.replace(tmp, path)
    except BaseException as exc:
        if os.path.exists(tmp):
            os.unlink(tmp)
        if isinstance(exc, OSError):
            raise EpisodeError(f"{path}: cannot write: {exc.strerror or exc}") from None
        raise


def check_labels(path: str, episodes: List[Episode]) -> None:
    """The writers' check: every episode has a known task and homotopy and at least one sample."""
    for ep in episodes:
        if ep.task not in TASKS or ep.homotopy not in HOMOTOPIES:
            raise EpisodeError(f"{path}: episode '{ep.id}': unknown task/homotopy {ep.task}/{ep.homotopy}")
        if len(ep) == 0:
            raise EpisodeError(f"{path}: episode '{ep.id}' has no samples")


def _fmt(v: float) -> str:
    return repr(float(v))


def write_episode_csv(path: str, episodes: List[Episode]) -> None:
    """Writes episodes as an episode CSV (robot_yaw is not part of the format and is dropped).
    Numbers are written with repr(), so they read back exactly. The file appears whole or not at
    all (written to a temporary file, then renamed). Raises EpisodeError."""
    check_labels(path, episodes)
    for ep in episodes:
        if "," in ep.id or not ep.id:
            raise EpisodeError(f"{path}: episode id '{ep.id}' is empty or contains a comma")
    with atomic_output(path, ".csv") as tmp, open(tmp, "w", newline="") as f:
        f.write(",".join(CSV_COLUMNS) + "\n")
        for ep in episodes:
            for i in range(len(ep)):
                f.write(",".join([ep.id, ep.task, ep.homotopy, _fmt(ep.t[i]), _fmt(ep.robot_x[i]),
                                  _fmt(ep.robot_y[i]), _fmt(ep.person_x[i]), _fmt(ep.person_y[i]),
                                  _fmt(ep.person_yaw[i])]) + "\n")
