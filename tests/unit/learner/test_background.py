"""learner.background: `gmmrrt-learn fit --background straight` fits the task model's background
(learner/include/gmmrrt_learner/background.hpp: each episode's straight line start-goal, as many
points as the episode) and stores it in the model file's background section (model.h), which
`gmmrrt-plan --task-cost background` then uses without --background-model.

Oracle: the same straight-line points built here and written as a features CSV (features by the C
core, gmmrrt_tools.core), fitted by `fit --features-csv` with the same K and seed, must give the
same mixture as the file's background (same points in the same order and the same EM: agreement
to 1e-9, leaving room for the last bits of a different summation order). Refusals: --background
with --kind xy or a features CSV (usage error, no file); a plan asking for the background cost of
a file without one (exit 1, the message says how to get one).
"""
import math
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

from gmmrrt_tools import core

REPO = Path(__file__).resolve().parents[3]
BIN = Path(os.environ.get("GMMRRT_BIN_DIR", REPO / "build" / "bin"))
LEARN, PLAN = BIN / "gmmrrt-learn", BIN / "gmmrrt-plan"
PERSON = (0.0, 0.0, math.pi)  # facing the walkers, who come from the left


def episodes():
    """Walkers from x = -3 to x = 3 at lateral offsets y0, swerving away from the person at the origin
    (a bump of 0.8 m that fades with the offset), 31 samples each."""
    out = []
    for k, y0 in enumerate(np.linspace(-1.5, 1.5, 12)):
        s = np.linspace(0.0, 1.0, 31)
        x = -3.0 + 6.0 * s
        bump = 0.8 * math.copysign(1.0, y0 if y0 != 0 else 1.0) * math.exp(-abs(y0)) * np.sin(math.pi * s) ** 2
        y = y0 + bump + 0.02 * k * s  # ends differ a little, so no two lines are the same
        out.append((f"ep{k:02d}", "left" if y0 >= 0 else "right", np.column_stack([x, y])))
    return out


def run(*args):
    for tool in (LEARN, PLAN):
        if not tool.is_file():
            pytest.fail(f"{tool} missing: build first (tools/run build)")
    return subprocess.run([str(a) for a in args], capture_output=True, text=True)


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    d = tmp_path_factory.mktemp("bg")
    rows = ["episode_id,task,homotopy,t,robot_x,robot_y,person_x,person_y,person_yaw"]
    lines = []
    for eid, hom, xy in episodes():
        for i, (x, y) in enumerate(xy):
            rows.append(f"{eid},avoid,{hom},{0.1 * i:.1f},{x!r},{y!r},{PERSON[0]!r},{PERSON[1]!r},{PERSON[2]!r}")
        # The learner's straight line: start + u (end - start), u = i / (n - 1), the same operations.
        n = len(xy)
        (ax, ay), (bx, by) = xy[0], xy[-1]
        dx, dy = bx - ax, by - ay
        for i in range(n):
            u = i / (n - 1)
            lines.append(core.features_from_xy(PERSON, ax + u * dx, ay + u * dy))
    csv = d / "episodes.csv"
    csv.write_text("\n".join(rows) + "\n")
    feats = d / "straight.csv"
    feats.write_text("".join(f"{a!r},{b!r}\n" for a, b in lines))
    return d, csv, feats


def test_background_is_the_mixture_of_the_straight_lines(data):
    d, csv, feats = data
    out, oracle = d / "with_bg.gmm", d / "oracle.gmm"
    r = run(LEARN, "fit", "-i", csv, "-t", "avoid", "--k", "3", "--seed", "4", "--quiet", "--background", "straight",
            "-o", out)
    assert r.returncode == 0, r.stderr
    r = run(LEARN, "fit", "--features-csv", feats, "--angle-dims", "2", "--k", "3", "--seed", "4", "--quiet",
            "-o", oracle)
    assert r.returncode == 0, r.stderr
    data_bytes = out.read_bytes()
    bg = core.model_background(data_bytes)
    assert bg is not None
    got, want = core.model_fields(bg), core.model_fields(core.decode_model(oracle.read_bytes()))
    task = core.model_fields(core.decode_model(data_bytes))
    assert (got["kind"], got["task"], got["dim"], got["angle_mask"]) == (task["kind"], task["task"], 2, 0b10)
    assert got["delta"] == task["delta"]  # the cost reads the task model's delta; the background carries the same
    assert got["k"] == want["k"] == 3
    for key in ("weights", "means", "chols"):
        assert np.allclose(np.asarray(got[key]), np.asarray(want[key]), rtol=1e-9, atol=1e-9), key
    # It is not the task model: the swerves are not on the straight lines.
    assert not np.allclose(np.asarray(got["means"]), np.asarray(task["means"]), atol=0.05)
    # Without --background the same fit has no section, and the task model's bytes are the same.
    plain = d / "plain.gmm"
    r = run(LEARN, "fit", "-i", csv, "-t", "avoid", "--k", "3", "--seed", "4", "--quiet", "--no-provenance",
            "-o", plain)
    assert r.returncode == 0, r.stderr
    assert core.model_background(plain.read_bytes()) is None
    size = len(plain.read_bytes())
    assert data_bytes[:size] == plain.read_bytes()
    # inspect says which file has one
    assert "background K = 3" in run(LEARN, "inspect", out).stdout
    assert "background none" in run(LEARN, "inspect", plain).stdout
    assert '"background_k": 3' in run(LEARN, "inspect", "--json", out).stdout


def test_plan_uses_the_files_background_and_says_when_there_is_none(data):
    d, csv, _ = data
    with_bg, plain = d / "plan_bg.gmm", d / "plan_plain.gmm"
    for out, extra in ((with_bg, ("--background", "straight")), (plain, ())):
        r = run(LEARN, "fit", "-i", csv, "-t", "avoid", "--k", "3", "--seed", "4", "--quiet", *extra, "-o", out)
        assert r.returncode == 0, r.stderr
    args = ("--start", "-3,0.3", "--goal", "3,0.3", "--person", "0,0,3.14159", "--iterations", "300", "--json",
            "--task-cost", "background")
    r = run(PLAN, "--model", with_bg, *args)
    assert r.returncode == 0, r.stderr
    assert '"status": "ok"' in r.stdout
    # --background-model overrides the file's own: the same background given explicitly plans the same path.
    r2 = run(PLAN, "--model", with_bg, "--background-model", with_bg, *args)
    assert r2.returncode == 0, r2.stderr
    r = run(PLAN, "--model", plain, *args)
    assert r.returncode == 1
    assert "background model" in r.stderr and "--background straight" in r.stderr


@pytest.mark.parametrize("extra", [("--kind", "xy"), ()])
def test_background_needs_episode_features(data, extra):
    d, csv, feats = data
    out = d / "refused.gmm"
    src = ("-i", csv, "-t", "avoid") if extra else ("--features-csv", feats)
    r = run(LEARN, "fit", *src, *extra, "--k", "2", "--quiet", "--background", "straight", "-o", out)
    assert r.returncode == 2
    assert "--background straight needs episodes" in r.stderr
    assert not out.exists()
    r = run(LEARN, "fit", "-i", csv, "-t", "avoid", "--k", "2", "--quiet", "--background", "sideways", "-o", out)
    assert r.returncode == 2 and "--background 'sideways'" in r.stderr
    assert not out.exists()
