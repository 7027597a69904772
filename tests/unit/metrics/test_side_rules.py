"""tools/side_rules.py: the person-frame geometry it learns the side from, its scoring on hand-made
episodes whose side the straight line decides (so every rule can be checked against the truth), and a
run on the real data (skipped, with the reason, without ../shared/data/real)."""
import math
import os
import subprocess
import sys
from pathlib import Path

import pytest

from gmmrrt_tools.episodes import Episode
from tool_script import load_tool_script

ROOT = Path(__file__).resolve().parents[3]
REAL = Path(os.environ.get("GMMRRT_REAL_DATA", ROOT.parent / "shared" / "data" / "real"))


SR = load_tool_script("side_rules")


def ep(eid, xy, person=(0.0, 0.0, 0.0), meta=None):
    e = Episode.from_rows(eid, "avoid", "left", [(0.1 * i, x, y, math.nan, *person) for i, (x, y) in enumerate(xy)])
    e.meta = meta or {}
    return e


def test_geometry_is_in_the_person_frame():
    # the person at (1, 1) facing +y: the mover goes from 3 m behind to 3 m ahead, 1 m to the person's right
    g = SR.geometry(ep("a", [(2, -2), (2, 4)], person=(1.0, 1.0, math.pi / 2)))
    s_x, s_y, g_x, g_y, offset, along, ux, uy = g
    assert (s_x, s_y, g_x, g_y) == pytest.approx((-3, -1, 3, -1))
    assert offset == pytest.approx(1.0)   # the person is on the line's left
    assert along == pytest.approx(0.5)
    assert (ux, uy) == pytest.approx((1, 0))


def test_rules_are_scored_against_the_humans_side():
    # the human passes on the straight line's side whenever the person is 0.3 m or more off the line;
    # so the straight line's rule is right on every episode, in cross-validation and on test
    eps = []
    for i in range(40):
        off = (0.3 + 0.05 * (i % 10)) * (1 if i % 2 else -1)
        bulge = 0.8 if off > 0 else -0.8  # passes farther out on the line's side
        eps.append(ep(f"e{i}", [(-3, off), (0, off + bulge), (3, off)], meta={"g": str(i // 4)}))
    train, test = eps[:30], eps[30:]
    rows = SR.evaluate(train, test, lambda e: e.meta["g"])
    assert rows[0][0] == "straight line's side" and rows[0][1:] == (1.0, 1.0)
    assert [r for r, _, _ in rows if "neighbours" in r] == ["1 nearest neighbours", "5 nearest neighbours",
                                                           "15 nearest neighbours"]  # 31 > a training fold
    assert all(0.0 <= cv <= 1.0 and 0.0 <= t <= 1.0 for _, cv, t in rows)
    assert dict((r, t) for r, _, t in rows)["logistic regression"] == 1.0  # the offset's sign separates


def test_cost_rules_are_learned_on_train_and_scored_on_test():
    """The rules on the two side costs: here the humans take the cheaper side unless the left costs at
    most 10 % more (a convention), so the cheaper side misses those near-ties and a bias on the cost
    ratio learned on train recovers them, in cross-validation and on test."""
    import numpy as np
    from gmmrrt_tools.experiments.side_costs import SideCosts

    def costs(n, seed):
        rng = np.random.default_rng(seed)
        ratio = np.exp(rng.uniform(-0.5, 0.5, n))
        left = ratio < 1.1
        eps = [ep(f"e{seed}_{i}", [(-3, 0.5), (0, 1.0), (3, 0.5)]) for i in range(n)]
        return SideCosts(eps, 10.0 * ratio, np.full(n, 10.0), left, [str(i // 3) for i in range(n)])

    rows = {r: (cv, t) for r, cv, t in SR.evaluate_costs(costs(120, 1), costs(60, 2), "paper")}
    cheaper = rows["cheaper side (paper cost)"]
    biased = rows["cheaper after a bias on the cost ratio (paper cost)"]
    assert cheaper[0] < 0.95 and cheaper[1] < 0.95  # the near-ties go left
    assert biased[0] > 0.97 and biased[1] > 0.97
    assert rows["cheaper after a bias on the cost difference (paper cost)"][1] > 0.97  # same costs, same scale here
    assert "logistic regression on the log cost ratio and the geometry (paper cost)" in rows
    always = rows["always the side most training humans take (paper cost)"]
    assert 0.5 < always[0] < 0.8 and 0.5 < always[1] < 0.8  # about 70 % of the ratios are below 1.1


def test_unknown_set_is_refused():
    r = subprocess.run([sys.executable, str(ROOT / "tools" / "side_rules.py"), "--sets", "nope"],
                       capture_output=True, text=True)
    assert r.returncode == 2 and "--sets: unknown nope" in r.stderr
    r = subprocess.run([sys.executable, str(ROOT / "tools" / "side_rules.py"), "--costs", "paper,cheap"],
                       capture_output=True, text=True)
    assert r.returncode == 2 and "--costs: unknown cheap" in r.stderr


@pytest.mark.skipif(not (REAL / "ucy_avoid_episodes.csv").is_file(),
                    reason=f"real data not found at {REAL} (set GMMRRT_REAL_DATA)")
def test_real_data_table_chooses_on_train():
    r = subprocess.run([sys.executable, str(ROOT / "tools" / "side_rules.py"), "--real-data", str(REAL),
                        "--sets", "ucy_avoid", "--costs", "none"], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    assert "chosen on train:" in r.stdout and r.stdout.count("(chosen)") == 1
    assert "| straight line's side" in r.stdout


def test_near_ties_are_the_episodes_the_costs_do_not_decide():
    import numpy as np
    from gmmrrt_tools.experiments.side_costs import SideCosts

    e = ep("a", [(-3, 0.5), (3, 0.5)])
    sc = SideCosts([e] * 4, np.array([10.0, 10.2, 10.0, 13.0]), np.array([10.1, 10.0, 10.4, 10.0]),
                   np.array([True, True, False, False]), ["g"] * 4)
    n, left = SR.near_ties(sc)  # |log ratio| < 0.05: the first three
    assert n == 3 and left == pytest.approx(2 / 3)


def test_chosen_tdm_scores_the_picked_sides_path():
    import numpy as np
    from gmmrrt_tools.experiments.side_costs import SideCosts

    human = ep("a", [(-3, 0.0), (0, 1.0), (3, 0.0)])
    left_path, right_path = [(-3, 0.0), (0, 1.0), (3, 0.0)], [(-3, 0.0), (0, -1.0), (3, 0.0)]
    sc = SideCosts([human, human], np.array([1.0, np.inf]), np.array([2.0, 2.0]), np.array([True, True]),
                   ["g", "g"], [(left_path, right_path), ([], right_path)])
    assert SR.chosen_tdm(sc, [True, True]) == pytest.approx(0.5 * SR.chosen_tdm(sc, [False, False]))
    # the second episode has no left path: its right path counts whatever the rule says
    assert SR.chosen_tdm(sc, [True, False]) == pytest.approx(SR.chosen_tdm(sc, [True, True]))
    # an episode with no path on either side has no TDM: named, not a NaN in the mean
    from gmmrrt_tools.episodes import EpisodeError
    none = SideCosts([human], np.array([np.inf]), np.array([np.inf]), np.array([True]), ["g"], [([], [])])
    with pytest.raises(EpisodeError, match=f"episode {human.episode_id}: no path on either side"):
        SR.chosen_tdm(none, [True])
