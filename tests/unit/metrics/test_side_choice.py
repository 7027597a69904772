"""metrics.side_choice: the rules that pick a side from the two costs `gmmrrt-plan --side either`
reports (tools/gmmrrt_tools/side_choice.py): the scores of a cost pair, a side without a path, the bias
learned by agreement (and no bias unless the data ask for it), and the training folds' index copies the
cross-fitted costs are learned from (experiments/side_costs.py)."""
import csv
import math

import numpy as np
import pytest

from gmmrrt_tools import side_choice as SC
from gmmrrt_tools.experiments import side_costs


def test_scores_of_a_cost_pair():
    assert SC.log_ratio(2.0, 1.0) == pytest.approx(math.log(2.0))
    assert SC.difference(2.0, 1.5) == pytest.approx(0.5)
    for f in (SC.log_ratio, SC.difference):
        assert f(math.inf, 3.0) > 1e8 and f(3.0, math.inf) < -1e8  # the side without a path loses
        assert f(math.nan, 3.0) > 1e8
        assert f(math.inf, math.inf) == 0.0


def test_a_side_without_a_path_is_never_chosen_whatever_the_bias():
    s = SC.scores([(math.inf, 5.0), (5.0, math.inf)], "ratio")
    for b in (-50.0, 0.0, 50.0):
        assert SC.choose(s, b).tolist() == [False, True]


def test_cheaper_side_is_the_zero_bias():
    s = SC.scores([(1.0, 2.0), (2.0, 1.0), (1.0, 1.0), (math.inf, math.inf)], "ratio")
    # as gmmrrt-plan --side either: the right only when strictly cheaper; a tie, or no path at all, is the left
    assert SC.choose(s).tolist() == [True, False, True, True]


def test_bias_is_learned_by_agreement():
    # the humans take the left unless it costs more than 20 % over the right: b between log 1.15 and log 1.25
    pairs = [(1.0 + 0.05 * i, 1.0) for i in range(-6, 10)]
    left = [c < 1.2 for c, _ in pairs]
    b = SC.fit_bias(SC.scores(pairs, "ratio"), np.array(left))
    assert math.log(1.15) < b < math.log(1.2)
    assert np.all(SC.choose(SC.scores(pairs, "ratio"), b) == np.array(left))


def test_no_bias_unless_the_data_ask_for_it():
    # the cheaper side explains every human: every threshold between the closest two ties, 0 is taken
    pairs = [(1.0, 2.0), (1.0, 1.5), (2.0, 1.0), (3.0, 1.0)]
    left = np.array([True, True, False, False])
    assert SC.fit_bias(SC.scores(pairs, "ratio"), left) == 0.0
    assert SC.fit_bias(SC.scores(pairs, "difference"), left) == 0.0
    # a side without a path does not add a threshold out at the sentinel
    pairs.append((math.inf, 1.0))
    assert SC.fit_bias(SC.scores(pairs, "ratio"), np.append(left, False)) == 0.0


def test_folds_keep_each_group_whole():
    groups = ["a", "a", "b", "c", "c", "c", "d", "e", "f"]
    fold = side_costs.fold_of(groups, 5)
    for g in set(groups):
        assert len({fold[i] for i, x in enumerate(groups) if x == g}) == 1
    assert set(fold.tolist()) == set(range(5))
    assert side_costs.fold_of(["a", "a", "b"], 5).max() == 1  # no more folds than groups


def test_fold_index_marks_the_fitting_episodes_train(tmp_path):
    src = tmp_path / "index.csv"
    src.write_text("episode_id,scene,split\na,s1,train\nb,s2,train\nc,s3,test\n")
    out = tmp_path / "folds" / "f0.csv"
    side_costs.fold_index(str(src), out, {"a"})
    rows = list(csv.DictReader(open(out)))
    assert [(r["episode_id"], r["scene"], r["split"]) for r in rows] == [("a", "s1", "train"), ("b", "s2", "test"),
                                                                          ("c", "s3", "test")]
    t = out.stat().st_mtime_ns
    side_costs.fold_index(str(src), out, {"a"})
    assert out.stat().st_mtime_ns == t  # unchanged: not rewritten, so its model is not refitted
    src.write_text("episode_id,scene\na,s1\n")
    with pytest.raises(RuntimeError, match=r"index\.csv: line 1: no split column"):
        side_costs.fold_index(str(src), out, {"a"})


def test_both_sides_are_read_from_the_planners_report(monkeypatch):
    """experiments/side_costs._plan_either on the `sides` object gmmrrt-plan --side either prints: a side
    whose status is not ok has no cost (inf) and no path, whatever numbers it carries."""
    from types import SimpleNamespace

    from gmmrrt_tools import runner as R

    sides = {"left": {"status": "ok", "cost": 3.0, "path": [[0, 0], [1, 1]]},
             "right": {"status": "no path on the preferred side", "cost": 7.0, "path": [[0, 0]]}}

    class Ctx:
        s = SimpleNamespace(seed=1, bias=0.95)

        def plan(self, *args, **kwargs):
            return ["gmmrrt-plan"]

        def run_plans(self, jobs, desc):
            return [(tag, R.PlanResult("ok", [], {}, seed, argv, sides)) for tag, argv, seed in jobs]

    monkeypatch.setattr(side_costs, "multi_person_scene", lambda e, people: None)
    e = SimpleNamespace(episode_id="a")
    cl, cr, paths = side_costs._plan_either(Ctx(), "set", [e], {"a": []}, [None], "paper")
    assert cl.tolist() == [3.0] and cr.tolist() == [math.inf]
    assert paths == [([(0.0, 0.0), (1.0, 1.0)], [])]
