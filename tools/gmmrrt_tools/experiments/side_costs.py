"""The two side costs of `gmmrrt-plan --side either` on the real avoid data, for learning a side rule
(gmmrrt_tools.side_choice) on the training split only:

- on the **training split, cross-fitted**: the training episodes are cut into grouped folds (by
  recording for UPO, by standing person for UCY, so no event is on both sides of a fold); for each fold
  the avoid model is fitted on the other folds (a copy of the index whose split column says which) and
  the fold's episodes are planned with it. So each training episode's costs come from a model that did
  not see it, as a test episode's do from the model fitted on the whole training split.
- on the **evaluation split**: planned with the model fitted on the whole training split (the real
  study's model).

Scenes, people, seeds and budgets are the real study's (experiments/real.py): every standing person,
seed = base + the episode's position in its list.
"""
from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Dict, List, Tuple

import numpy as np

from gmmrrt_tools import realdata as RD
from gmmrrt_tools import runner as R

from .common import Ctx
from .real import _k_suffix, _real_file, _study_episodes, multi_person_scene

FOLDS = 5

# data set -> (episodes file, index file, the group no fold splits: one recording / one standing person)
SETS: Dict[str, Tuple[str, str, Callable]] = {
    "upo_avoid": ("upo_avoid_episodes.csv", "upo_avoid_index.csv", lambda e: str(e.meta["scene"])),
    "ucy_avoid": ("ucy_avoid_episodes.csv", "ucy_index.csv",
                  lambda e: f"{e.meta['scene']}/{e.meta['person_track']}"),
}


@dataclass
class SideCosts:
    """Per episode (in the order of `episodes`): the cost of the best path on each side (inf: none on
    that side) and the human's side (True: left, realdata.side_of_sweep)."""
    episodes: list
    cost_left: np.ndarray
    cost_right: np.ndarray
    human_left: np.ndarray
    groups: List[str]
    paths: List[Tuple[list, list]] = field(default_factory=list)  # per episode: (left path, right path); [] = none

    def pairs(self) -> List[Tuple[float, float]]:
        return list(zip(self.cost_left.tolist(), self.cost_right.tolist()))


def fold_of(groups: List[str], folds: int = FOLDS) -> np.ndarray:
    """The fold of each item: sklearn's GroupKFold over the groups (deterministic; every group in one
    fold), at most as many folds as groups."""
    from sklearn.model_selection import GroupKFold

    n = min(folds, len(set(groups)))
    out = np.zeros(len(groups), dtype=int)
    for f, (_, held) in enumerate(GroupKFold(n).split(np.zeros(len(groups)), groups=groups)):
        out[held] = f
    return out


def fold_index(index_path: str, out: Path, fit_ids: set) -> Path:
    """A copy of the index whose split column is 'train' for the episodes in fit_ids and 'test' for
    every other (the learner knows those two): gmmrrt-learn fit --split train then fits on exactly them."""
    with open(index_path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows or "split" not in rows[0]:
        raise RuntimeError(f"{index_path}: line 1: no split column")
    buf = io.StringIO(newline="")
    w = csv.DictWriter(buf, fieldnames=list(rows[0]))
    w.writeheader()
    for r in rows:
        w.writerow({**r, "split": "train" if r["episode_id"] in fit_ids else "test"})
    text = buf.getvalue()
    if out.is_file():
        with open(out, newline="") as f:
            if f.read() == text:
                return out  # unchanged: keep its time, so the fold's model is not refitted
    out.parent.mkdir(parents=True, exist_ok=True)
    tmp = out.with_suffix(".tmp")
    with open(tmp, "w", newline="") as f:
        f.write(text)
    tmp.replace(out)
    return out


def _cost(side: dict) -> float:
    c = side.get("cost") if side else None
    return float(c) if c is not None and side.get("status") == "ok" else math.inf


def _people(ctx: Ctx, name: str, idx: str, every: list, eps: list) -> Dict[str, list]:
    if name == "upo_avoid":
        return RD.upo_people(idx, every)
    return RD.ucy_people(_real_file(ctx, "ucy_tracks.csv"), idx, eps, every)


def _plan_either(ctx: Ctx, name: str, eps: list, people, models: List[Path], cost: str):
    """Costs and paths of each side for eps[k] planned with models[k] (seed = base + k)."""
    jobs = []
    for k, (e, mdl) in enumerate(zip(eps, models)):
        sc = multi_person_scene(e, people[e.episode_id])
        args = ["--task-cost", cost, "--side", "either", "--side-person", "0"]
        jobs.append(({"k": k}, ctx.plan(sc, "gmm-rrt-star", ctx.s.seed + k, mdl, None, ctx.s.bias, args),
                     ctx.s.seed + k))
    res = ctx.run_plans(jobs, f"{name} {cost} cost, both sides")
    cl = np.array([_cost(r.sides.get("left", {})) for _, r in res])
    cr = np.array([_cost(r.sides.get("right", {})) for _, r in res])
    paths = []
    for (_, r), c_left, c_right in zip(res, cl, cr):
        pair = []
        for side, c in (("left", c_left), ("right", c_right)):
            pts = r.sides.get(side, {}).get("path") or [] if math.isfinite(c) else []
            pair.append([(float(x), float(y)) for x, y in pts])
        paths.append((pair[0], pair[1]))
    return cl, cr, paths


def side_costs(ctx: Ctx, name: str, cost: str) -> Tuple[SideCosts, SideCosts]:
    """(training split cross-fitted, evaluation split) side costs of data set `name` under the task
    cost `cost` (paper | inward | background)."""
    ep_file, idx_file, group_of = SETS[name]
    ep_csv, idx = _real_file(ctx, ep_file), _real_file(ctx, idx_file)
    every, _ = _study_episodes(ctx, ep_csv, idx)
    train = [e for e in every if e.split == ctx.train_split]
    test = [e for e in every if e.split == ctx.split]
    groups = [group_of(e) for e in train]
    fold = fold_of(groups)
    models_dir = ctx.work / "models"
    fold_models = []
    for f in range(int(fold.max()) + 1):
        fit_ids = {e.episode_id for e, g in zip(train, fold) if g != f}
        fidx = fold_index(idx, ctx.work / "folds" / f"{name}_{ctx.train_split}_fold{f}_index.csv", fit_ids)
        out = models_dir / f"{name}_{ctx.train_split}_fold{f}of{FOLDS}_all_bg{_k_suffix(ctx)}.gmm"
        if out.exists() and out.stat().st_mtime < Path(fidx).stat().st_mtime:
            out.unlink()  # the fold's episodes changed: refit
        fold_models.append(R.fit_model(out, "avoid", [ep_csv], homotopy="all", k=ctx.real_k,
                                       seed=ctx.s.seed, index=str(fidx), split="train", bin_dir=ctx.bin_dir,
                                       background=True))
    full = R.fit_model(models_dir / f"{name}_{ctx.train_split}_all_bg{_k_suffix(ctx)}.gmm", "avoid", [ep_csv],
                       homotopy="all", k=ctx.real_k, seed=ctx.s.seed, index=idx, split=ctx.train_split,
                       bin_dir=ctx.bin_dir, background=True)
    people = _people(ctx, name, idx, every, train + test)
    cl, cr, paths = _plan_either(ctx, f"{name} {ctx.train_split} (cross-fitted)", train, people,
                                 [fold_models[f] for f in fold], cost)
    tl, tr, tpaths = _plan_either(ctx, f"{name} {ctx.split}", test, people, [full] * len(test), cost)

    def human(es):
        return np.array([RD.side_of_sweep(e.xy, e.person) == "left" for e in es])
    return (SideCosts(train, cl, cr, human(train), groups, paths),
            SideCosts(test, tl, tr, human(test), [group_of(e) for e in test], tpaths))
