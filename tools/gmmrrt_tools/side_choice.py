"""Choosing the side of the person from the two costs `gmmrrt-plan --side either` reports: the planner
plans each side (same seed and budget) and returns the best path of each homotopy with its cost
(docs/planner.md, "The preferred side"); a caller picks one. The rules here see only those costs, so
they apply to any planner that reports them:

- **cheaper side**: the side with the lower cost (what one unconstrained plan converges to; no parameter);
- **cheaper after a bias on the cost ratio**: left when log(c_left / c_right) < b, b learned on training
  episodes (b > 0 leans left, i.e. a convention such as keeping right; one parameter);
- **cheaper after a bias on the cost difference**: left when c_left - c_right < b (one parameter, in the
  cost's units, so it depends on the path's length where the ratio does not).

A side without a path has an infinite cost; the other is chosen whatever the bias. `fit_bias` learns b
by the agreement with the humans' sides: the threshold between two observed values that agrees with the
most, and among equals the one nearest to 0 (no bias unless the data ask for it).
"""
from __future__ import annotations

import math
from typing import Sequence, Tuple

import numpy as np

# A side without a path: its score is this far beyond any finite one, so no bias flips it.
_NO_PATH = 1e9


def log_ratio(c_left: float, c_right: float) -> float:
    """log(c_left / c_right) of two positive costs; +_NO_PATH when the left has no path (inf or NaN),
    -_NO_PATH when the right has none; 0 when neither has."""
    lok, rok = math.isfinite(c_left) and c_left > 0, math.isfinite(c_right) and c_right > 0
    if lok and rok:
        return math.log(c_left / c_right)
    return 0.0 if lok == rok else (-_NO_PATH if lok else _NO_PATH)


def difference(c_left: float, c_right: float) -> float:
    """c_left - c_right; +_NO_PATH when the left has no path, -_NO_PATH when the right has none."""
    lok, rok = math.isfinite(c_left), math.isfinite(c_right)
    if lok and rok:
        return c_left - c_right
    return 0.0 if lok == rok else (-_NO_PATH if lok else _NO_PATH)


SCORES = {"ratio": log_ratio, "difference": difference}


def scores(costs: Sequence[Tuple[float, float]], kind: str) -> np.ndarray:
    """The score of each (c_left, c_right) pair under `kind` (ratio | difference)."""
    f = SCORES[kind]
    return np.array([f(float(l), float(r)) for l, r in costs], dtype=float)


def choose(score: np.ndarray, bias: float = 0.0) -> np.ndarray:
    """True (left) where score <= bias: the left is at most as dear after the bias. With bias 0 this is
    gmmrrt-plan --side either's own pick (planner/cli/gmmrrt_plan.c): the right only when it has a path
    and is strictly cheaper, so a tie, or no path on either side, is the left."""
    return np.asarray(score, dtype=float) <= bias


def fit_bias(score: np.ndarray, left: np.ndarray) -> float:
    """The b of `choose` that agrees most with the humans' sides `left` (True: left): candidates are 0
    and the midpoints between consecutive distinct finite scores; ties go to the smallest |b|."""
    s = np.asarray(score, dtype=float)
    y = np.asarray(left, dtype=bool)
    fin = np.unique(s[np.abs(s) < _NO_PATH])
    cands = np.concatenate([[0.0], (fin[1:] + fin[:-1]) / 2.0]) if fin.size > 1 else np.array([0.0])
    agree = np.array([np.sum(choose(s, b) == y) for b in cands])
    best = agree.max()
    return float(min(cands[agree == best], key=abs))
