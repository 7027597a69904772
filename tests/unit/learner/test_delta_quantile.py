"""learner.delta_quantile: `gmmrrt-learn fit --delta-quantile Q` (default Q = 0.25) stores as the model's delta the
Q-quantile of the fitted density over the training points (learner/src/delta_quantile.cpp; the task
cost c = delta / max(p, delta) of paper Sect. 4).

Checked against an independent computation: the model file's mixture evaluated by the C core
(gmmrrt_tools.mixture, not the learner's Eigen code) on the same points, and numpy's quantile. Bad
values and --delta together with --delta-quantile are refused with a clear error and no file.
"""
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

from gmmrrt_tools import core, mixture

REPO = Path(__file__).resolve().parents[3]
LEARN = Path(os.environ.get("GMMRRT_BIN_DIR", REPO / "build" / "bin")) / "gmmrrt-learn"


def stored_delta(path):
    return core.model_fields(core.decode_model(Path(path).read_bytes()))["delta"]


@pytest.fixture(scope="module")
def points(tmp_path_factory):
    rng = np.random.default_rng(5)
    d = np.concatenate([rng.normal(1.2, 0.2, 300), rng.normal(2.0, 0.3, 200)])
    th = np.concatenate([rng.normal(1.0, 0.3, 300), rng.normal(-2.5, 0.4, 200)])
    th = np.array([core.wrap_angle(a) for a in th])
    csv = tmp_path_factory.mktemp("dq") / "features.csv"
    np.savetxt(csv, np.column_stack([d, th]), delimiter=",", fmt="%.9f")
    return csv, np.column_stack([d, th])


def fit(csv, out, *extra):
    if not LEARN.is_file():
        pytest.fail(f"{LEARN} missing: build the learner (tools/run build)")
    return subprocess.run([str(LEARN), "fit", "--features-csv", str(csv), "--angle-dims", "2", "--k", "3",
                           "--seed", "2", "--quiet", "-o", str(out), *extra], capture_output=True, text=True)


@pytest.mark.parametrize("q", [0.05, 0.5, 1.0])
def test_stored_delta_is_the_density_quantile(points, tmp_path, q):
    csv, pts = points
    out = tmp_path / "m.gmm"
    r = fit(csv, out, "--delta-quantile", str(q))
    assert r.returncode == 0, r.stderr
    dens = mixture.Model(str(out)).density(np.loadtxt(csv, delimiter=","))
    expect = float(np.quantile(dens, q))
    assert stored_delta(out) == pytest.approx(expect, rel=1e-9)
    assert stored_delta(out) != pytest.approx(0.001)


def test_default_is_the_quartile_and_delta_fixes_it(points, tmp_path):
    """No option: the 0.25-quantile (the product default); --delta 0.001: the paper's fixed delta."""
    csv, _ = points
    out = tmp_path / "m.gmm"
    assert fit(csv, out).returncode == 0
    dens = mixture.Model(str(out)).density(np.loadtxt(csv, delimiter=","))
    assert stored_delta(out) == pytest.approx(float(np.quantile(dens, 0.25)), rel=1e-9)
    assert fit(csv, out, "--delta", "0.001").returncode == 0
    assert stored_delta(out) == 0.001


@pytest.mark.parametrize("extra, message", [
    (["--delta-quantile", "1.5"], "--delta-quantile"),
    (["--delta-quantile", "-0.1"], "--delta-quantile"),
    (["--delta-quantile", "nan"], "--delta-quantile"),
    (["--delta-quantile", "0.5", "--delta", "0.01"], "not both"),
])
def test_bad_quantile_is_refused(points, tmp_path, extra, message):
    out = tmp_path / "m.gmm"
    r = fit(points[0], out, *extra)
    assert r.returncode != 0
    assert message in r.stderr
    assert not out.exists()
