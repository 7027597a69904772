"""Demonstration episodes and the episode CSV format (paper Sect. 2 and 5.1: models are learned from
demonstrations of each task and homotopy).

The CSV format is the one of ../shared/data/real/README.md:
    episode_id,task,homotopy,t,robot_x,robot_y,person_x,person_y,person_yaw
(metres, radians, seconds from the episode's start). The same rules as the learner's C++ reader
(learner/src/demo_io.cpp) apply, with the same error texts: rows of an episode are contiguous,
keep one task and homotopy, and have strictly increasing t; every number is finite. The CSV has
no robot heading: readers estimate it from the motion (estimate_headings), NaN where the robot
never moved. Layout and rules: docs/demonstrations.md.
"""
from __future__ import annotations

import math
import os
import tempfile
from dataclasses import dataclass, field
from typing import Dict, Iterable, List, Optional

import numpy as np

CSV_COLUMNS = ("episode_id", "task", "homotopy", "t", "robot_x", "robot_y", "person_x", "person_y",
               "person_yaw")

# Wire values: nav_goal_t.TASK_* / demo_info_t.HOMOTOPY_* (= gmmrrt_task_t / gmmrrt_homotopy_t).
TASKS = {"avoid": 1, "approach": 2}
HOMOTOPIES = {"left": 1, "right": 2, "frontal": 3}
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
    person the task is about in the log's PEOPLE messages."""

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

    def __len__(self) -> int:
        return int(self.t.shape[0])

    @staticmethod
    def from_rows(episode_id: str, task: str, homotopy: str, rows: Iterable[Iterable[float]],
                  person_id: int = 1) -> "Episode":
        """rows: (t, robot_x, robot_y, robot_yaw, person_x, person_y, person_yaw) per sample."""
        a = np.asarray(list(rows), dtype=float).reshape(-1, 7)
        return Episode(episode_id, task, homotopy, *(a[:, i].copy() for i in range(7)), person_id=person_id)


def estimate_headings(x: np.ndarray, y: np.ndarray, min_step_m: float = 0.01) -> np.ndarray:
    """Heading [rad] of each sample from the direction of motion: from the nearest earlier sample at
    least min_step_m away to the nearest later one (one-sided at the ends). NaN when the robot never
    moved that far. Same rule as gmmrrt::learn::EstimateHeadingsFromMotion."""
    n = len(x)
    out = np.full(n, np.nan)
    for i in range(n):
        back = fwd = i
        for j in range(i - 1, -1, -1):
            if math.hypot(x[i] - x[j], y[i] - y[j]) >= min_step_m:
                back = j
                break
        for k in range(i + 1, n):
            if math.hypot(x[k] - x[i], y[k] - y[i]) >= min_step_m:
                fwd = k
                break
        if back != i or fwd != i:
            out[i] = math.atan2(y[fwd] - y[back], x[fwd] - x[back])
    return out


def _finite(text: str) -> Optional[float]:
    if not text or text[0].isspace() or text[-1].isspace():
        return None
    try:
        v = float(text)
    except ValueError:
        return None
    return v if math.isfinite(v) else None


def read_episode_csv(path: str) -> List[Episode]:
    """Reads an episode CSV; raises EpisodeError naming the file and line on any problem."""
    try:
        with open(path, "r", newline="") as f:
            lines = f.read().split("\n")
    except OSError as e:
        raise EpisodeError(f"{path}: cannot open: {e.strerror}") from None
    except UnicodeDecodeError:
        raise EpisodeError(f"{path}: not a text file (is it an LCM log?)") from None
    if not lines or lines == [""]:
        raise EpisodeError(f"{path}: line 1: empty file (expected the header)")
    if tuple(lines[0].rstrip("\r").split(",")) != CSV_COLUMNS:
        raise EpisodeError(f"{path}: line 1: header must be {','.join(CSV_COLUMNS)}")
    episodes: List[Episode] = []
    order: List[str] = []
    rows: Dict[str, list] = {}
    labels: Dict[str, tuple] = {}
    for line_no, line in enumerate(lines[1:], start=2):
        line = line.rstrip("\r")
        if not line:
            continue
        where = f"{path}: line {line_no}"
        f = line.split(",")
        if len(f) != len(CSV_COLUMNS):
            raise EpisodeError(f"{where}: {len(f)} columns, expected {len(CSV_COLUMNS)}")
        eid, task, hom = f[0], f[1], f[2]
        if not eid:
            raise EpisodeError(f"{where}: empty episode_id")
        if task not in TASKS:
            raise EpisodeError(f"{where}: unknown task '{task}' (expected avoid or approach)")
        if hom not in HOMOTOPIES:
            raise EpisodeError(f"{where}: unknown homotopy '{hom}' (expected left, right or frontal)")
        vals = []
        for col, text in zip(CSV_COLUMNS[3:], f[3:]):
            v = _finite(text)
            if v is None:
                raise EpisodeError(f"{where}: column {col} = '{text}' is not a finite number")
            vals.append(v)
        if not order or order[-1] != eid:
            if eid in rows:
                raise EpisodeError(f"{where}: episode '{eid}' appears again after other episodes")
            order.append(eid)
            rows[eid] = []
            labels[eid] = (task, hom)
        if labels[eid] != (task, hom):
            raise EpisodeError(f"{where}: episode '{eid}' changes its task or homotopy")
        r = rows[eid]
        if r and not vals[0] > r[-1][0]:
            raise EpisodeError(f"{where}: time does not increase in episode '{eid}' (t = {f[3]})")
        t, rx, ry, px, py, pyaw = vals
        r.append((t, rx, ry, math.nan, px, py, pyaw))
    if not order:
        raise EpisodeError(f"{path}: no episodes (only a header)")
    for eid in order:
        ep = Episode.from_rows(eid, labels[eid][0], labels[eid][1], rows[eid])
        ep.robot_yaw = estimate_headings(ep.robot_x, ep.robot_y)
        episodes.append(ep)
    return episodes


def _fmt(v: float) -> str:
    return repr(float(v))


def write_episode_csv(path: str, episodes: List[Episode]) -> None:
    """Writes episodes as an episode CSV (robot_yaw is not part of the format and is dropped).
    Numbers are written with repr(), so they read back exactly. The file appears whole or not at
    all (written to a temporary file, then renamed). Raises EpisodeError."""
    for ep in episodes:
        if ep.task not in TASKS or ep.homotopy not in HOMOTOPIES:
            raise EpisodeError(f"{path}: episode '{ep.id}': unknown task/homotopy {ep.task}/{ep.homotopy}")
        if "," in ep.id or not ep.id:
            raise EpisodeError(f"{path}: episode id '{ep.id}' is empty or contains a comma")
    directory = os.path.dirname(os.path.abspath(path))
    try:
        fd, tmp = tempfile.mkstemp(prefix=".tmp-", suffix=".csv", dir=directory)
    except OSError as e:
        raise EpisodeError(f"{path}: cannot write: {e.strerror}") from None
    try:
        with os.fdopen(fd, "w", newline="") as f:
            f.write(",".join(CSV_COLUMNS) + "\n")
            for ep in episodes:
                for i in range(len(ep)):
                    f.write(",".join([ep.id, ep.task, ep.homotopy, _fmt(ep.t[i]), _fmt(ep.robot_x[i]),
                                      _fmt(ep.robot_y[i]), _fmt(ep.person_x[i]), _fmt(ep.person_y[i]),
                                      _fmt(ep.person_yaw[i])]) + "\n")
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise


def read_split_index(path: str) -> Dict[str, str]:
    """episode_id -> split from an index CSV with episode_id and split columns."""
    try:
        with open(path, "r", newline="") as f:
            lines = f.read().split("\n")
    except OSError as e:
        raise EpisodeError(f"{path}: cannot open: {e.strerror}") from None
    header = lines[0].rstrip("\r").split(",") if lines else []
    if "episode_id" not in header or "split" not in header:
        raise EpisodeError(f"{path}: line 1: header has no episode_id or no split column")
    i_id, i_split = header.index("episode_id"), header.index("split")
    out: Dict[str, str] = {}
    for line_no, line in enumerate(lines[1:], start=2):
        line = line.rstrip("\r")
        if not line:
            continue
        f = line.split(",")
        if len(f) != len(header):
            raise EpisodeError(f"{path}: line {line_no}: {len(f)} columns, the header has {len(header)}")
        if not f[i_id] or not f[i_split]:
            raise EpisodeError(f"{path}: line {line_no}: empty episode_id or split")
        if f[i_id] in out:
            raise EpisodeError(f"{path}: line {line_no}: episode '{f[i_id]}' is listed twice")
        out[f[i_id]] = f[i_split]
    return out
