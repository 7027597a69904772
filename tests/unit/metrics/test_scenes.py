"""gmmrrt_tools.scenes: episodes (read by the learner's reader) with their index, the person frame and the planning scenes made from episodes."""
import math

import numpy as np
import pytest

from gmmrrt_tools import core, scenes

CSV = """episode_id,task,homotopy,t,robot_x,robot_y,person_x,person_y,person_yaw
e1,avoid,left,0.0,4.0,0.0,1.0,1.0,{yaw}
e1,avoid,left,0.1,1.0,3.0,1.0,1.0,{yaw}
e2,approach,frontal,0.0,5.0,5.0,0.0,0.0,0.0
e2,approach,frontal,0.1,0.2,0.0,0.0,0.0,0.0
"""
INDEX = """episode_id,task,split
e1,avoid,train
e2,approach,test
"""


@pytest.fixture()
def files(tmp_path):
    c = tmp_path / "ep.csv"
    c.write_text(CSV.format(yaw=math.pi / 2))
    i = tmp_path / "idx.csv"
    i.write_text(INDEX)
    return str(c), str(i)


def _need_core():
    try:
        core.lib()
    except core.CoreNotBuilt as exc:
        pytest.fail(f"libgmmrrt.so not built: {exc}")


def test_read_episodes_groups_rows_and_filters_by_split(files):
    c, i = files
    eps = scenes.read_episodes(c, index=i)
    assert [e.episode_id for e in eps] == ["e1", "e2"]
    assert [e.split for e in eps] == ["train", "test"] and eps[0].meta["task"] == "avoid"
    assert eps[0].xy.shape == (2, 2) and eps[0].person == (1.0, 1.0, math.pi / 2)
    assert [e.episode_id for e in scenes.read_episodes(c, index=i, split="test")] == ["e2"]
    assert [e.episode_id for e in scenes.read_episodes(c, task="avoid")] == ["e1"]


def test_an_event_listed_twice_is_read_once_and_its_warning_passed_on(tmp_path):
    c = tmp_path / "ep.csv"
    # a and b: one walker listed with both labels (a loop round the person has no one side)
    rows = CSV.format(yaw=0.0).replace("e1,", "a,")
    rows += "".join(f"b,avoid,right,{r}\n" for r in ("0.0,4.0,0.0,1.0,1.0,0.0", "0.1,1.0,3.0,1.0,1.0,0.0"))
    c.write_text(rows)
    said = []
    eps = scenes.read_episodes(str(c), warnings=said)
    assert [e.episode_id for e in eps] == ["a", "e2"]
    assert said == [f"{c}: episodes a and b are one event (the same person and positions at the same times) "
                    "with opposite homotopy labels (left, right); counted once, as a"]
    assert [e.episode_id for e in scenes.read_episodes(str(c), task="avoid")] == ["a"]


def test_bad_rows_name_file_and_line(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text(CSV.format(yaw="nan"))
    with pytest.raises(ValueError, match=r"bad.csv: line 2: column person_yaw = 'nan' is not a finite number"):
        scenes.read_episodes(str(bad))
    bad.write_text("a,b\n1,2\n")
    with pytest.raises(ValueError, match="line 1: header must be"):
        scenes.read_episodes(str(bad))


def test_person_frame(files):
    _need_core()
    e = scenes.read_episodes(files[0])[0]
    p = scenes.to_person_frame(e)
    # Person at (1, 1) facing +y: the point (4, 0) is 1 m behind-ish and 3 m to the person's right.
    assert p.person == (0.0, 0.0, 0.0)
    np.testing.assert_allclose(p.xy[0], [-1.0, -3.0], atol=1e-12)
    np.testing.assert_allclose(p.xy[1], [2.0, 0.0], atol=1e-12)


def test_canonical_scene_means_and_bounds():
    a = scenes.Episode.from_path("a", "avoid", "left", (0, 0, 0), np.array([[4.0, 0.0], [-4.0, 1.0]]))
    b = scenes.Episode.from_path("b", "avoid", "left", (0, 0, 0), np.array([[4.0, 2.0], [-4.0, 3.0]]))
    s = scenes.canonical_scene([a, b], margin_m=1.0)
    assert s.start == (4.0, 1.0) and s.goal == (-4.0, 2.0)
    assert s.bounds == (-5.0, -1.0, 5.0, 4.0)
    with pytest.raises(ValueError):
        scenes.canonical_scene([])


def test_episode_scene_pushes_a_goal_out_of_the_person(files):
    e = scenes.read_episodes(files[0])[1]  # ends 0.2 m in front of the person
    s = scenes.episode_scene(e, clearance_m=0.6)
    assert s.start == (5.0, 5.0)
    assert s.goal == pytest.approx((0.6, 0.0))
    assert s.people == [(0.0, 0.0, 0.0)]
