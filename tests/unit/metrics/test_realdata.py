"""metrics.realdata: the selections of tools/gmmrrt_tools/realdata.py on small hand-made data (every
standing person of a UPO recording, the UCY scene's standing pedestrians, the side of a sweep, how often
two humans agree) and the named errors for a data set without a split or an episode without a person."""
import math
import os
from pathlib import Path

import pytest

from gmmrrt_tools import realdata as RD
from gmmrrt_tools.episodes import Episode, EpisodeError


def ep(eid, person, xy, split="test", meta=None):
    """An episode of the mover's positions xy past a standing person (x, y, yaw)."""
    e = Episode.from_rows(eid, "avoid", "left", [(0.1 * i, x, y, math.nan, *person) for i, (x, y) in enumerate(xy)])
    e.split, e.meta = split, meta
    return e


def test_side_of_sweep_is_counterclockwise_left():
    # the person at the origin; passing below it going +x turns the bearing counterclockwise
    assert RD.side_of_sweep([(-3, 0.1), (0, -1), (3, 0.1)], (0, 0, 0)) == "left"
    assert RD.side_of_sweep([(-3, -0.1), (0, 1), (3, -0.1)], (0, 0, 0)) == "right"
    assert RD.side_of_sweep([(3, 0.1), (0, 1), (-3, 0.1)], (0, 0, 0)) == "left"


def test_upo_people_are_the_recordings_persons_own_first(tmp_path):
    idx = tmp_path / "index.csv"
    idx.write_text("episode_id,scene,person_track,split\n"
                   "a,rec1,1,test\nb,rec1,2,test\nc,rec2,1,train\nd,rec1,2,train\n")
    eps = [ep("a", (0, 0, 0), [(0, 1)]), ep("b", (5, 0, 1), [(0, 1)]), ep("c", (9, 9, 0), [(0, 1)]),
           ep("d", (5, 0, 1), [(0, 1)])]
    people = RD.upo_people(str(idx), eps)
    assert people["a"] == [(0, 0, 0), (5, 0, 1)]
    assert people["b"] == [(5, 0, 1), (0, 0, 0)]
    assert people["c"] == [(9, 9, 0)]
    assert people["d"] == [(5, 0, 1), (0, 0, 0)]  # one entry per person track
    idx.write_text("episode_id,person_track,split\na,1,test\n")
    with pytest.raises(EpisodeError, match="no scene column"):
        RD.upo_people(str(idx), eps[:1])


def test_ucy_people_are_the_standing_pedestrians_of_the_window(tmp_path):
    idx = tmp_path / "ucy_index.csv"
    idx.write_text("episode_id,scene,person_track,robot_track,k0,k1,split\ne1,z,1,2,1,3,test\ne2,z,3,2,1,3,train\n")
    tracks = tmp_path / "tracks.csv"
    rows = ["scene,track,t,x,y"]
    for k in (1, 2, 3):
        t = round(0.4 * k, 1)
        rows += [f"z,1,{t},0,0", f"z,2,{t},{k},5",            # the person, the walker
                 f"z,3,{t},4,{0.1 * k}",                      # stands (with an annotated facing: episode e2)
                 f"z,4,{t},{-4},{2}",                         # stands, no facing: towards the walker
                 f"z,5,{t},{3 * k},-3",                       # walks: not standing
                 f"q,6,{t},1,1"]                              # another scene
    rows += ["z,7,0.4,8,8", "z,7,0.8,8,8"]                    # leaves before the window ends
    tracks.write_text("\n".join(rows) + "\n")
    e1 = ep("e1", (0, 0, 0.5), [(1, 5), (2, 5), (3, 5)])
    e2 = ep("e2", (4, 0.2, 2.0), [(1, 5)], split="train")
    people = RD.ucy_people(str(tracks), str(idx), [e1], [e1, e2])["e1"]
    assert people[0] == (0, 0, 0.5)
    assert len(people) == 3
    assert people[1][:2] == pytest.approx((4, 0.2)) and people[1][2] == 2.0
    assert people[2][:2] == pytest.approx((-4, 2)) and people[2][2] == pytest.approx(math.atan2(3, 6))


def test_ucy_walkers_are_the_people_walking_at_the_start(tmp_path):
    idx = tmp_path / "ucy_index.csv"
    idx.write_text("episode_id,scene,person_track,robot_track,k0,k1,split\ne1,z,1,2,1,3,test\n")
    tracks = tmp_path / "tracks.csv"
    rows = ["scene,track,t,x,y"]
    for k in (1, 2, 3):
        t = round(0.4 * k, 1)
        rows += [f"z,1,{t},0,0", f"z,2,{t},{k},5",            # the person, the walker: never walkers
                 f"z,3,{t},4,{0.04 * k}",                     # 0.1 m/s: standing, left out
                 f"z,4,{t},{-2 + 0.4 * k},{2 - 0.2 * k}",     # walks at (1, -0.5) m/s
                 f"z,5,{t},{30 + k},0",                       # walks, outside the bounds
                 f"q,6,{t},{k},1"]                            # another scene
    rows += ["z,7,0.8,1,1"]                                   # not there at t0 = 0.4
    tracks.write_text("\n".join(rows) + "\n")
    e1 = ep("e1", (0, 0, 0.5), [(1, 5), (2, 5), (3, 5)])
    w = RD.ucy_walkers(str(tracks), str(idx), [e1], {"e1": (-10, -10, 10, 10)})["e1"]
    assert len(w) == 1
    x, y, yaw, vx, vy = w[0]
    assert (x, y) == pytest.approx((-1.6, 1.8))
    assert (vx, vy) == pytest.approx((1.0, -0.5))
    assert yaw == pytest.approx(math.atan2(-0.5, 1.0))
    with pytest.raises(EpisodeError, match="not in the index"):
        RD.ucy_walkers(str(tracks), str(idx), [ep("zz", (0, 0, 0), [(0, 1)])], {"zz": (0, 0, 1, 1)})


def test_ucy_walkers_leave_out_the_walkers_own_group(tmp_path):
    idx = tmp_path / "ucy_index.csv"
    idx.write_text("episode_id,scene,person_track,robot_track,k0,k1,split\ne1,z,1,2,1,4,test\n")
    tracks = tmp_path / "tracks.csv"
    rows = ["scene,track,t,x,y"]
    for k in (1, 2, 3, 4):
        t = round(0.4 * k, 1)
        rows += [f"z,1,{t},0,0", f"z,2,{t},{0.5 * k},5",       # the person, the walker (1.25 m/s)
                 f"z,3,{t},{0.5 * k},{5.8}",                 # abreast of the walker throughout: its group
                 f"z,4,{t},{0.5 * k + 1.4 * (k - 1)},4"]     # starts 1 m away, then walks off: not a group
    tracks.write_text("\n".join(rows) + "\n")
    e1 = ep("e1", (0, 0, 0.5), [(0.5, 5), (2, 5)])
    every = RD.ucy_walkers(str(tracks), str(idx), [e1], {"e1": (-10, -10, 10, 10)})["e1"]
    assert sorted(round(w[1], 3) for w in every) == [4.0, 5.8]
    crowd = RD.ucy_walkers(str(tracks), str(idx), [e1], {"e1": (-10, -10, 10, 10)}, exclude_group=True)["e1"]
    assert [round(w[1], 3) for w in crowd] == [4.0]
    walker = {0.4: (0.0, 0.0), 0.8: (1.0, 0.0)}
    assert RD.walks_with(walker, {0.4: (0.0, 1.5), 0.8: (1.0, 1.5)}, [0.4, 0.8])
    assert not RD.walks_with(walker, {0.4: (0.0, 1.0), 0.8: (1.0, 1.6)}, [0.4, 0.8])
    assert not RD.walks_with(walker, {0.4: (0.0, 1.0)}, [0.4, 0.8])  # one common step says nothing


REAL = Path(os.environ.get("GMMRRT_REAL_DATA", "../shared/data/real"))


@pytest.mark.skipif(not all((REAL / f).is_file() for f in ("ucy_tracks.csv", "ucy_index.csv", "ucy_avoid_episodes.csv")),
                    reason=f"real data not found at {REAL} (set GMMRRT_REAL_DATA)")
def test_real_ucy_starts_inside_a_walker_are_mostly_its_own_group():
    """On the UCY avoid test split, most walkers that start in contact with another walking pedestrian
    (centres within 0.55 m) start beside a member of their own group: leaving the group out removes
    most such starts and keeps everyone else."""
    from gmmrrt_tools.scenes import read_episodes

    idx, tracks = str(REAL / "ucy_index.csv"), str(REAL / "ucy_tracks.csv")
    eps = read_episodes(str(REAL / "ucy_avoid_episodes.csv"), index=idx, split="test")
    assert eps, f"{idx}: no test episode"
    wide = {e.episode_id: (-1e9, -1e9, 1e9, 1e9) for e in eps}
    all_w = RD.ucy_walkers(tracks, idx, eps, wide)
    crowd = RD.ucy_walkers(tracks, idx, eps, wide, exclude_group=True)

    def starts_inside(walkers):
        return sum(any(math.hypot(w[0] - e.xy[0][0], w[1] - e.xy[0][1]) < 0.55 for w in walkers[e.episode_id])
                   for e in eps)
    before, after = starts_inside(all_w), starts_inside(crowd)
    assert before > 0 and after < before / 2, (before, after)
    for e in eps:  # the crowd is a subset: only group members were dropped
        assert set(crowd[e.episode_id]) <= set(all_w[e.episode_id])


def test_human_agreement_pairs_nearest_situations_of_other_groups():
    person = (0, 0, 0)
    left = [(-3, 0.1), (0, -1), (3, 0.1)]
    right = [(-3, 0.1), (0, 1), (3, 0.1)]
    eps = [ep("a", person, left, meta={"g": "1"}), ep("b", person, left, meta={"g": "2"}),
           ep("c", person, right, meta={"g": "3"}), ep("d", person, [(-3, 2), (3, 2)], meta={"g": "3"})]
    frac, dist, pairs = RD.human_side_agreement(eps, lambda e: e.meta["g"])
    assert pairs == 4
    # a<->b agree; c pairs with a (same ends, other group) and disagrees; d's nearest is a or b: right vs left
    assert frac == pytest.approx(0.5)
    assert dist == pytest.approx(0.0, abs=1e-12)  # three pairs share their ends exactly; d's is 3.8 m off


def test_agreement_within_counts_pairs_of_other_groups_by_distance():
    person = (0, 0, 0)
    left = [(-3, 0.1), (0, -1), (3, 0.1)]
    right = [(-3, 0.1), (0, 1), (3, 0.1)]
    far_right = [(-3, 0.9), (0, 1.5), (3, 0.9)]  # start and goal each 0.8 m from the others': 1.6 m apart
    eps = [ep("a", person, left, meta={"g": "1"}), ep("b", person, left, meta={"g": "2"}),
           ep("c", person, right, meta={"g": "3"}), ep("d", person, far_right, meta={"g": "3"})]
    bands = RD.side_agreement_within(eps, lambda e: e.meta["g"], radii=(0.5, 2.0))
    # within 0.5 m: a-b agree, a-c and b-c disagree (c-d share a group and never pair)
    assert bands[0] == (0.5, 3, pytest.approx(1 / 3))
    # within 2 m: also a-d and b-d, both disagree
    assert bands[1] == (2.0, 5, pytest.approx(1 / 5))
    assert RD.side_agreement_within(eps[:1], lambda e: e.meta["g"], radii=(1.0,))[0][1] == 0


def test_side_ceiling_bounds_the_best_rule_over_any_mix_of_situations():
    import random

    assert RD.side_ceiling(1.0) == 1.0
    assert RD.side_ceiling(0.5) == 0.5 and RD.side_ceiling(0.3) == 0.5
    assert RD.side_ceiling(0.9 ** 2 + 0.1 ** 2) == pytest.approx(0.9)  # one situation: exact
    assert math.isnan(RD.side_ceiling(math.nan))
    rnd = random.Random(7)
    for _ in range(200):  # the best rule (the likelier side everywhere) never beats the bound of the mean
        ps = [rnd.random() for _ in range(rnd.randint(1, 20))]
        q = sum(p * p + (1 - p) ** 2 for p in ps) / len(ps)
        best = sum(max(p, 1 - p) for p in ps) / len(ps)
        assert best <= RD.side_ceiling(q) + 1e-12, (ps, best, q)


def test_missing_split_and_missing_person_are_named(tmp_path):
    idx = tmp_path / "idx.csv"
    idx.write_text("episode_id,split\na,train\n")
    with pytest.raises(EpisodeError, match=r"idx\.csv: no episode in split 'test' \(splits found: train\)"):
        RD.require_split(str(idx), "test", [ep("a", (0, 0, 0), [(1, 1)], split="train")])
    RD.require_split(str(idx), "train", [ep("a", (0, 0, 0), [(1, 1)], split="train")])
    bad = ep("x7", (0, float("nan"), 0), [(1, 1)])
    with pytest.raises(EpisodeError, match="eps.csv: episode x7: no standing person"):
        RD._require_person("eps.csv", [bad])


def test_side_limit_counts_the_other_side_plans_a_target_allows():
    """experiments.real._side_limit: with same-side mean s and other-side mean o, a target T allows
    X <= n (T - s) / (o - s) plans on the other side."""
    from gmmrrt_tools.experiments import real as RE

    rs = RE.RealSet("real_upo_avoid", "", "", [None] * 10, [], [])
    gmm = [{"tdm_m": 0.2, "same_side": True}] * 8 + [{"tdm_m": 1.0, "same_side": False}] * 2
    rrt = [{"tdm_m": 0.5, "same_side": True}] * 10
    text = RE._side_limit(rs, {"GMM-RRT* (paper cost)": gmm, "RRT*": rrt}, ["GMM-RRT* (paper cost)", "RRT*"])
    # mean 0.36; T = 0.30 allows 10 (0.30 - 0.2) / 0.8 = 1.25 -> 1 plan: agreement >= 88 % (it has 80 %)
    assert "2 of 10 plans on the other side carry 56 %" in text
    assert "allows 1 such plans, a side agreement ≥ 88 % (it has 80 %)" in text
    rs.name = "real_ucy_avoid"  # 0.9 x RRT* = 0.45: 10 (0.45 - 0.2) / 0.8 = 3.1 -> 3 plans
    text = RE._side_limit(rs, {"GMM-RRT* (paper cost)": gmm, "RRT*": rrt}, ["GMM-RRT* (paper cost)", "RRT*"])
    assert "0.450 m" in text and "allows 3 such plans" in text
    # against RRT*: which other-side plans the two share, and the ratio where both are on the human's side
    assert "RRT* takes the other side too in 0 of its 2" in text
    assert "where both take the human's side (8 episodes) it scores 0.200 m against RRT*'s 0.500 m (0.40x)" in text
    rrt2 = [{"tdm_m": 0.5, "same_side": True}] * 9 + [{"tdm_m": 0.8, "same_side": False}]
    text = RE._side_limit(rs, {"GMM-RRT* (paper cost)": gmm, "RRT*": rrt2}, ["GMM-RRT* (paper cost)", "RRT*"])
    assert "RRT* takes the other side too in 1 of its 2 (1.00 m against RRT*'s 0.80 m)" in text
    # a row given the walking crowd is compared with RRT* given the same crowd, not with RRT* without it
    walk = "GMM-RRT* (paper cost, walking people given)"
    per = {walk: gmm, "RRT*": rrt, "RRT* (walking people given)": rrt2}
    text = RE._side_limit(rs, per, [walk, "RRT*", "RRT* (walking people given)"])
    assert "RRT* takes the other side too in 1 of its 2" in text
    rs.name = "real_ucy_approach"
    assert RE._side_limit(rs, {}, []) == ""
