"""tools/synth_demonstrations.py: deterministic from the seed (and logs/demos/ is what the documented command
makes), 9 demonstrations per task and homotopy with the asked homotopy, bounded speed, passing and
final distances inside the documented ranges. Features come from the C core (gmmrrt_tools.core)."""
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from gmmrrt_tools import core
from gmmrrt_tools.episodes import read_episodes

REPO = Path(__file__).resolve().parents[3]
SYNTH = REPO / "tools" / "synth_demonstrations.py"
FILES = {"avoid_left": ("avoid", "left"), "avoid_right": ("avoid", "right"),
         "approach_frontal": ("approach", "frontal"), "approach_left": ("approach", "left"),
         "approach_right": ("approach", "right")}


def synth(out: Path, seed: int):
    r = subprocess.run([sys.executable, str(SYNTH), "--seed", str(seed), "--out-dir", str(out)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr


@pytest.fixture(scope="module")
def seed1(tmp_path_factory):
    out = tmp_path_factory.mktemp("seed1")
    synth(out, 1)
    return out


def test_same_seed_same_bytes_and_repo_logs_are_that_output(seed1, tmp_path):
    synth(tmp_path, 1)
    for name in FILES:
        a = (seed1 / f"{name}.lcmlog").read_bytes()
        assert a == (tmp_path / f"{name}.lcmlog").read_bytes(), name
        assert a == (REPO / "logs" / "demos" / f"{name}.lcmlog").read_bytes(), \
            f"logs/demos/{name}.lcmlog is not what `synth_demonstrations.py --seed 1` makes: regenerate it"
    total = sum(p.stat().st_size for p in (REPO / "logs" / "demos").glob("*"))
    assert total < 700_000, f"logs/demos/ holds {total} bytes"


def test_other_seed_other_demonstrations(seed1, tmp_path):
    synth(tmp_path, 2)
    assert (seed1 / "avoid_left.lcmlog").read_bytes() != (tmp_path / "avoid_left.lcmlog").read_bytes()


def person_frame(ep):
    d, th = [], []
    for i in range(len(ep)):
        di, ti = core.features_from_xy((ep.person_x[i], ep.person_y[i], ep.person_yaw[i]), ep.robot_x[i],
                                       ep.robot_y[i])
        d.append(di)
        th.append(ti)
    return np.array(d), np.array(th)


@pytest.mark.parametrize("name", sorted(FILES))
def test_demonstrations_have_the_asked_shape(seed1, name):
    task, homotopy = FILES[name]
    eps, warnings = read_episodes(str(seed1 / f"{name}.lcmlog"))
    assert warnings == []
    assert len(eps) == 9
    for ep in eps:
        assert (ep.task, ep.homotopy) == (task, homotopy)
        d, th = person_frame(ep)
        dt = np.diff(ep.t)
        speed = np.hypot(np.diff(ep.robot_x), np.diff(ep.robot_y)) / dt
        assert np.all(dt > 0)
        assert speed.max() < 0.65 + 0.05, f"{ep.id}: speed {speed.max():.2f} m/s"  # V_MAX + noise
        assert d.min() > 0.45, f"{ep.id}: {d.min():.2f} m from the person"
        k = int(np.argmin(d))
        if task == "avoid":
            assert 0.6 < d.min() < 2.6  # UPO d_min deciles span 0.63..2.46 m
            assert (th[k] > 0) == (homotopy == "left"), f"{ep.id}: passes on the wrong side"
        else:
            assert 0.45 < d[-1] < 2.1, f"{ep.id}: stops {d[-1]:.2f} m away"
            assert abs(th[-1]) < math.radians(60), f"{ep.id}: stops beside or behind the person"
            if homotopy == "frontal":
                assert abs(th[0]) < math.pi / 2
            else:
                assert abs(th[0]) > math.radians(110), f"{ep.id}: does not start behind the person"
                abeam = np.abs(np.abs(th) - math.pi / 2) < math.radians(20)
                assert abeam.any() and np.all((th[abeam] > 0) == (homotopy == "left"))


def test_bad_arguments_exit_nonzero(tmp_path):
    r = subprocess.run([sys.executable, str(SYNTH), "--count", "0", "--out-dir", str(tmp_path)],
                       capture_output=True, text=True)
    assert r.returncode == 2 and "--count" in r.stderr
    blocker = tmp_path / "file"
    blocker.write_text("x")
    r = subprocess.run([sys.executable, str(SYNTH), "--out-dir", str(blocker / "sub")], capture_output=True,
                       text=True)
    assert r.returncode == 1 and "cannot create" in r.stderr


def test_from_behind_approaches_straddle_the_seam(seed1):
    """Some from-behind approaches start across theta = +-pi from the side they curve round, so the
    learner's wrapped model sees data on both sides of the seam (docs/demonstrations.md)."""
    for name, sign in (("approach_left", 1.0), ("approach_right", -1.0)):
        eps, _ = read_episodes(str(seed1 / f"{name}.lcmlog"))
        starts = [person_frame(e)[1][0] for e in eps]
        assert any(sign * t < 0 for t in starts), f"{name}: no start across the seam"
        assert any(sign * t > 0 for t in starts), f"{name}: every start across the seam"
