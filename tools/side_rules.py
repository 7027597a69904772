#!/usr/bin/env python3
"""side_rules.py - can a rule learned on the training split guess the side of the person a human passes
on better than the planner does? Two families, each learned and chosen on the training split only and
scored once on the evaluation split:

- **geometry**: the straight line's side (the side the segment start-goal passes the person on) and
  classifiers on the episode's geometry in the person frame (start, goal, the person's signed offset from
  the line start-goal and where along it they stand, the line's direction): k nearest neighbours (k = 1,
  5, 15, 31), logistic regression, gradient boosting;
- **the two side costs** (`--costs`): `gmmrrt-plan --side either` returns the best path of each side with
  its cost; the rules of gmmrrt_tools.side_choice pick from those (the cheaper side; the cheaper after a
  bias on the cost ratio or difference), logistic regression on the log cost ratio alone and with the geometry,
  and "always the side most training humans take" (a convention such as keeping right, checked on train).
  The training costs are cross-fitted (experiments/side_costs.py: each fold's model is fitted on the
  other folds), so a rule sees costs like the evaluation split's.

Each rule is scored on the training split by grouped 5-fold cross-validation (folds by recording for UPO,
by standing person for UCY, so no event is on both sides of a fold), the best is chosen there, and every
rule is then scored once on the evaluation split. The side is realdata.side_of_sweep of the human's path.

    side_rules.py [--real-data DIR] [--split test] [--train-split train] [--sets upo_avoid,ucy_avoid]
                  [--costs paper,background|none] [--jobs 2]

Prints a markdown table per data set; docs/experiments.md ("What limits the TDM") quotes it.
"""
from __future__ import annotations

import argparse
import os
import sys
import warnings
from pathlib import Path
from typing import List, Tuple

import numpy as np

from gmmrrt_tools import core
from gmmrrt_tools import realdata as RD
from gmmrrt_tools import side_choice
from gmmrrt_tools.episodes import EpisodeError
from gmmrrt_tools.experiments.side_costs import SETS as SIDE_COST_SETS
from gmmrrt_tools.runner import MissingTool
from gmmrrt_tools.scenes import read_episodes

ROOT = Path(__file__).resolve().parent.parent

# data set -> (episodes file, index file, the group no fold splits): the side costs' own table.
SETS = SIDE_COST_SETS


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


def _cv_fold(groups, folds: int = 5):
    """The grouped folds of the training split: those of experiments/side_costs.fold_of, so the folds
    that choose a cost rule are the folds its costs were cross-fitted on."""
    from gmmrrt_tools.experiments.side_costs import fold_of

    return fold_of(groups, folds)


def _cost_features(costs, geo: np.ndarray) -> np.ndarray:
    """[log cost ratio (clipped to +-5: a side without a path counts as 150 times dearer), geometry]."""
    lr = np.clip(side_choice.scores(costs.pairs(), "ratio"), -5.0, 5.0)
    return np.column_stack([lr, geo])


def evaluate_costs(train, test, cost_name: str, test_choice=None) -> List[Tuple[str, float, float]]:
    """(rule, agreement on train by grouped cross-validation, agreement on test) for the rules on the two
    side costs (train, test: experiments/side_costs.SideCosts; train's costs cross-fitted). test_choice,
    a dict, receives each rule's side per test episode (True: left)."""
    from sklearn.linear_model import LogisticRegression
    from sklearn.pipeline import make_pipeline
    from sklearn.preprocessing import StandardScaler

    y, yt = train.human_left, test.human_left
    fold = _cv_fold(train.groups)
    rows = []
    choice = test_choice if test_choice is not None else {}

    def add(rule, cv_agreement, pt):
        """One row: the rule (tagged with the cost), its cross-validated agreement, its test choices."""
        name = f"{rule} ({cost_name} cost)"
        choice[name] = np.asarray(pt, dtype=bool)
        rows.append((name, cv_agreement, float(np.mean(choice[name] == yt))))

    def cv(rule, fit, predict, x, xt):
        """Fitted on four folds, scored on the fifth; then fitted on all of train for the test."""
        p = np.zeros(len(y), dtype=bool)
        for f in range(int(fold.max()) + 1):
            m = fit(x[fold != f], y[fold != f])
            p[fold == f] = predict(m, x[fold == f])
        add(rule, float(np.mean(p == y)), predict(fit(x, y), xt))

    ratio, ratio_t = (side_choice.scores(c.pairs(), "ratio") for c in (train, test))
    add("cheaper side", float(np.mean(side_choice.choose(ratio) == y)), side_choice.choose(ratio_t))
    for kind in ("ratio", "difference"):
        x, xt = (side_choice.scores(c.pairs(), kind) for c in (train, test))
        cv(f"cheaper after a bias on the cost {kind}", side_choice.fit_bias,
           lambda b, s: side_choice.choose(s, b), x, xt)
    # A convention (keep right: the person on the mover's left) would show as one side taken more often.
    cv("always the side most training humans take", lambda _x, yy: bool(np.mean(yy) >= 0.5),
       lambda b, s: np.full(len(s), b), ratio, ratio_t)
    geo, geo_t = (np.array([geometry(e) for e in c.episodes]) for c in (train, test))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        # The bias again, as the point where a fitted probability of 'left' crosses 1/2 (smoother than
        # counting agreements).
        cv("logistic regression on the log cost ratio", lambda x, yy: LogisticRegression().fit(x, yy),
           lambda m, x: m.predict(x), _cost_features(train, geo)[:, :1], _cost_features(test, geo_t)[:, :1])
        cv("logistic regression on the log cost ratio and the geometry",
           lambda x, yy: make_pipeline(StandardScaler(), LogisticRegression()).fit(x, yy),
           lambda m, x: m.predict(x), _cost_features(train, geo), _cost_features(test, geo_t))
    return rows


def chosen_tdm(test, left) -> float:
    """Mean TDM (metrics.tdm_pair, eq. (2)) of the test plans on the sides `left` (True: left) against
    the humans' paths; an episode whose chosen side has no path counts its other side's."""
    from gmmrrt_tools import metrics as M

    out = []
    for e, (pl, pr), lf in zip(test.episodes, test.paths, left):
        p = (pl if lf else pr) or (pr if lf else pl)
        if not p:
            raise EpisodeError(f"episode {e.episode_id}: no path on either side, so no rule has a TDM there")
        out.append(M.tdm_pair(e.xy, np.array(p)))
    return float(np.mean(out))


def near_ties(costs, within: float = 0.05) -> Tuple[int, float]:
    """(how many episodes, the share of their humans passing with the person on their left) among those
    whose two side costs are within `within` of each other (|log ratio| < within): where the costs do
    not decide, a convention (keeping right: the person on the left) would show."""
    r = side_choice.scores(costs.pairs(), "ratio")
    m = np.abs(r) < within
    return int(m.sum()), float(np.mean(costs.human_left[m])) if m.any() else float("nan")


def _cost_ctx(a):
    """The experiments' context for planning the side costs (the real study's settings)."""
    from gmmrrt_tools.experiments.common import Ctx

    ns = argparse.Namespace(quick=False, max_episodes=None, drivable=False, trials=None, iterations=None, seed=None,
                            jobs=a.jobs, out=a.work, work=a.work, bin_dir=a.bin_dir, demos_dir=None,
                            real_data=a.real_data, split=a.split, train_split=a.train_split, real_k=None,
                            real_sets=None)
    return Ctx(ns)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--real-data", default=os.environ.get("GMMRRT_REAL_DATA", str(ROOT.parent / "shared" / "data" / "real")))
    ap.add_argument("--split", default="test", help="the split scored once (default test)")
    ap.add_argument("--train-split", default="train", help="the split rules are learned and chosen on (default train)")
    ap.add_argument("--sets", default="upo_avoid,ucy_avoid", help=f"comma-separated, of {', '.join(SETS)}")
    ap.add_argument("--costs", default="paper,background",
                    help="task costs whose two side costs the cost rules learn from (comma-separated, of paper, "
                         "inward, background), or none (geometry rules only, no planning); default paper,background")
    ap.add_argument("--jobs", type=int, default=1, help="planner runs in parallel (default 1)")
    ap.add_argument("--work", default=str(ROOT / "out" / "side_rules"), help="scratch folder for the fold models")
    ap.add_argument("--bin-dir", default=os.environ.get("GMMRRT_BIN_DIR"), help="folder of gmmrrt-plan and gmmrrt-learn")
    a = ap.parse_args(argv)
    costs = [] if a.costs == "none" else a.costs.split(",")
    bad = [c for c in costs if c not in ("paper", "inward", "background")]
    if bad:
        ap.error(f"--costs: unknown {', '.join(bad)} (choose from paper, inward, background, or none)")
    if a.jobs < 1:
        ap.error(f"--jobs must be >= 1, got {a.jobs}")
    for name in a.sets.split(","):
        if name not in SETS:
            ap.error(f"--sets: unknown {name} (choose from {', '.join(SETS)})")
    for name in a.sets.split(","):
        ep_file, idx_file, group_of = SETS[name]
        ep_path, idx_path = os.path.join(a.real_data, ep_file), os.path.join(a.real_data, idx_file)
        try:
            said: list = []
            every = read_episodes(ep_path, index=idx_path, warnings=said)
            for w in said:
                print(w, file=sys.stderr)
            RD._require_person(ep_path, every)
            RD.require_split(idx_path, a.train_split, every)
            RD.require_split(idx_path, a.split, every)
            train = [e for e in every if e.split == a.train_split]
            test = [e for e in every if e.split == a.split]
            rows = evaluate(train, test, group_of)
            ties, tdm = [], {}
            if costs:
                from gmmrrt_tools.experiments.side_costs import side_costs

                ctx = _cost_ctx(a)
                for c in costs:
                    tr, te = side_costs(ctx, name, c)
                    test_choice: dict = {}
                    rows += evaluate_costs(tr, te, c, test_choice)
                    for r, left in test_choice.items():
                        tdm[r] = chosen_tdm(te, left)
                    for split, sc in ((a.train_split, tr), (a.split, te)):
                        n, left = near_ties(sc)
                        ties.append(f"{c} cost, {split}: {n} episodes, {100 * left:.0f} % with the person on the "
                                    f"human's left")
        except (EpisodeError, MissingTool, OSError, RuntimeError) as exc:
            print(f"side_rules: {name}: {exc}", file=sys.stderr)
            return 1
        best = max(rows, key=lambda r: r[1])
        print(f"\n{name}: {len(train)} {a.train_split} / {len(test)} {a.split} episodes; chosen on "
              f"{a.train_split}: {best[0]}\n")
        print(f"| rule | {a.train_split}, grouped 5-fold CV | {a.split} |\n|---|---|---|")
        for r, cv, t in rows:
            print(f"| {r}{' (chosen)' if r == best[0] else ''} | {100 * cv:.1f} % | {100 * t:.1f} % |")
        if tdm:
            print(f"\nTest TDM of the plans on the side each cost rule picks (`--side either`'s path of that side): "
                  + "; ".join(f"{r}: {v:.3f} m" for r, v in tdm.items()) + ".")
        if ties:
            print(f"\nWhere the two side costs are within 5 % of each other (the costs do not decide; a convention "
                  f"would show): {'; '.join(ties)}.")
    return 0


if __name__ == "__main__":
    sys.exit(main())
