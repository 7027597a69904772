"""learner.plot: `gmmrrt-learn plot MODEL -o IMAGE` (learner/cli/cmd_plot.cpp, the renderer
learner/cli/plot_render.py run by the system's python3 with Debian's matplotlib).

- a (d, theta) model is drawn in the person's frame and a generic 2-D model in its own coordinates,
  with the training points: the image is a PNG (an SVG holds the title). The numbers handed to the
  renderer are checked against independent paths through the C core: the density on the grid
  against GaussianMixture.score_samples (gmmrrt_gmm_log_density, 1e-12 relative: the batch kernel
  and the scalar one differ in the last bits of exp), the grid points' features against
  core.features_from_xy, the contours against core.features_to_xy of mu + L (cos a, sin a);
- a 3-D model, a corrupt model, a points file of the wrong width are refused naming the file, and
  no image appears; an interpreter without matplotlib is named with the Debian package to install.
"""
import json
import math
import os
import stat
import subprocess
from pathlib import Path

import numpy as np
import pytest

from gmmrrt_tools import core
from gmmrrt_tools.learn import GaussianMixture

BIN = Path(os.environ.get("GMMRRT_BIN_DIR", "build/bin")) / "gmmrrt-learn"
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def plot(*args, env=None):
    return subprocess.run([str(BIN), "plot", *map(str, args)], capture_output=True, text=True, timeout=300,
                          env=dict(os.environ, **(env or {})))


def spy(tmp_path):
    """An interpreter wrapper that keeps a copy of the data file the renderer gets, then renders."""
    keep = tmp_path / "data.json"
    w = tmp_path / "spy-python3"
    w.write_text(f'#!/bin/sh\ncp "$2" "{keep}"\nexec /usr/bin/python3 "$@"\n')
    w.chmod(w.stat().st_mode | stat.S_IXUSR)
    return {"GMMRRT_PYTHON3": str(w)}, keep


@pytest.fixture
def features_model(tmp_path):
    """A (d, theta) model as fit learns it from demonstrations: passes on the person's left."""
    rng = np.random.default_rng(4)
    rows, feats = ["episode_id,task,homotopy,t,robot_x,robot_y,person_x,person_y,person_yaw"], []
    for e in range(20):
        y = 1.0 + 0.4 * rng.random()
        for i, x in enumerate(np.linspace(-3, 3, 40)):
            rows.append(f"e{e},avoid,left,{0.1 * i:.1f},{x!r},{y!r},0,0,0")
            feats.append(core.features_from_xy((0.0, 0.0, 0.0), x, y))
    episodes = tmp_path / "eps.csv"
    episodes.write_text("\n".join(rows) + "\n")
    pts = tmp_path / "f.csv"
    np.savetxt(pts, np.array(feats), delimiter=",", header="d,theta", comments="", fmt="%.17g")
    model = tmp_path / "f.gmm"
    r = subprocess.run([str(BIN), "fit", "--input", str(episodes), "--task", "avoid", "--k", "3", "--delta", "0.001",
                        "-o", str(model), "-q"], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    return model, pts


def test_generic_model_is_drawn_in_its_coordinates_with_the_core_density(tmp_path):
    rng = np.random.default_rng(7)
    x = np.vstack([rng.normal([0, 0], 0.5, (600, 2)), rng.normal([4, 2], [0.3, 0.8], (600, 2))])
    gm = GaussianMixture(n_components=2, random_state=1).fit(x)
    model = tmp_path / "g.gmm"
    gm.save(model)
    pts = tmp_path / "g.csv"
    np.savetxt(pts, x, delimiter=",", header="a,b", comments="")
    env, keep = spy(tmp_path)
    png = tmp_path / "g.png"
    r = plot(model, "-o", png, "--points", pts, env=env)
    assert r.returncode == 0, r.stderr
    assert png.read_bytes()[:8] == PNG_MAGIC
    d = json.loads(keep.read_text())
    assert d["person_frame"] is False and len(d["grid_x"]) == len(d["grid_y"]) == 161
    gx, gy = np.meshgrid(d["grid_x"], d["grid_y"])
    want = np.exp(gm.score_samples(np.column_stack([gx.ravel(), gy.ravel()]))).reshape(gx.shape)
    np.testing.assert_allclose(np.array(d["density"]), want, rtol=1e-12, atol=0)
    np.testing.assert_array_equal(np.array(d["points"]), x)
    a = 2 * math.pi * np.arange(73) / 72
    for i, line in enumerate(d["contours"]):
        L = np.linalg.cholesky(gm.covariances_[i])
        np.testing.assert_allclose(np.array(line), gm.means_[i] + (L @ np.stack([np.cos(a), np.sin(a)])).T,
                                   rtol=1e-9, atol=1e-12)
    # The view covers every contour.
    allc = np.vstack(d["contours"])
    assert d["grid_x"][0] < allc[:, 0].min() and d["grid_x"][-1] > allc[:, 0].max()


def test_features_model_is_drawn_in_the_person_frame(tmp_path, features_model):
    model, pts = features_model
    gm = GaussianMixture.load(model)
    env, keep = spy(tmp_path)
    svg = tmp_path / "f.svg"
    r = plot(model, "-o", svg, "--points", pts, "--extent", 4, env=env)
    assert r.returncode == 0, r.stderr
    assert "<svg" in svg.read_text()[:2000] and "f.gmm: K = 3" in svg.read_text()
    d = json.loads(keep.read_text())
    assert d["person_frame"] is True and d["grid_x"][0] == -4 and d["grid_y"][-1] == 4
    gx, gy = np.meshgrid(d["grid_x"], d["grid_y"])
    f = np.array([core.features_from_xy((0.0, 0.0, 0.0), px, py) for px, py in zip(gx.ravel(), gy.ravel())])
    np.testing.assert_allclose(np.array(d["density"]).ravel(), np.exp(gm.score_samples(f)), rtol=1e-12, atol=0)
    a = 2 * math.pi * np.arange(73) / 72
    for i, line in enumerate(d["contours"]):
        L = np.linalg.cholesky(gm.covariances_[i])
        fc = gm.means_[i] + (L @ np.stack([np.cos(a), np.sin(a)])).T
        want = [core.features_to_xy((0.0, 0.0, 0.0), dd, tt) for dd, tt in fc]
        np.testing.assert_allclose(np.array(line), want, rtol=1e-9, atol=1e-12)
    # The left pass's mass is on the person's left (y' > 0).
    dens = np.array(d["density"])
    assert dens[gy > 0].sum() > 5 * dens[gy < 0].sum()
    # The default view: from the components (1.2 x the farthest d + 2 sigma_d), within [1, 8] m.
    png = tmp_path / "f.png"
    env2, keep2 = spy(tmp_path)
    assert plot(model, "-o", png, env=env2).returncode == 0
    half = json.loads(keep2.read_text())["grid_x"][-1]
    assert 1.0 <= half <= 8.0 and png.read_bytes()[:8] == PNG_MAGIC


def test_bad_models_points_and_a_missing_matplotlib_are_named(tmp_path, features_model):
    model, pts = features_model
    m3 = tmp_path / "m3.gmm"
    GaussianMixture(n_components=2, random_state=1).fit(np.random.default_rng(0).normal(size=(500, 3))).save(m3)
    out = tmp_path / "x.png"
    r = plot(m3, "-o", out)
    assert r.returncode == 1 and "m3.gmm: D = 3; only D = 2" in r.stderr and not out.exists()
    bad = tmp_path / "bad.gmm"
    raw = bytearray(model.read_bytes())
    raw[40] ^= 1
    bad.write_bytes(bytes(raw))
    r = plot(bad, "-o", out)
    assert r.returncode == 1 and "bad.gmm" in r.stderr and not out.exists()
    wide = tmp_path / "wide.csv"
    np.savetxt(wide, np.ones((5, 3)), delimiter=",")
    r = plot(model, "-o", out, "--points", wide)
    assert r.returncode == 1 and "wide.csv: 3 columns" in r.stderr and not out.exists()
    r = plot(model, "-o", out, "--extent", "-1")
    assert r.returncode == 2 and "--extent" in r.stderr
    # An interpreter without matplotlib (-S: no site packages, so no Debian dist-packages).
    nompl = tmp_path / "bare-python3"
    nompl.write_text('#!/bin/sh\nexec /usr/bin/python3 -S "$@"\n')
    nompl.chmod(0o755)
    r = plot(model, "-o", out, env={"GMMRRT_PYTHON3": str(nompl)})
    assert r.returncode == 1 and "apt-get install python3-matplotlib" in r.stderr and not out.exists()
    r = plot(model, "-o", out, env={"GMMRRT_PYTHON3": str(tmp_path / "no-such-python")})
    assert r.returncode == 1 and "no-such-python" in r.stderr and not out.exists()
    # A folder that cannot take the image: the renderer's reason, no stray temporary file.
    r = plot(model, "-o", tmp_path / "no-such-dir" / "x.png")
    assert r.returncode == 1 and "no-such-dir" in r.stderr
    assert not list(tmp_path.glob("gmmrrt-plot-*")) and not list(tmp_path.glob(".plot-*"))
