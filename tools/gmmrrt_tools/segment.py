"""Cut continuous recordings (LCM logs of ROBOT_POSE and PEOPLE, no DEMO_INFO) into labelled
demonstration episodes: the robot passing or approaching a person who stands still (paper Sect. 2
tasks, Sect. 5.1 demonstrations), so that a team can learn from its own teleoperation logs without
labelling them by hand. The output is an episode CSV that `gmmrrt-learn fit` reads.

Rules (defaults in SegmentOptions; docs/learner.md, "Raw recordings in"):
  1. A person stands still while their speed, measured over `speed_window_s`, stays below
     `still_speed_mps`, for at least `min_still_s`; the standing position is the median of the
     track over that span and the facing (person_yaw) its circular mean.
  2. An encounter is a maximal stretch of ROBOT_POSE samples within `radius_m` of a standing
     person while they stand; the robot must travel at least `min_path_m` in it.
  3. Task: approach when the robot ends the encounter within `approach_stop_m` of the person,
     stopped (speed over its last `speed_window_s` below `still_speed_mps`), without having gone
     round them (|swept angle| < `approach_max_swept_rad`); otherwise avoid, and an
     avoid encounter must go round the person: |swept angle| >= `min_swept_rad` (metrics.swept_angle),
     else it is reported as "not a pass" and left out.
  4. Homotopy, from the geometry as the metrics module and the real-data README define it: avoid,
     the side passed (metrics.passing_side: the sign of theta, in the person's frame, at the
     closest point); approach, frontal when the robot starts in the person's front half-plane
     (|theta| < pi/2, core.features_from_xy), else the side it ends on (passing_side at the end).
Bad input is named: a log without PEOPLE (or ROBOT_POSE) raises SegmentError naming the file; a
person who never stands still, and encounters that are not passes, are notes naming the file and
the person (and time) in the result.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, List, Optional, Tuple

import numpy as np

from gmmrrt_tools import core
from gmmrrt_tools.demolog import CH_PEOPLE, CH_POSE, DemoLogError, _decode_people, _decode_pose, _Reject, scan_structure
from gmmrrt_tools.episodes import Episode, EpisodeError
from gmmrrt_tools.metrics import passing_side, swept_angle


class SegmentError(EpisodeError):
    """A recording cannot be segmented; the message names the file."""


@dataclass
class SegmentOptions:
    still_speed_mps: float = 0.3   # a tracked standing person jitters by a few cm per sample
    speed_window_s: float = 1.0
    min_still_s: float = 2.0
    radius_m: float = 3.0          # UPO's avoid episodes start and end about 2.1-2.5 m from the person
    min_path_m: float = 0.5
    approach_stop_m: float = 1.5
    approach_max_swept_rad: float = math.pi / 2  # an approach ends near the person without going round them
    min_swept_rad: float = math.pi / 4  # UPO passes start and end about 2 m out: 0.8-1.6 rad


@dataclass
class SegmentResult:
    episodes: List[Episode] = field(default_factory=list)
    notes: List[str] = field(default_factory=list)


def _read_streams(path: str) -> Tuple[np.ndarray, Dict[int, np.ndarray], List[str]]:
    """ROBOT_POSE as (t, x, y) rows and each person's (t, x, y, yaw) rows, t in s from the first
    event; undecodable events are notes; a cut last event is read up to the last whole one."""
    try:
        data = Path(path).read_bytes()
    except OSError as e:
        raise SegmentError(f"{path}: cannot open: {e.strerror}") from None
    notes: List[str] = []
    cut: List[str] = []
    try:
        events = scan_structure(path, data, cut)
    except DemoLogError as e:
        raise SegmentError(str(e)) from None
    notes += [f"{c}; read up to the last complete event" for c in cut]
    poses, people = [], {}
    t0 = None
    for i, (off, ch, payload) in enumerate(events):
        try:
            if ch == CH_POSE:
                m = _decode_pose(payload)
                t0 = m.utime if t0 is None else t0
                poses.append(((m.utime - t0) * 1e-6, m.x, m.y))
            elif ch == CH_PEOPLE:
                m = _decode_people(payload)
                t0 = m.utime if t0 is None else t0
                for p in m.people[:m.num_people]:
                    people.setdefault(p.id, []).append(((m.utime - t0) * 1e-6, p.x, p.y, p.yaw))
        except _Reject as r:
            notes.append(f"{path}: event {i + 1} (byte {off}, channel {ch}): {r}; skipped")
    if not poses:
        raise SegmentError(f"{path}: no ROBOT_POSE event: nothing to segment")
    if not people:
        raise SegmentError(f"{path}: no PEOPLE event with a person: no one to pass or approach")
    return np.asarray(poses), {k: np.asarray(v) for k, v in people.items()}, notes


def _speeds(track: np.ndarray, window_s: float) -> np.ndarray:
    """Speed [m/s] at each sample over the preceding window (the first samples: the following one)."""
    t = track[:, 0]
    j = np.searchsorted(t, t - window_s)
    j = np.minimum(j, np.arange(len(t)))
    back = np.where(t - t[j] >= 0.5 * window_s, j, np.searchsorted(t, t + window_s).clip(max=len(t) - 1))
    dt = np.abs(t - t[back])
    dist = np.hypot(track[:, 1] - track[back, 1], track[:, 2] - track[back, 2])
    return np.where(dt > 0, dist / np.maximum(dt, 1e-9), 0.0)


def _runs(mask: np.ndarray) -> List[Tuple[int, int]]:
    """[start, end) index ranges where mask is True."""
    out, start = [], None
    for i, v in enumerate(mask):
        if v and start is None:
            start = i
        elif not v and start is not None:
            out.append((start, i))
            start = None
    if start is not None:
        out.append((start, len(mask)))
    return out


def segment_log(path: str, options: Optional[SegmentOptions] = None) -> SegmentResult:
    """Episodes of one recording, in time order, ids '<file stem>_seg<NNNN>'."""
    o = options or SegmentOptions()
    robot, people, notes = _read_streams(path)
    res = SegmentResult(notes=notes)
    stem = Path(path).name.split(".")[0]
    robot_speed = _speeds(robot, o.speed_window_s)
    found = []
    for pid, track in sorted(people.items()):
        still = _speeds(track, o.speed_window_s) < o.still_speed_mps
        spans = [(a, b) for a, b in _runs(still) if track[b - 1, 0] - track[a, 0] >= o.min_still_s]
        if not spans:
            res.notes.append(f"{path}: person {pid} never stands still for {o.min_still_s:g} s "
                             f"(speed < {o.still_speed_mps:g} m/s): no episode around them")
            continue
        for a, b in spans:
            px, py = float(np.median(track[a:b, 1])), float(np.median(track[a:b, 2]))
            pyaw = math.atan2(float(np.mean(np.sin(track[a:b, 3]))), float(np.mean(np.cos(track[a:b, 3]))))
            t_lo, t_hi = track[a, 0], track[b - 1, 0]
            inside = (robot[:, 0] >= t_lo) & (robot[:, 0] <= t_hi) & \
                (np.hypot(robot[:, 1] - px, robot[:, 2] - py) < o.radius_m)
            for r0, r1 in _runs(inside):
                seg = robot[r0:r1]
                if len(seg) < 3 or np.sum(np.hypot(np.diff(seg[:, 1]), np.diff(seg[:, 2]))) < o.min_path_m:
                    continue
                person = (px, py, pyaw)
                path_xy = seg[:, 1:3]
                end_d = math.hypot(seg[-1, 1] - px, seg[-1, 2] - py)
                sw = swept_angle(path_xy, person)
                if end_d < o.approach_stop_m and robot_speed[r1 - 1] < o.still_speed_mps and \
                        abs(sw) < o.approach_max_swept_rad:
                    task = "approach"
                    _, th0 = core.features_from_xy(person, seg[0, 1], seg[0, 2])
                    hom = "frontal" if abs(th0) < math.pi / 2 else passing_side(path_xy[-1:], person)
                else:
                    if abs(sw) < o.min_swept_rad:
                        res.notes.append(f"{path}: person {pid}, t = {seg[0, 0]:.1f}..{seg[-1, 0]:.1f} s: "
                                         f"not a pass (swept angle {sw:.2f} rad): left out")
                        continue
                    task, hom = "avoid", passing_side(path_xy, person)
                rows = [(t - seg[0, 0], x, y, math.nan, px, py, pyaw) for t, x, y in seg]
                found.append((seg[0, 0], pid, task, hom, rows))
    for n, (_t, pid, task, hom, rows) in enumerate(sorted(found, key=lambda f: (f[0], f[1]))):
        res.episodes.append(Episode.from_rows(f"{stem}_seg{n:04d}", task, hom, rows, person_id=pid))
    return res
