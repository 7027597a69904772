"""gmmrrt_tools.mixture: the ctypes path the plots use, against the shared model test vectors."""
import math
import os
from pathlib import Path

import numpy as np
import pytest

from gmmrrt_tools import core

DATA = Path(os.environ.get("GMMRRT_TEST_DATA_DIR", Path(__file__).resolve().parents[2] / "data")) / "model_vectors"


@pytest.fixture(scope="module")
def mixture():
    try:
        core.lib()
    except core.CoreNotBuilt as exc:
        pytest.fail(f"libgmmrrt.so not built: {exc}")
    from gmmrrt_tools import mixture as mx
    return mx


@pytest.mark.parametrize("name,kind,dim", [("features_seam", "features", 2), ("xy", "xy", 3), ("generic_d4", "generic", 4)])
def test_density_matches_the_oracle(mixture, name, kind, dim):
    m = mixture.Model(str(DATA / f"{name}.gmm"))
    assert (m.kind, m.dim) == (kind, dim)
    rows = np.loadtxt(DATA / f"{name}.csv", delimiter=",", skiprows=1)
    keep = rows[:, -1] > -600  # exp() of the rest underflows to 0, as it should
    p = m.density(rows[keep, :-1])
    np.testing.assert_allclose(np.log(p), rows[keep, -1], rtol=1e-9, atol=1e-9)


def test_corrupt_model_is_rejected_with_reason(mixture, tmp_path):
    data = bytearray((DATA / "features_seam.gmm").read_bytes())
    data[40] ^= 0xFF
    bad = tmp_path / "bad.gmm"
    bad.write_bytes(bytes(data))
    with pytest.raises(ValueError, match="not a valid model"):
        mixture.Model(str(bad))


def test_person_frame_grid_uses_the_features(mixture):
    m = mixture.Model(str(DATA / "features_seam.gmm"))
    xs, ys = np.array([1.0, -2.0]), np.array([0.5])
    grid = m.density_person_frame(xs, ys)
    d0, t0 = math.hypot(1.0, 0.5), math.atan2(0.5, 1.0)
    d1, t1 = math.hypot(-2.0, 0.5), math.atan2(0.5, -2.0)
    np.testing.assert_allclose(grid[0], m.density([[d0, t0], [d1, t1]]), rtol=1e-12)
