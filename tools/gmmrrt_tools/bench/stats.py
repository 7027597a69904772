"""Small statistics for the benchmarks: medians that keep "never" as infinity, and
best-cost curves read at a time or a cost.

A curve is a list of (time_ms, iterations, cost) points of one run, as gmmrrt-bench-ompl and
gmmrrt-bench-social write them; the best cost at time t is the lowest cost of the points at or
before t (infinity before the first solution).
"""
from __future__ import annotations

import math
import statistics
from typing import Iterable, List, Optional, Sequence

INF = math.inf


def median(values: Iterable[float]) -> float:
    """Median; infinities (a run that never got there) count as the largest values. NaN if empty."""
    vals = [INF if v is None else float(v) for v in values]
    if not vals:
        return math.nan
    return statistics.median(vals)


def quantile(values: Iterable[float], q: float) -> float:
    """The q-quantile (0..1) by the nearest rank; infinities kept; NaN if empty."""
    vals = sorted(INF if v is None else float(v) for v in values)
    if not vals:
        return math.nan
    return vals[min(len(vals) - 1, max(0, int(math.ceil(q * len(vals))) - 1))]


def cost_at(curve: Sequence[Sequence[float]], time_ms: float) -> float:
    """Best cost reached at or before time_ms (infinity if none)."""
    best = INF
    for t, _it, c in curve:
        if c is not None and t <= time_ms and c < best:
            best = c
    return best


def time_to_cost(curve: Sequence[Sequence[float]], target: float) -> float:
    """First time (ms) the best cost is <= target (infinity if never)."""
    for t, _it, c in sorted(curve, key=lambda p: p[0]):
        if c is not None and c <= target:
            return t
    return INF


def ratio(ours: float, peer: float) -> Optional[float]:
    """ours / peer, or None when either is missing, zero or not finite."""
    if ours is None or peer is None:
        return None
    if not (math.isfinite(ours) and math.isfinite(peer)) or peer == 0:
        return None
    return ours / peer


def finite_or_none(v: Optional[float]) -> Optional[float]:
    """JSON has no infinity or NaN: those become None."""
    if v is None or not math.isfinite(v):
        return None
    return float(v)


def clean(obj):
    """Recursively replaces non-finite floats by None so json.dump writes valid JSON."""
    if isinstance(obj, float):
        return finite_or_none(obj)
    if isinstance(obj, dict):
        return {k: clean(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [clean(v) for v in obj]
    return obj


def fmt(v: Optional[float], digits: int = 3, unit: str = "") -> str:
    """A number for a Markdown table: '-' when missing, 'never' when infinite."""
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return "-"
    if isinstance(v, float) and math.isinf(v):
        return "never"
    if isinstance(v, float):
        if v != 0 and (abs(v) >= 10 ** 6 or abs(v) < 10 ** -(digits)):
            return f"{v:.{digits}g}{unit}"
        return f"{v:,.{digits}f}{unit}"
    return f"{v}{unit}"


def counts(values: List[float]) -> int:
    """How many values are finite."""
    return sum(1 for v in values if v is not None and math.isfinite(v))
