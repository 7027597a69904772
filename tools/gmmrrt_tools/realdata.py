"""Selections of the real demonstrations in ../shared/data/real (README.md there): the UPO avoid
episodes by split and by encounter (the paper's avoid task, Sect. 2, has the person facing the
oncoming robot: UPO flags those episodes frontal_encounter in upo_avoid_index.csv); every standing
person of an episode's scene (UPO: the recording's people from the index's scene column; UCY: the
scene's other standing pedestrians from ucy_tracks.csv); the side a path passes its person on; and
how often two humans in nearly the same situation pass on the same side.
"""
from __future__ import annotations

import csv
import math
import os
from typing import Dict, List, Tuple

from .episodes import Episode, EpisodeError, read_episodes
from .scenes import read_index


def select_upo(real_data: str, split: str, encounter: str) -> List[Episode]:
    """UPO avoid episodes of a split (all|train|test) and encounter (frontal|all)."""
    index = os.path.join(real_data, "upo_avoid_index.csv")
    upo, _ = read_episodes(os.path.join(real_data, "upo_avoid_episodes.csv"), index=index)
    keep = {e.id for e in upo}
    if split != "all":
        keep &= {e.id for e in upo if e.split == split}
    if encounter == "frontal":
        keep &= frontal_encounters(index)
    return [e for e in upo if e.id in keep]


def frontal_encounters(index_path: str) -> set:
    """Episode ids whose frontal_encounter column is True."""
    try:
        rows = read_index(index_path)
    except OSError as e:
        raise EpisodeError(f"{index_path}: cannot open: {e.strerror}") from None
    except ValueError as e:
        raise EpisodeError(str(e)) from None
    if not rows or "frontal_encounter" not in next(iter(rows.values())):
        raise EpisodeError(f"{index_path}: line 1: no frontal_encounter column")
    return {k for k, r in rows.items() if r["frontal_encounter"] == "True"}


# ---------------------------------------------------------------- every person in the scene

def side_of_sweep(xy, person) -> str:
    """'left' when the bearing from the person to the mover turns counterclockwise from the first
    to the last point (the person stays on the mover's left), else 'right': the planner's
    preferred side (planner.h, gmmrrt_side_t), counted as metrics.swept_angle counts it."""
    from . import metrics

    return "left" if metrics.swept_angle(xy, person) > 0.0 else "right"


def _require_person(path: str, episodes) -> None:
    """Every episode needs a finite standing person: names the file and the episode otherwise."""
    for e in episodes:
        if e.person is None or len(e.person) < 3 or not all(math.isfinite(v) for v in e.person):
            raise EpisodeError(f"{path}: episode {e.episode_id}: no standing person (person_x/y/yaw missing)")


def require_split(index_path: str, split: str, episodes) -> None:
    """Raises EpisodeError naming the index file when no episode of `episodes` is in `split`. The
    splits are the ones the learner's reader gave the episodes from that index (read_episodes with
    index=index_path), so the index's split column is read in one place."""
    if not any(e.split == split for e in episodes):
        found = sorted({e.split for e in episodes if e.split})
        raise EpisodeError(f"{index_path}: no episode in split '{split}' (splits found: {', '.join(found) or 'none'})")


def upo_people(index_path: str, episodes) -> Dict[str, List[Tuple[float, float, float]]]:
    """episode id -> every standing person of its recording: its own person first, then the persons
    of the other episodes of the same recording (the index's `scene` column; episodes of one
    recording share the robot's path and each is about one of the people), one per person_track."""
    rows = read_index(index_path)
    if not rows or "scene" not in next(iter(rows.values())):
        raise EpisodeError(f"{index_path}: line 1: no scene column (the recording of each episode)")
    by_scene: Dict[str, Dict[str, Tuple[float, float, float]]] = {}
    for e in episodes:
        r = rows.get(e.episode_id)
        if r is None:
            raise EpisodeError(f"{index_path}: episode {e.episode_id} is not in the index")
        by_scene.setdefault(r["scene"], {}).setdefault(r.get("person_track", e.episode_id), tuple(e.person))
    out = {}
    for e in episodes:
        r = rows[e.episode_id]
        own = tuple(e.person)
        others = [p for t, p in by_scene[r["scene"]].items()
                  if t != r.get("person_track") and math.hypot(p[0] - own[0], p[1] - own[1]) > 1e-6]
        out[e.episode_id] = [own] + others
    return out


STANDING_SPAN_M = 0.5  # a track whose positions within the episode stay within this of their mean is standing


def ucy_people(tracks_path: str, index_path: str, episodes, all_episodes=()) -> Dict[str, List[Tuple[float, float, float]]]:
    """episode id -> its standing person first, then every other pedestrian of the scene that stands
    (all positions within STANDING_SPAN_M of their mean) through the whole episode window
    t = 0.4 k0 .. 0.4 k1 (ucy_tracks.csv), walker excluded. Their facing: the person_yaw of a UCY
    episode about that track (the annotated gaze) when there is one, else towards the walker's
    mean position (the data has no other facing for them; counted in the return's meta)."""
    import numpy as np

    rows = read_index(index_path)
    tracks = _read_tracks(tracks_path)
    yaw_of: Dict[Tuple[str, str], float] = {}
    for e in list(all_episodes) + list(episodes):
        r = rows.get(e.episode_id)
        if r:
            yaw_of.setdefault((r["scene"], r["person_track"]), float(e.person[2]))
    out = {}
    for e in episodes:
        r = rows.get(e.episode_id)
        if r is None:
            raise EpisodeError(f"{index_path}: episode {e.episode_id} is not in the index")
        t0, t1 = 0.4 * int(r["k0"]), 0.4 * int(r["k1"])
        times = [round(0.4 * k, 1) for k in range(int(r["k0"]), int(r["k1"]) + 1)]
        walker = np.mean(e.xy, axis=0)
        people = [tuple(e.person)]
        for (scene, track), pos in tracks.items():
            if scene != r["scene"] or track in (r["person_track"], r["robot_track"]):
                continue
            if not all(t in pos for t in times):
                continue
            pts = np.array([pos[t] for t in times])
            c = pts.mean(axis=0)
            if np.linalg.norm(pts - c, axis=1).max() > STANDING_SPAN_M:
                continue
            yaw = yaw_of.get((scene, track))
            if yaw is None:
                yaw = math.atan2(walker[1] - c[1], walker[0] - c[0])
            people.append((float(c[0]), float(c[1]), float(yaw)))
        del t0, t1
        out[e.episode_id] = people
    return out


def _read_tracks(tracks_path: str) -> Dict[Tuple[str, str], Dict[float, Tuple[float, float]]]:
    """(scene, track) -> {t [s, rounded to 0.1]: (x, y)} of ucy_tracks.csv."""
    tracks: Dict[Tuple[str, str], Dict[float, Tuple[float, float]]] = {}
    try:
        with open(tracks_path, newline="") as f:
            for r in csv.DictReader(f):
                tracks.setdefault((r["scene"], r["track"]), {})[round(float(r["t"]), 1)] = (float(r["x"]), float(r["y"]))
    except (OSError, KeyError, ValueError) as exc:
        raise EpisodeError(f"{tracks_path}: cannot read scene,track,t,x,y: {exc}") from None
    return tracks


# A pedestrian is given as walking when their first step is at least this fast: clearly above the
# planner's standing threshold (gmmrrt-plan --person: below 0.2 m/s standing), so that no one is
# handed to the planner as a walker it would then treat as standing.
WALKING_MIN_SPEED_M_S = 0.3

# A pedestrian who stays this close to the walker at every step both are tracked in the episode window
# walks in the walker's group: pairs walk abreast and threes in a V, neighbours about 0.7-0.8 m apart,
# so the members of a group of two or three stay within about 1.5 m of one another (Moussaid et al., "The
# walking behaviour of pedestrian social groups and its impact on crowd dynamics", PLoS ONE 5(4) e10047,
# 2010); a group moves as one, so the robot put in the walker's place walks with them, not past them.
GROUP_DISTANCE_M = 1.5


def walks_with(walker: Dict[float, Tuple[float, float]], other: Dict[float, Tuple[float, float]], times) -> bool:
    """True when `other` walks in the walker's group through the window `times` [s]: tracked with the
    walker at two or more of those times, and within GROUP_DISTANCE_M of them at every one."""
    common = [t for t in times if t in walker and t in other]
    return len(common) >= 2 and all(math.hypot(walker[t][0] - other[t][0], walker[t][1] - other[t][1])
                                    <= GROUP_DISTANCE_M for t in common)


def ucy_walkers(tracks_path: str, index_path: str, episodes,
                bounds_of: Dict[str, Tuple[float, float, float, float]],
                exclude_group: bool = False) -> Dict[str, List[Tuple[float, ...]]]:
    """episode id -> the pedestrians walking in the scene when the episode starts, as a planner at
    that moment would see them: position at t0 = 0.4 k0, velocity of their next 0.4 s step (the
    constant-velocity prediction of gmmrrt-plan --person x,y,yaw,vx,vy), yaw = their heading;
    everyone tracked at t0 and t0 + 0.4 except the walker and the standing person of the episode,
    whose step is at least WALKING_MIN_SPEED_M_S, inside bounds_of[episode id] (xmin, ymin, xmax, ymax).
    With exclude_group, the walker's own group (walks_with through the episode window) is left out too."""
    rows = read_index(index_path)
    tracks = _read_tracks(tracks_path)
    out = {}
    for e in episodes:
        r = rows.get(e.episode_id)
        if r is None:
            raise EpisodeError(f"{index_path}: episode {e.episode_id} is not in the index")
        t0 = round(0.4 * int(r["k0"]), 1)
        t1 = round(t0 + 0.4, 1)
        window = [round(0.4 * k, 1) for k in range(int(r["k0"]), int(r["k1"]) + 1)]
        own = tracks.get((r["scene"], r["robot_track"]), {})
        b = bounds_of[e.episode_id]
        walkers = []
        for (scene, track), pos in tracks.items():
            if scene != r["scene"] or track in (r["person_track"], r["robot_track"]) or t0 not in pos or t1 not in pos:
                continue
            if exclude_group and walks_with(own, pos, window):
                continue
            (x0, y0), (x1, y1) = pos[t0], pos[t1]
            vx, vy = (x1 - x0) / 0.4, (y1 - y0) / 0.4
            if math.hypot(vx, vy) < WALKING_MIN_SPEED_M_S or not (b[0] <= x0 <= b[2] and b[1] <= y0 <= b[3]):
                continue
            walkers.append((x0, y0, math.atan2(vy, vx), vx, vy))
        out[e.episode_id] = walkers
    return out


def _situations(episodes, group_of):
    """Each episode's situation: (start and goal in the person frame, the side it passed on, its group)."""
    import numpy as np
    from . import core

    out = []
    for e in episodes:
        s = core.world_to_person(tuple(e.person), *e.xy[0])
        g = core.world_to_person(tuple(e.person), *e.xy[-1])
        out.append((np.array(s), np.array(g), side_of_sweep(e.xy, e.person), group_of(e)))
    return out


def _situation_distance(a, b) -> float:
    """How far apart two situations are: start-to-start plus goal-to-goal, in the person frame [m]."""
    import numpy as np

    return float(np.linalg.norm(a[0] - b[0]) + np.linalg.norm(a[1] - b[1]))


def human_side_agreement(episodes, group_of) -> Tuple[float, float, int]:
    """How often two humans in nearly the same situation pass on the same side: for each episode,
    the episode of another group (recording / standing person, so not the same event) whose start
    and goal in the person frame are nearest (sum of the two distances); returns (fraction passing
    on the same side by side_of_sweep, median start+goal distance of the pairs [m], pairs)."""
    import numpy as np

    if len(episodes) < 2:
        return math.nan, math.nan, 0
    ends = _situations(episodes, group_of)
    same, dists = [], []
    for i, a in enumerate(ends):
        best, bd = None, math.inf
        for j, b in enumerate(ends):
            if j == i or b[3] == a[3]:
                continue
            d = _situation_distance(a, b)
            if d < bd:
                best, bd = j, d
        if best is not None:
            same.append(a[2] == ends[best][2])
            dists.append(bd)
    return (float(np.mean(same)) if same else math.nan, float(np.median(dists)) if dists else math.nan, len(same))


# The pair distances (start + goal, person frame) at which the humans' agreement is reported.
AGREEMENT_RADII_M = (0.5, 1.0, 2.0)


def side_agreement_within(episodes, group_of, radii=AGREEMENT_RADII_M) -> List[Tuple[float, int, float]]:
    """[(r, pairs, fraction passing on the same side)] over every pair of episodes of different groups
    whose situations lie within r of each other (_situation_distance): whether humans agree more as
    their situations get closer, i.e. whether the situation decides the side."""
    ends = _situations(episodes, group_of)
    out = []
    for r in radii:
        same = [a[2] == b[2] for i, a in enumerate(ends) for b in ends[i + 1:]
                if a[3] != b[3] and _situation_distance(a, b) < r]
        out.append((float(r), len(same), sum(same) / len(same) if same else math.nan))
    return out


def side_ceiling(agreement: float) -> float:
    """The most often any rule on the situation can pass on the human's side, given how often two
    humans in the same situation agree (the situation being whatever the agreement was measured over,
    e.g. start and goal in the person frame; a rule that sees more is not bound by it). If a situation makes a human pass on one side with probability p
    and two humans choose independently, they agree with probability q = p^2 + (1 - p)^2, and the best rule
    (always the likelier side) agrees with one with probability m = max(p, 1 - p) = (1 + sqrt(2q - 1)) / 2.
    m is concave in q, so over a mix of situations the mean of m is at most this value at the mean q
    (Jensen's inequality). Agreement below one half (no pair of humans does that) gives one half."""
    if not math.isfinite(agreement):
        return math.nan
    return (1.0 + math.sqrt(max(0.0, 2.0 * agreement - 1.0))) / 2.0
