"""learner.real_data: avoid models from the UPO train split, judged on the test split.

Needs GMMRRT_REAL_DATA (../shared/data/real); skips with the reason when it is absent. Small
K and iteration caps keep it quick; the K = 19 figures of docs/learner.md come from the
commands listed there. Checks that can fail: a mixture beats a single Gaussian on held-out
data, and a side-specific model explains its own side's test episodes better than the
other side's model does.
"""
import os
import subprocess
from pathlib import Path

import pytest

BIN = Path(os.environ.get("GMMRRT_BIN_DIR", "build/bin")) / "gmmrrt-learn"
REAL = Path(os.environ.get("GMMRRT_REAL_DATA", "../shared/data/real"))
EPISODES = REAL / "upo_avoid_episodes.csv"
INDEX = REAL / "upo_avoid_index.csv"

pytestmark = pytest.mark.skipif(not (EPISODES.exists() and INDEX.exists()),
                                reason=f"real data not found at {REAL} (set GMMRRT_REAL_DATA)")


def run(*args):
    r = subprocess.run([str(BIN), *map(str, args)], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    return r.stdout


def fit(out, homotopy, k):
    run("fit", "--input", EPISODES, "--task", "avoid", "--homotopy", homotopy, "--index", INDEX,
        "--split", "train", "--k", k, "--max-iter", 60, "--restarts", 2, "-q", "-o", out)


def score(model, homotopy):
    out = run("score", model, "--input", EPISODES, "--index", INDEX, "--split", "test",
              "--homotopy", homotopy, "-q")
    return float(out.split()[1])


@pytest.fixture(scope="module")
def models(tmp_path_factory):
    d = tmp_path_factory.mktemp("upo")
    m = {}
    for name, homotopy, k in (("left", "left", 6), ("right", "right", 6), ("single", "left", 1)):
        m[name] = d / f"{name}.gmm"
        fit(m[name], homotopy, k)
    return m


def test_mixture_beats_a_single_gaussian_on_test_episodes(models):
    assert score(models["left"], "left") > score(models["single"], "left") + 0.1


def test_side_models_prefer_their_own_side(models):
    assert score(models["left"], "left") > score(models["right"], "left") + 0.1
    assert score(models["right"], "right") > score(models["left"], "right") + 0.1


def test_model_header_records_task_and_side(models):
    out = run("inspect", models["right"])
    assert "task     avoid" in out and "homotopy right" in out and "kind     features" in out
