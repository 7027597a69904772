#!/usr/bin/env python3
"""side_rules.py - can a rule learned on the training split guess the side of the person a human passes
on better than the planner does? Candidates: the straight line's side (the side the segment start-goal
passes the person on) and classifiers on the episode's geometry in the person frame (start, goal, the
person's signed offset from the line start-goal and where along it they stand, the line's direction):
k nearest neighbours (k = 1, 5, 15, 31), logistic regression, gradient boosting. Each is scored on the
training split by grouped 5-fold cross-validation (folds by recording for UPO, by standing person for
UCY, so no event is on both sides of a fold), the best is chosen there, and every candidate is then
scored once on the evaluation split. The side is realdata.side_of_sweep of the human's path.

    side_rules.py [--real-data DIR] [--split test] [--train-split train] [--sets upo_avoid,ucy_avoid]

Prints a markdown table per data set; docs/experiments.md ("What limits the TDM") quotes it.
"""
from __future__ import annotations

import argparse
import os
import sys
import warnings
from pathlib import Path
from typing import Callable, Dict, List, Tuple

import numpy as np

from gmmrrt_tools import core
from gmmrrt_tools import realdata as RD
from gmmrrt_tools.episodes import EpisodeError
from gmmrrt_tools.runner import MissingTool
from gmmrrt_tools.scenes import read_episodes

ROOT = Path(__file__).resolve().parent.parent

# data set -> (episodes file, index file, the group no fold splits: one recording / one standing person)
SETS: Dict[str, Tuple[str, str, Callable]] = {
    "upo_avoid": ("upo_avoid_episodes.csv", "upo_avoid_index.csv", lambda e: str(e.meta["scene"])),
    "ucy_avoid": ("ucy_avoid_episodes.csv", "ucy_index.csv",
                  lambda e: f"{e.meta['scene']}/{e.meta['person_track']}"),
}


def geometry(e) -> List[float]:
    """The episode's start and goal in the person frame (x ahead of the person, y to their left), the
    person's signed offset from the line start-goal (> 0: on the line's left), where along the line the
    person stands (0 at the start, 1 at the goal) and the line's unit direction."""
    s = np.array(core.world_to_person(tuple(e.person), *e.xy[0]))
    g = np.array(core.world_to_person(tuple(e.person), *e.xy[-1]))
    d = g - s
    n = float(np.linalg.norm(d)) or 1.0
    u = d / n
    offset = float(u[0] * -s[1] - u[1] * -s[0])
    along = float(np.dot(-s, u)) / n
    return [s[0], s[1], g[0], g[1], offset, along, u[0], u[1]]


def straight_side(e) -> str:
    return RD.side_of_sweep(np.array([e.xy[0], e.xy[-1]]), e.person)


def classifiers(max_k: int) -> Dict[str, object]:
    """The candidates; k nearest neighbours only for k <= max_k (the smallest training fold)."""
    from sklearn.ensemble import GradientBoostingClassifier
    from sklearn.linear_model import LogisticRegression
    from sklearn.neighbors import KNeighborsClassifier
    from sklearn.pipeline import make_pipeline
    from sklearn.preprocessing import StandardScaler

    out: Dict[str, object] = {f"{k} nearest neighbours": make_pipeline(StandardScaler(), KNeighborsClassifier(k))
                              for k in (1, 5, 15, 31) if k <= max_k}
    out["logistic regression"] = make_pipeline(StandardScaler(), LogisticRegression())
    out["gradient boosting"] = GradientBoostingClassifier(random_state=0)
    return out


def evaluate(train, test, group_of, folds: int = 5) -> List[Tuple[str, float, float]]:
    """(rule, agreement on train by grouped cross-validation, agreement on test) for the straight line's
    side and each classifier, in that order."""
    from sklearn.model_selection import GroupKFold, cross_val_predict

    y = np.array([RD.side_of_sweep(e.xy, e.person) == "left" for e in train])
    yt = np.array([RD.side_of_sweep(e.xy, e.person) == "left" for e in test])
    x, xt = np.array([geometry(e) for e in train]), np.array([geometry(e) for e in test])
    groups = [group_of(e) for e in train]
    st, stt = (np.array([straight_side(e) == "left" for e in es]) for es in (train, test))
    rows = [("straight line's side", float(np.mean(st == y)), float(np.mean(stt == yt)))]
    cv = GroupKFold(min(folds, len(set(groups))))
    smallest = min(len(tr) for tr, _ in cv.split(x, y, groups))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for name, model in classifiers(smallest).items():
            p = cross_val_predict(model, x, y, groups=groups, cv=cv)
            model.fit(x, y)
            rows.append((name, float(np.mean(p == y)), float(np.mean(model.predict(xt) == yt))))
    return rows


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--real-data", default=os.environ.get("GMMRRT_REAL_DATA", str(ROOT.parent / "shared" / "data" / "real")))
    ap.add_argument("--split", default="test", help="the split scored once (default test)")
    ap.add_argument("--train-split", default="train", help="the split rules are learned and chosen on (default train)")
    ap.add_argument("--sets", default="upo_avoid,ucy_avoid", help=f"comma-separated, of {', '.join(SETS)}")
    a = ap.parse_args(argv)
    for name in a.sets.split(","):
        if name not in SETS:
            ap.error(f"--sets: unknown {name} (choose from {', '.join(SETS)})")
        ep_file, idx_file, group_of = SETS[name]
        ep_path, idx_path = os.path.join(a.real_data, ep_file), os.path.join(a.real_data, idx_file)
        try:
            every = read_episodes(ep_path, index=idx_path)
            RD._require_person(ep_path, every)
            RD.require_split(idx_path, a.train_split, every)
            RD.require_split(idx_path, a.split, every)
        except (EpisodeError, MissingTool, OSError) as exc:
            print(f"side_rules: {name}: {exc}", file=sys.stderr)
            return 1
        train = [e for e in every if e.split == a.train_split]
        test = [e for e in every if e.split == a.split]
        rows = evaluate(train, test, group_of)
        best = max(rows, key=lambda r: r[1])
        print(f"\n{name}: {len(train)} {a.train_split} / {len(test)} {a.split} episodes; chosen on "
              f"{a.train_split}: {best[0]}\n")
        print(f"| rule | {a.train_split}, grouped 5-fold CV | {a.split} |\n|---|---|---|")
        for r, cv, t in rows:
            print(f"| {r}{' (chosen)' if r == best[0] else ''} | {100 * cv:.1f} % | {100 * t:.1f} % |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
