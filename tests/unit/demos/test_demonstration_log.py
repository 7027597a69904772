"""Python demonstration I/O (tools/gmmrrt_tools/{episodes,demonstration_log}.py, tools/convert_demonstrations.py): the
Python writers against the one reader, the learner's (read through `gmmrrt-learn dump --json`).
CSV -> log -> CSV round trip (values to 1e-9, labels kept), the writer's refusals, the reader's
errors and warnings reaching Python with file and place, sparse PEOPLE within the pairing age.
The reader's own fault tests (truncated and bit-flipped logs, every CSV rule) are
tests/unit/demos/test_demo_io.cpp."""
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from gmmrrt import demo_info_t, people_t, pose2d_t
from gmmrrt_tools.demonstration_log import MAX_PERSON_AGE_S, write_demo_log
from gmmrrt_tools.episodes import Episode, EpisodeError, read_episodes

import lcm

REPO = Path(__file__).resolve().parents[3]
CONVERT = REPO / "tools" / "convert_demonstrations.py"
HEADER = "episode_id,task,homotopy,t,robot_x,robot_y,person_x,person_y,person_yaw\n"


def sample_csv(path: Path) -> None:
    rng = np.random.default_rng(4)
    rows = [HEADER]
    for eid, task, hom, n in (("a_1", "avoid", "left", 30), ("b_7", "approach", "frontal", 12),
                              ("c_9", "approach", "right", 5)):
        x0, y0 = rng.normal(size=2)
        px, py, pyaw = rng.normal(size=3)
        for i in range(n):
            t = 0.1 * i
            rows.append(f"{eid},{task},{hom},{t!r},{x0 + 0.05 * i + rng.normal() * 1e-3!r},"
                        f"{y0 + rng.normal() * 1e-3!r},{px!r},{py!r},{pyaw!r}\n")
    path.write_text("".join(rows))


def run_convert(*args):
    env = dict(os.environ)
    return subprocess.run([sys.executable, str(CONVERT), *map(str, args)], capture_output=True, text=True,
                          env=env)


def assert_same_episodes(a, b):
    assert len(a) == len(b)
    for ea, eb in zip(a, b):
        assert (ea.task, ea.homotopy) == (eb.task, eb.homotopy)
        assert len(ea) == len(eb)
        for name in ("t", "robot_x", "robot_y", "person_x", "person_y", "person_yaw"):
            np.testing.assert_allclose(getattr(eb, name), getattr(ea, name), rtol=0, atol=1e-9, err_msg=name)


def test_csv_log_csv_round_trip_keeps_values_and_labels(tmp_path):
    src = tmp_path / "src.csv"
    sample_csv(src)
    log, back = tmp_path / "demo.lcmlog", tmp_path / "back.csv"
    r = run_convert("csv2log", src, log)
    assert r.returncode == 0, r.stderr
    assert "episode 1: b_7 approach frontal" in r.stdout
    r = run_convert("log2csv", log, back)
    assert r.returncode == 0, r.stderr
    a, b = read_episodes(str(src))[0], read_episodes(str(back))[0]
    assert_same_episodes(a, b)
    assert [e.id for e in b] == ["demo_0000", "demo_0001", "demo_0002"]
    # The log itself carries the labels and a heading from the motion (finite, +x mostly).
    eps, warnings = read_episodes(str(log))
    assert warnings == []
    assert [(e.task, e.homotopy) for e in eps] == [("avoid", "left"), ("approach", "frontal"),
                                                   ("approach", "right")]
    assert np.all(np.isfinite(eps[0].robot_yaw))
    assert abs(np.median(eps[0].robot_yaw)) < 0.3


def test_real_upo_round_trip_with_split(tmp_path):
    real = Path(os.environ.get("GMMRRT_REAL_DATA", ""))
    src, index = real / "upo_avoid_episodes.csv", real / "upo_avoid_index.csv"
    if not src.is_file() or not index.is_file():
        pytest.skip(f"real data not found ({src}): set GMMRRT_REAL_DATA")
    log, back = tmp_path / "upo.lcmlog", tmp_path / "back.csv"
    r = run_convert("csv2log", src, log, "--index", index, "--split", "test", "--max-episodes", 20)
    assert r.returncode == 0, r.stderr
    orig = [e for e in read_episodes(str(src), index=str(index))[0] if e.split == "test"][:20]
    r = run_convert("log2csv", log, back)
    assert r.returncode == 0, r.stderr
    assert_same_episodes(orig, read_episodes(str(back))[0])


def test_writer_refuses_bad_input_and_leaves_no_file(tmp_path):
    ep = Episode.from_rows("x", "avoid", "left", [(0, 0, 0, 0, 1, 1, 0), (0.1, math.nan, 0, 0, 1, 1, 0)])
    out = tmp_path / "bad.lcmlog"
    with pytest.raises(EpisodeError, match="non-finite"):
        write_demo_log(str(out), [ep])
    assert list(tmp_path.iterdir()) == []
    r = run_convert("csv2log", tmp_path / "missing.csv", out)
    assert r.returncode == 1 and "missing.csv: cannot open" in r.stderr
    assert not out.exists()


def write_events(path: Path, events):
    log = lcm.EventLog(str(path), "w", overwrite=True)
    for ch, msg in events:
        log.write_event(msg.utime, ch, msg.encode())
    log.close()


def info(utime, episode, task=1, homotopy=1, person=3):
    m = demo_info_t()
    m.utime, m.episode, m.task, m.homotopy, m.person_id = utime, episode, task, homotopy, person
    return m


def pose(utime, x):
    m = pose2d_t()
    m.frame = "map"
    m.utime, m.x = utime, x
    return m


def people(utime, pid=3):
    m = people_t()
    m.frame = "map"
    m.utime, m.num_people = utime, 1
    m.people[0].utime, m.people[0].id, m.people[0].x = utime, pid, 1.0
    return m


def test_bad_events_are_skipped_with_warnings_naming_the_event(tmp_path):
    t0 = 1_700_000_000_000_000
    age = int(MAX_PERSON_AGE_S * 1e6)
    p = tmp_path / "bad.lcmlog"
    write_events(p, [("DEMO_INFO", info(t0, 0)), ("PEOPLE", people(t0)),            # events 1, 2
                     ("ROBOT_POSE", pose(t0 + 1, 0.0)),                               # 3 ok
                     ("ROBOT_POSE", pose(t0 + 2, math.nan)),                          # 4 NaN
                     ("ROBOT_POSE", pose(t0 + 1, 0.5)),                               # 5 backwards
                     ("ROBOT_POSE", pose(t0 + age, 1.0)),                             # 6 at the age limit
                     ("ROBOT_POSE", pose(t0 + age + 1000, 2.0))])                     # 7 stale
    eps, warnings = read_episodes(str(p))
    assert len(eps) == 1 and len(eps[0]) == 2
    text = "\n".join(warnings)
    assert f"{p}: event 4 (byte" in text and "pose2d_t.x is not finite" in text
    assert f"{p}: event 5 (byte" in text and "time does not advance" in text
    assert "1 ROBOT_POSE events had no PEOPLE entry of person 3" in text


def test_missing_channels_are_errors(tmp_path):
    t0 = 1_700_000_000_000_000
    p = tmp_path / "nopeople.lcmlog"
    write_events(p, [("DEMO_INFO", info(t0, 0)), ("ROBOT_POSE", pose(t0, 0.0))])
    with pytest.raises(EpisodeError, match="no PEOPLE event"):
        read_episodes(str(p))
    p = tmp_path / "noinfo.lcmlog"
    write_events(p, [("PEOPLE", people(t0)), ("ROBOT_POSE", pose(t0, 0.0))])
    with pytest.raises(EpisodeError, match="no DEMO_INFO event"):
        read_episodes(str(p))
    p = tmp_path / "text.lcmlog"
    p.write_text("hello, not a log\n")
    # Without the LCM sync word the reader takes the file for an episode CSV.
    with pytest.raises(EpisodeError, match="text.lcmlog: line 1: header must be"):
        read_episodes(str(p))


@pytest.mark.parametrize("body,expect", [
    ("a,avoid,left,0.0,0,0,1,1\n", "line 2: 8 columns"),
    ("a,walk,left,0.0,0,0,1,1,0\n", "line 2: unknown task 'walk'"),
    ("a,avoid,up,0.0,0,0,1,1,0\n", "line 2: unknown homotopy 'up'"),
    ("a,avoid,left,0.0,nan,0,1,1,0\n", "line 2: column robot_x = 'nan'"),
    ("a,avoid,left,0.0,0,0,1,1,0\na,avoid,left,0.0,0,0,1,1,0\n", "line 3: time does not increase"),
    ("a,avoid,left,0.0,0,0,1,1,0\nb,avoid,left,0.0,0,0,1,1,0\na,avoid,left,1,0,0,1,1,0\n",
     "line 4: episode 'a' appears again"),
])
def test_csv_errors_name_file_and_line(tmp_path, body, expect):
    p = tmp_path / "bad.csv"
    p.write_text(HEADER + body)
    with pytest.raises(EpisodeError) as exc:
        read_episodes(str(p))
    assert str(p) in str(exc.value) and expect in str(exc.value)
    r = run_convert("csv2log", p, tmp_path / "out.lcmlog")
    assert r.returncode == 1 and expect in r.stderr
    assert not (tmp_path / "out.lcmlog").exists()


def test_read_episodes_dispatches_by_content(tmp_path):
    src = tmp_path / "x.csv"
    sample_csv(src)
    log = tmp_path / "looks_like.csv"
    write_demo_log(str(log), read_episodes(str(src))[0])
    eps, _ = read_episodes(str(log))
    assert len(eps) == 3 and eps[0].id == "looks_like_0000"
    eps, _ = read_episodes(str(src))
    assert eps[0].id == "a_1"


def test_sparse_people_pair_within_the_age_limit(tmp_path):
    """write_demo_log(people_every=k) writes PEOPLE at every k-th sample; readers pair each pose with
    the latest entry, which must carry that sample's person pose."""
    n = 12
    rows = [(0.5 * i, 0.1 * i, 0.0, 0.0, 2.0 + 0.01 * i, 1.0, 0.3) for i in range(n)]
    ep = Episode.from_rows("s", "avoid", "left", rows)
    p = tmp_path / "sparse.lcmlog"
    write_demo_log(str(p), [ep], people_every=4)
    eps, warnings = read_episodes(str(p))
    assert warnings == [] and len(eps[0]) == n
    np.testing.assert_allclose(eps[0].person_x, [2.0 + 0.01 * (4 * (i // 4)) for i in range(n)], atol=1e-12)
    # Too sparse for the limit: poses more than MAX_PERSON_AGE_S after the last entry are dropped.
    slow = Episode.from_rows("s", "avoid", "left", [(2.0 * i, 0.1 * i, 0, 0, 2, 1, 0.3) for i in range(8)])
    write_demo_log(str(p), [slow], people_every=4)
    eps, warnings = read_episodes(str(p))
    assert len(eps[0]) == 6  # ages 0, 2, 4 kept, 6 s dropped, in both groups of four
    assert any("2 ROBOT_POSE events had no PEOPLE entry" in w for w in warnings)
