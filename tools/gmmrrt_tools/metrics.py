"""Path-quality metrics: the paper's TDM and l_e (Sect. 5.2, eqs. (2)-(4)) and social-navigation metrics.

Paths are sequences of world points (N x 2 arrays, metres), read as polylines: a robot following the
path occupies every point of every segment, not only the vertices.

TDM, eq. (2). As printed, (2) is ambiguous between "for each demonstrated point the closest planned
point" and a double sum over all pairs. We implement the min-distance reading:

    TDM(zD, zP) = 1/|zD| * sum_i dist(zD(i), zP)

where dist(q, zP) is the Euclidean distance from the demonstration point q to the planned *polyline*:
the minimum over its segments [p_j, p_j+1] of |q - (p_j + t (p_j+1 - p_j))| with t clamped to [0, 1]
(so a demonstration point lying on a long straight planned segment counts 0, whatever the planner's
waypoint spacing). A one-point planned path is a single point. Averaging is over demonstration
points, as in (2), so the demonstration's sampling rate weights the sum, as in the paper.

Eq. (3): TDM over sets = mean of TDM(zD, zP) over all |D| x |P| pairs.
Eq. (4): l_e = mean over all pairs of |l(zD) - l(zP)| / l(zD), returned as a fraction
(multiply by 100 for the paper's percent); l is the polyline length.

Social metrics (not in the paper; what social-navigation evaluations usually report):
minimum distance from the path (polyline) to any person, fraction of the path's *length* within
0.45 m and 1.2 m of a person (Hall's intimate and personal zones; computed exactly per segment
from segment-disc intersections), smoothness as cumulative absolute heading change [rad], and for
the approach task the final distance to the person and the angle errors at the end of the path.
Outcome rates (success / collision / timeout) are computed from per-run outcomes by `outcome` and
`rates`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Dict, Iterable, List, Optional, Sequence, Tuple

import numpy as np

INTIMATE_ZONE_M = 0.45
PERSONAL_ZONE_M = 1.2


def as_path(points) -> np.ndarray:
    """`points` as an (N, 2) float array; raises ValueError on wrong shape, no points, NaN or Inf."""
    arr = np.asarray(points, dtype=float)
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise ValueError(f"a path must be N x 2 points, got shape {arr.shape}")
    if arr.shape[0] == 0:
        raise ValueError("a path must have at least one point")
    if not np.all(np.isfinite(arr)):
        raise ValueError("a path has NaN or Inf coordinates")
    return arr


def path_length(path) -> float:
    """Polyline length [m]."""
    p = as_path(path)
    return float(np.sum(np.linalg.norm(np.diff(p, axis=0), axis=1)))


def point_to_path_distances(points, path) -> np.ndarray:
    """Distance [m] from each of `points` (M x 2) to the polyline `path` (N x 2): min over segments,
    with the projection clamped to the segment. Shape (M,)."""
    q = as_path(points)
    p = as_path(path)
    if p.shape[0] == 1:
        return np.linalg.norm(q - p[0], axis=1)
    a = p[:-1]                       # (S, 2) segment starts
    ab = p[1:] - a                   # (S, 2)
    ab2 = np.sum(ab * ab, axis=1)    # (S,)
    aq = q[:, None, :] - a[None, :, :]                     # (M, S, 2)
    with np.errstate(invalid="ignore", divide="ignore"):
        t = np.sum(aq * ab[None], axis=2) / ab2[None]      # (M, S)
    t = np.where(ab2[None] > 0.0, np.clip(t, 0.0, 1.0), 0.0)
    closest = a[None] + t[..., None] * ab[None]
    d = np.linalg.norm(q[:, None, :] - closest, axis=2)
    return d.min(axis=1)


def tdm_pair(demo, planned) -> float:
    """TDM(zD, zP) [m], eq. (2), min-distance reading: mean over demonstration points of the distance
    to the planned polyline."""
    return float(np.mean(point_to_path_distances(demo, planned)))


def length_error_pair(demo, planned) -> float:
    """|l(zD) - l(zP)| / l(zD) (fraction), the term of eq. (4). Raises ValueError if l(zD) = 0."""
    ld = path_length(demo)
    if ld <= 0.0:
        raise ValueError("a demonstration of zero length has no length ratio")
    return abs(ld - path_length(planned)) / ld


def tdm(demos: Sequence, planned: Sequence) -> float:
    """Eq. (3): mean of TDM(zD, zP) over every (demonstration, planned) pair [m]."""
    if not demos or not planned:
        raise ValueError("TDM needs at least one demonstration and one planned path")
    return float(np.mean([tdm_pair(d, p) for d in demos for p in planned]))


def length_error(demos: Sequence, planned: Sequence) -> float:
    """Eq. (4): l_e over every (demonstration, planned) pair, as a fraction (x100 for percent)."""
    if not demos or not planned:
        raise ValueError("l_e needs at least one demonstration and one planned path")
    return float(np.mean([length_error_pair(d, p) for d in demos for p in planned]))


def per_plan_tdm_le(demos: Sequence, planned: Sequence) -> Tuple[np.ndarray, np.ndarray]:
    """For each planned path, its TDM and l_e against all demonstrations (eqs. (2)-(4) with |P| = 1).
    The mean of each array equals `tdm` / `length_error`; their spread gives the paper's "± std"."""
    t = np.array([np.mean([tdm_pair(d, p) for d in demos]) for p in planned])
    le = np.array([np.mean([length_error_pair(d, p) for d in demos]) for p in planned])
    return t, le


# ----------------------------------------------------------------------------- social metrics

def _people_xy(people) -> np.ndarray:
    arr = np.atleast_2d(np.asarray(people, dtype=float))
    if arr.shape[1] < 2 or not np.all(np.isfinite(arr[:, :2])):
        raise ValueError(f"people must be K x 2 or K x 3 finite rows, got shape {arr.shape}")
    return arr[:, :2]


def min_distance_to_people(path, people) -> float:
    """Smallest distance [m] from the polyline to any person centre (people: K x 2 or K x 3 (x, y, yaw)).
    +inf when there are no people."""
    if len(people) == 0:
        return math.inf
    return float(point_to_path_distances(_people_xy(people), path).min())


def _segment_disc_interval(a: np.ndarray, b: np.ndarray, c: np.ndarray, r: float):
    """Parameter interval [t0, t1] within [0, 1] of segment a->b inside the closed disc (c, r), or None."""
    d = b - a
    f = a - c
    A = float(d @ d)
    if A == 0.0:
        return (0.0, 1.0) if float(f @ f) <= r * r else None
    B = 2.0 * float(f @ d)
    C = float(f @ f) - r * r
    disc = B * B - 4.0 * A * C
    if disc < 0.0:
        return None
    s = math.sqrt(disc)
    t0 = (-B - s) / (2.0 * A)
    t1 = (-B + s) / (2.0 * A)
    lo, hi = max(t0, 0.0), min(t1, 1.0)
    return (lo, hi) if lo <= hi else None


def fraction_within(path, people, radius_m: float) -> float:
    """Fraction of the path's length that lies within radius_m of at least one person (exact: per
    segment, the union of its intervals inside each person's disc). A zero-length path counts 1 if
    its point is inside a disc, else 0."""
    p = as_path(path)
    if len(people) == 0:
        return 0.0
    centres = _people_xy(people)
    total = path_length(p)
    if total == 0.0:
        return 1.0 if np.min(np.linalg.norm(centres - p[0], axis=1)) <= radius_m else 0.0
    inside = 0.0
    for a, b in zip(p[:-1], p[1:]):
        seg = float(np.linalg.norm(b - a))
        if seg == 0.0:
            continue
        ivs = sorted(iv for iv in (_segment_disc_interval(a, b, c, radius_m) for c in centres) if iv)
        covered, cur_lo, cur_hi = 0.0, None, None
        for lo, hi in ivs:
            if cur_hi is None or lo > cur_hi:
                if cur_hi is not None:
                    covered += cur_hi - cur_lo
                cur_lo, cur_hi = lo, hi
            else:
                cur_hi = max(cur_hi, hi)
        if cur_hi is not None:
            covered += cur_hi - cur_lo
        inside += covered * seg
    return inside / total


def heading_changes(path) -> np.ndarray:
    """|wrap(heading_k+1 - heading_k)| [rad] between consecutive non-zero segments of the
    polyline (empty for fewer than two); the wrap is the core's (metrics.wrap)."""
    p = as_path(path)
    d = np.diff(p, axis=0)
    d = d[np.linalg.norm(d, axis=1) > 1e-12]
    if len(d) < 2:
        return np.zeros(0)
    h = np.arctan2(d[:, 1], d[:, 0])
    return np.abs([wrap(a) for a in np.diff(h)])


def smoothness(path) -> float:
    """Cumulative absolute heading change [rad] along the polyline: the sum of heading_changes.
    0 for a straight line."""
    return float(np.sum(heading_changes(path)))


def resample_by_arc_length(path, step_m: float) -> np.ndarray:
    """The polyline's points every `step_m` metres of arc length from its start, plus its end."""
    p = as_path(path)
    if not (step_m > 0.0):
        raise ValueError("step_m must be > 0")
    seg = np.linalg.norm(np.diff(p, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    if s[-1] <= 0.0:
        return p[:1].copy()
    targets = np.arange(0.0, s[-1], step_m)
    if s[-1] - targets[-1] > 1e-9:
        targets = np.append(targets, s[-1])
    return np.stack([np.interp(targets, s, p[:, 0]), np.interp(targets, s, p[:, 1])], axis=1)


def max_turn_per_step(path, step_m: float = 0.1) -> float:
    """Largest heading change [rad] between consecutive `step_m` pieces of the path (resampled by
    arc length, so waypoint spacing does not matter): what a follower must turn within step_m. A
    kink of the polyline shows as its full angle; an arc of radius R as about step_m / R."""
    return smoothness_max(resample_by_arc_length(path, step_m))


def smoothness_max(path) -> float:
    """Largest |wrap(heading_k+1 - heading_k)| between consecutive non-zero segments [rad]."""
    dh = heading_changes(path)
    return float(np.max(dh)) if len(dh) else 0.0


def turns_tighter_than(path, yaw, min_turn_radius_m: float) -> int:
    """Waypoint steps of a published plan that turn tighter than `min_turn_radius_m` [m]: the change of
    the published yaw (the tangent) between consecutive waypoints beyond what an arc of that radius
    through both allows, 2 asin(chord / 2R) (+1e-6 rad for rounding). 0 for a radius of 0 (turning in
    place allowed) or fewer than two waypoints."""
    p = as_path(path)
    y = np.asarray(yaw, dtype=float).reshape(-1)
    if y.shape[0] != p.shape[0]:
        raise ValueError(f"yaw has {y.shape[0]} values for {p.shape[0]} waypoints")
    if not (min_turn_radius_m > 0.0) or len(p) < 2:
        return 0
    chord = np.linalg.norm(np.diff(p, axis=0), axis=1)
    allowed = 2.0 * np.arcsin(np.minimum(1.0, chord / (2.0 * min_turn_radius_m))) + 1e-6
    turned = np.abs([wrap(a) for a in np.diff(y)])
    return int(np.sum(turned > allowed))


def summed_heading_change(path) -> float:
    """Total turning along the path [rad] (the cumulative heading change of `smoothness`)."""
    return smoothness(path)


def arrival_heading_error(path, goal_yaw: float, final_yaw: Optional[float] = None) -> float:
    """|wrap(heading at the goal - goal_yaw)| [rad]; the heading is `final_yaw` when given (the plan's
    published yaw), else the direction of the last non-zero segment (nan when there is none)."""
    if final_yaw is None:
        p = as_path(path)
        d = np.diff(p, axis=0)
        nz = d[np.linalg.norm(d, axis=1) > 1e-12]
        if not len(nz):
            return math.nan
        final_yaw = math.atan2(nz[-1, 1], nz[-1, 0])
    return abs(wrap(final_yaw - goal_yaw))


def min_distance_to_predicted_people(path, people, velocities, speed_m_s: float, horizon_s: float = 5.0,
                                     step_m: float = 0.02) -> float:
    """Smallest centre distance [m] between the robot following `path` at `speed_m_s` from its start
    and each person predicted with constant velocity, held where `horizon_s` leaves them (a
    conservative reading for evaluation; the planner itself does not predict beyond its horizon,
    moving_people.c). people: (x, y[, yaw]) rows; velocities: (vx, vy) rows, same order.
    inf without people."""
    if not (speed_m_s > 0.0) or not (horizon_s >= 0.0):
        raise ValueError("speed_m_s must be > 0 and horizon_s >= 0")
    if len(people) == 0:
        return math.inf
    ppl = _people_xy(people)
    vel = np.asarray(velocities, dtype=float).reshape(-1, 2)
    if vel.shape[0] != len(ppl) or not np.all(np.isfinite(vel)):
        raise ValueError("velocities must be finite (vx, vy) rows, one per person")
    q = resample_by_arc_length(path, step_m)
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(q, axis=0), axis=1))])
    t = np.minimum(s / speed_m_s, horizon_s)
    pos = ppl[None, :, :] + t[:, None, None] * vel[None, :, :]
    return float(np.min(np.linalg.norm(q[:, None, :] - pos, axis=2)))


def wrap(a: float) -> float:
    """Angle wrapped to (-pi, pi] by the C core (gmmrrt_wrap_angle): the one convention."""
    from gmmrrt_tools import core

    return core.wrap_angle(a)


@dataclass
class ApproachEnd:
    final_distance_m: float        # distance from the path's last point to the person
    distance_error_m: float        # |final_distance - reference final distance| (nan without reference)
    theta_error_rad: float         # |wrap(theta_end - theta_ref)| in the person's frame (nan without ref)
    heading_error_rad: float       # angle between the final segment's heading and the bearing to the person


def approach_end(path, person: Sequence[float], reference_end: Optional[Sequence[float]] = None) -> ApproachEnd:
    """End-of-path errors for the approach task. person = (x, y, yaw); reference_end = the point
    where the robot should stop (the goal or the demonstration's last point). theta is the person-frame
    bearing of the paper's features, computed by the C core (gmmrrt_tools.core.features_from_xy)."""
    from gmmrrt_tools import core  # the one definition of the features

    p = as_path(path)
    end = p[-1]
    d_end, th_end = core.features_from_xy(tuple(person), end[0], end[1])
    dist_err = th_err = math.nan
    if reference_end is not None:
        d_ref, th_ref = core.features_from_xy(tuple(person), reference_end[0], reference_end[1])
        dist_err = abs(d_end - d_ref)
        th_err = abs(wrap(th_end - th_ref))
    head_err = math.nan
    d = np.diff(p, axis=0)
    nz = d[np.linalg.norm(d, axis=1) > 1e-12]
    if len(nz):
        h = math.atan2(nz[-1, 1], nz[-1, 0])
        to_person = math.atan2(person[1] - end[1], person[0] - end[0])
        head_err = abs(wrap(to_person - h))
    return ApproachEnd(d_end, dist_err, th_err, head_err)


# ----------------------------------------------------------------------------- collisions, outcomes

def _segment_segment_distance(p0, p1, q0, q1) -> float:
    def cross(u, v):
        return u[0] * v[1] - u[1] * v[0]
    r, s = p1 - p0, q1 - q0
    den = cross(r, s)
    if den != 0.0:
        t = cross(q0 - p0, s) / den
        u = cross(q0 - p0, r) / den
        if 0.0 <= t <= 1.0 and 0.0 <= u <= 1.0:
            return 0.0
    cands = [point_to_path_distances([p0], [q0, q1])[0], point_to_path_distances([p1], [q0, q1])[0],
             point_to_path_distances([q0], [p0, p1])[0], point_to_path_distances([q1], [p0, p1])[0]]
    return float(min(cands))


def distance_to_box(path, box: Sequence[float]) -> float:
    """Distance [m] from the polyline to an oriented box (cx, cy, w, h, yaw): 0 when they touch."""
    cx, cy, w, h, yaw = (float(v) for v in box)
    p = as_path(path)
    c, s = math.cos(yaw), math.sin(yaw)
    local = np.column_stack(((p[:, 0] - cx) * c + (p[:, 1] - cy) * s,
                             -(p[:, 0] - cx) * s + (p[:, 1] - cy) * c))
    hw, hh = w / 2.0, h / 2.0
    if np.any((np.abs(local[:, 0]) <= hw) & (np.abs(local[:, 1]) <= hh)):
        return 0.0
    corners = np.array([[-hw, -hh], [hw, -hh], [hw, hh], [-hw, hh]])
    best = math.inf
    segs = [(local[0], local[0])] if len(local) == 1 else list(zip(local[:-1], local[1:]))
    for a, b in segs:
        for k in range(4):
            best = min(best, _segment_segment_distance(a, b, corners[k], corners[(k + 1) % 4]))
    return best


def path_collides(path, circles=(), boxes=(), people=(), robot_radius_m: float = 0.0,
                  person_radius_m: float = 0.0, tolerance_m: float = 1e-9) -> bool:
    """True if the disc robot (radius robot_radius_m) swept along the polyline overlaps an obstacle
    circle (x, y, r), an oriented box (cx, cy, w, h, yaw) or a person disc (person_radius_m) by more
    than tolerance_m (a planner that checks edges at a finite resolution can graze a corner by a
    fraction of that resolution)."""
    p = as_path(path)
    for x, y, r in circles:
        if point_to_path_distances([[x, y]], p)[0] < r + robot_radius_m - tolerance_m:
            return True
    for b in boxes:
        d = distance_to_box(p, b)
        if d < robot_radius_m - tolerance_m or (robot_radius_m <= tolerance_m and d == 0.0):
            return True
    if len(people) and person_radius_m + robot_radius_m > 0.0:
        if min_distance_to_people(p, people) < person_radius_m + robot_radius_m - tolerance_m:
            return True
    return False


SUCCESS, COLLISION, TIMEOUT, FAILURE = "success", "collision", "timeout", "failure"


def outcome(status: str, path, goal: Sequence[float], goal_tolerance_m: float = 0.3, **obstacles) -> str:
    """Classifies one planning run: `timeout` when the planner returned no path (status names the
    deadline or iteration cap, or no path found in the budget), `collision` when the returned path
    hits an obstacle or person (see path_collides; keyword arguments passed on), `failure` when it
    ends farther than goal_tolerance_m from the goal or the status is an error, else `success`. A
    drivable path flagged for a corner tighter than the turning radius (the core's
    GMMRRT_TIGHT_TURNS) is a path like an "ok" one: the flag is about the follower, not the plan."""
    from gmmrrt_tools import core

    st = (status or "").lower()
    if path is None or len(path) == 0:
        return TIMEOUT if ("timeout" in st or "no_path" in st or "no path" in st or st in ("", "ok")) \
            else FAILURE
    p = as_path(path)
    if path_collides(p, **obstacles):
        return COLLISION
    if np.linalg.norm(p[-1] - np.asarray(goal[:2], dtype=float)) > goal_tolerance_m:
        return FAILURE
    if st not in ("ok", "success", "gmmrrt_ok", core.status_str(core.STATUS_TIGHT_TURNS).lower()):
        return FAILURE
    return SUCCESS


def rates(outcomes: Iterable[str]) -> Dict[str, float]:
    """Fractions of success / collision / timeout / failure among outcomes (empty -> all nan)."""
    outs = list(outcomes)
    n = len(outs)
    return {k: (outs.count(k) / n if n else math.nan) for k in (SUCCESS, COLLISION, TIMEOUT, FAILURE)}


def social_metrics(path, people) -> Dict[str, float]:
    """min distance to a person [m], fractions within 0.45 m and 1.2 m, smoothness [rad], length [m]."""
    return {
        "min_dist_person_m": min_distance_to_people(path, people),
        "frac_within_0.45m": fraction_within(path, people, INTIMATE_ZONE_M),
        "frac_within_1.2m": fraction_within(path, people, PERSONAL_ZONE_M),
        "smoothness_rad": smoothness(path),
        "length_m": path_length(path),
    }


def passing_side(path, person: Sequence[float]) -> Optional[str]:
    """Side of the person the path passes, in the person's frame ('left': theta > 0, as the real-data
    README defines homotopy), taken at the path point closest to the person (the C core's
    gmmrrt_path_passing_side, which the learner's segmenter labels with too)."""
    from gmmrrt_tools import core

    return "left" if core.path_passing_side(tuple(person), as_path(path)) > 0 else "right"


def swept_angle(path, person: Sequence[float]) -> float:
    """Signed angle [rad] swept by the bearing from the person to the mover along the polyline
    (counter-clockwise positive): the sum of the wrapped bearing changes between consecutive points
    (the C core's gmmrrt_path_swept_angle). Two paths with the same start and goal pass the person
    on the same side iff their swept angles differ by less than pi (otherwise by about 2 pi): see
    same_homotopy."""
    from gmmrrt_tools import core

    return core.path_swept_angle(tuple(person), as_path(path))


def same_homotopy(path_a, path_b, person: Sequence[float]) -> bool:
    """True when two paths between (about) the same start and goal pass `person` on the same side:
    their swept angles (swept_angle) differ by less than pi. Robust where the side at the closest
    point is not (a closest approach in front of or behind the person)."""
    return abs(swept_angle(path_a, person) - swept_angle(path_b, person)) < math.pi


def mean_std(values) -> Tuple[float, float]:
    """Mean and population std of the finite values (nan, nan if none)."""
    v = np.asarray([x for x in values if x is not None and np.isfinite(x)], dtype=float)
    if v.size == 0:
        return math.nan, math.nan
    return float(v.mean()), float(v.std())


__all__ = [
    "INTIMATE_ZONE_M", "PERSONAL_ZONE_M", "as_path", "path_length", "point_to_path_distances",
    "tdm_pair", "length_error_pair", "tdm", "length_error", "per_plan_tdm_le",
    "min_distance_to_people", "fraction_within", "smoothness", "turns_tighter_than", "approach_end", "ApproachEnd",
    "distance_to_box", "path_collides", "outcome", "rates", "social_metrics", "passing_side",
    "swept_angle", "same_homotopy",
    "mean_std", "SUCCESS", "COLLISION", "TIMEOUT", "FAILURE",
]
