"""learner.python_module: gmmrrt_tools.learn.GaussianMixture (ctypes over libgmmrrt_learn.so)
against scikit-learn, on data where both find the same optimum:
  - fit: mean log-likelihood per point at least scikit-learn's (n_init 1, its defaults) minus 1e-3;
  - score_samples of our mixture equals scikit-learn's score_samples of the same parameters
    (1e-9 relative: two implementations of the same density, last-bit differences of exp/log);
  - bic equals scikit-learn's bic of the same parameters (1e-9 relative) and equals the learner's;
  - save/load round trip through the gmmrrt-learn file format (gmmrrt-learn inspect reads it);
    a corrupt file raises; sampling reproduces weights and means (statistical tolerance);
  - same seed, same model; any thread count, same model.
"""
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest
from sklearn.mixture import GaussianMixture as SkGM

from gmmrrt_tools.learn import GaussianMixture  # tools/ on PYTHONPATH

BIN = Path(os.environ.get("GMMRRT_BIN_DIR", "build/bin")) / "gmmrrt-learn"


def data(seed=3, n=6000):
    rng = np.random.default_rng(seed)
    means = np.array([[0.0, 0.0], [5.0, 1.0], [1.0, 6.0], [6.0, 6.0]])
    covs = np.array([[[1.0, 0.3], [0.3, 0.5]], [[0.4, 0.0], [0.0, 0.9]], [[0.6, -0.2], [-0.2, 0.6]],
                     [[0.3, 0.1], [0.1, 0.3]]])
    z = rng.choice(4, n, p=[0.4, 0.25, 0.2, 0.15])
    return means[z] + np.einsum("nij,nj->ni", np.linalg.cholesky(covs)[z], rng.normal(size=(n, 2)))


def sk_with(params: GaussianMixture) -> SkGM:
    sk = SkGM(len(params.weights_), covariance_type="full")
    sk.weights_, sk.means_, sk.covariances_ = params.weights_, params.means_, params.covariances_
    chol = np.linalg.cholesky(params.covariances_)
    sk.precisions_cholesky_ = np.array([np.linalg.inv(c).T for c in chol])
    sk.precisions_ = sk.precisions_cholesky_ @ sk.precisions_cholesky_.transpose(0, 2, 1)
    return sk


def test_fit_score_bic_against_sklearn():
    x = data()
    gm = GaussianMixture(n_components=4, random_state=1).fit(x)
    assert gm.converged_ and gm.weights_.shape == (4,) and gm.covariances_.shape == (4, 2, 2)
    sk = SkGM(4, covariance_type="full", random_state=0).fit(x)
    assert gm.score(x) >= sk.score(x) - 1e-3
    assert abs(gm.lower_bound_ - gm.score(x)) < 1e-9
    same = sk_with(gm)
    np.testing.assert_allclose(gm.score_samples(x), same.score_samples(x), rtol=1e-9)
    assert gm.bic(x) == pytest.approx(same.bic(x), rel=1e-9)


def test_save_load_sample_and_determinism(tmp_path):
    x = data(5)
    gm = GaussianMixture(n_components=4, random_state=2, n_threads=1).fit(x)
    path = tmp_path / "m.gmm"
    gm.save(path)
    r = subprocess.run([str(BIN), "inspect", str(path)], capture_output=True, text=True)
    assert r.returncode == 0 and "K        4" in r.stdout, r.stderr
    back = GaussianMixture.load(path)
    np.testing.assert_array_equal(back.weights_, gm.weights_)
    np.testing.assert_array_equal(back.score_samples(x[:100]), gm.score_samples(x[:100]))
    again = GaussianMixture(n_components=4, random_state=2, n_threads=2).fit(x)
    np.testing.assert_array_equal(again.means_, gm.means_)  # same seed, any thread count: same bits
    s, labels = gm.sample(40000, random_state=7)
    freq = np.bincount(labels, minlength=4) / len(labels)
    np.testing.assert_allclose(freq, gm.weights_, atol=0.01)  # 5 sigma of a binomial at n = 40 000
    for i in range(4):
        np.testing.assert_allclose(s[labels == i].mean(axis=0), gm.means_[i], atol=0.05)
    data_bytes = bytearray(path.read_bytes())
    data_bytes[40] ^= 1
    bad = tmp_path / "bad.gmm"
    bad.write_bytes(bytes(data_bytes))
    with pytest.raises(ValueError):
        GaussianMixture.load(bad)


def test_bad_input_raises_with_the_reason():
    with pytest.raises(ValueError, match="need at least"):
        GaussianMixture(n_components=4).fit(np.arange(10.0).reshape(5, 2))
    with pytest.raises(ValueError, match="not finite"):
        GaussianMixture(n_components=1).fit(np.array([[0.0, 1.0], [np.nan, 2.0], [1.0, 0.0], [2.0, 3.0]]))
    with pytest.raises(RuntimeError):
        GaussianMixture().score_samples(np.zeros((1, 2)))
