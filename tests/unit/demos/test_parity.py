"""The Python demonstration reader (tools/gmmrrt_tools/demolog.py, episodes.py) against the
learner's C++ reader (learner/src/demo_io.cpp, through the test helper demos_dump_episodes): same
samples to the last bit, same labels, same number of warnings, errors in the same cases with the
same text, on logs/demos, on damaged copies of one of them, and on CSVs."""
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

from gmmrrt_tools.demolog import read_episodes
from gmmrrt_tools.episodes import HOMOTOPIES, TASKS, EpisodeError

REPO = Path(__file__).resolve().parents[3]
BUILD = Path(os.environ.get("GMMRRT_BUILD_DIR", REPO / "build"))
DUMP = BUILD / "tests" / "demos_dump_episodes"


def cpp_read(path):
    if not DUMP.is_file():
        pytest.fail(f"{DUMP} is missing: build the tests (tools/run build)")
    r = subprocess.run([str(DUMP), str(path)], capture_output=True, text=True)
    lines = r.stdout.splitlines()
    if lines[0].startswith("error\t"):
        return None, lines[0].split("\t", 1)[1], None
    warnings = int(lines[1].split("\t")[1])
    rows = [l.split(",") for l in lines[2:]]
    return rows, None, warnings


def py_read(path):
    try:
        eps, warnings = read_episodes(str(path))
    except EpisodeError as e:
        return None, str(e), None
    rows = []
    for e in eps:
        for i in range(len(e)):
            rows.append([e.id, str(TASKS[e.task]), str(HOMOTOPIES[e.homotopy])] +
                        [getattr(e, n)[i] for n in ("t", "robot_x", "robot_y", "robot_yaw", "person_x",
                                                    "person_y", "person_yaw")])
    return rows, None, len(warnings)


def assert_same(path):
    c_rows, c_err, c_warn = cpp_read(path)
    p_rows, p_err, p_warn = py_read(path)
    assert c_err == p_err, f"{path}: C++ error {c_err!r}, Python error {p_err!r}"
    if c_err is not None:
        return
    assert c_warn == p_warn
    assert len(c_rows) == len(p_rows)
    for c, p in zip(c_rows, p_rows):
        assert c[:3] == p[:3]
        cv = np.array([float(v) for v in c[3:]])
        pv = np.array(p[3:], dtype=float)
        # t: C++ and Python both compute (utime difference) * 1e-6; positions are copied.
        np.testing.assert_array_equal(np.isnan(cv), np.isnan(pv))
        np.testing.assert_allclose(cv[~np.isnan(cv)], pv[~np.isnan(pv)], rtol=0, atol=1e-12)


@pytest.mark.parametrize("name", ["avoid_left", "avoid_right", "approach_frontal", "approach_left",
                                  "approach_right"])
def test_repository_logs_read_the_same(name):
    assert_same(REPO / "logs" / "demos" / f"{name}.lcmlog")


def test_damaged_logs_read_the_same(tmp_path):
    data = (REPO / "logs" / "demos" / "approach_frontal.lcmlog").read_bytes()
    p = tmp_path / "damaged.lcmlog"
    rng = np.random.default_rng(7)
    for n in sorted(rng.choice(len(data), size=40, replace=False)):  # truncations
        p.write_bytes(data[:n])
        assert_same(p)
    for i in sorted(rng.choice(len(data), size=120, replace=False)):  # byte flips
        bad = bytearray(data)
        bad[i] ^= 0x5A
        p.write_bytes(bytes(bad))
        assert_same(p)


def test_csvs_read_the_same(tmp_path):
    p = tmp_path / "e.csv"
    p.write_text("episode_id,task,homotopy,t,robot_x,robot_y,person_x,person_y,person_yaw\n"
                 "a,avoid,left,0,0,0,1,1,0\na,avoid,left,0.1,0.005,0,1,1,0\na,avoid,left,0.2,0.02,0.01,1,1,0\n"
                 "b,approach,right,0,3,3,0,0,1\n")
    assert_same(p)
    p.write_text("episode_id,task,homotopy,t,robot_x,robot_y,person_x,person_y,person_yaw\n"
                 "a,avoid,left,0,0,0,1,1,0\na,avoid,left,0.1,0.005,0,1,1\n")
    assert_same(p)
    real = Path(os.environ.get("GMMRRT_REAL_DATA", "")) / "ucy_approach_episodes.csv"
    if real.is_file():
        assert_same(real)
