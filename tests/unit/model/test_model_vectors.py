"""planner.model_vectors: the shared test vectors are current, and the Python encoder/oracle
of tools/gen_model_vectors.py agrees with the C core (build/lib/libgmmrrt.so via ctypes).

- `gen_model_vectors.py --check`: the checked-in files are what the script makes, every header
  field exactly and every number within gmmrrt_tools.model_vectors.CHECK_RTOL (other BLAS kernels change the
  last bits; tools/run test runs this file again under a second OpenBLAS kernel); a copy
  changed by 1e-9 relative in one value, or in one header byte, fails the check.
- Every vector file decodes in C and re-encodes to the same bytes (both byte layouts agree).
- Random models for every D in 1..8 with random angle dimensions (up to 3^A images),
  encoded in Python: the C log-density matches the numpy/scipy oracle.
"""
import ctypes
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[3]
from gmmrrt_tools import model_vectors as gmv  # noqa: E402  (the independent oracle)

VECTORS = REPO / "tests" / "data" / "model_vectors"
MODEL_BYTES = 1 << 20  # more than sizeof(gmmrrt_model_t) for any limits.h


@pytest.fixture(scope="module")
def core():
    build = Path(os.environ.get("GMMRRT_BUILD_DIR", REPO / "build"))
    path = build / "lib" / "libgmmrrt.so"
    if not path.is_file():
        pytest.fail("%s not found: build first (tools/run build)" % path)
    lib = ctypes.CDLL(str(path))
    lib.gmmrrt_model_decode.argtypes = [ctypes.c_char_p, ctypes.c_size_t, ctypes.c_void_p,
                                        ctypes.c_char_p, ctypes.c_size_t]
    lib.gmmrrt_model_decode.restype = ctypes.c_int
    lib.gmmrrt_model_encode.argtypes = [ctypes.c_void_p, ctypes.c_char_p, ctypes.c_size_t,
                                        ctypes.POINTER(ctypes.c_size_t), ctypes.c_char_p, ctypes.c_size_t]
    lib.gmmrrt_model_encode.restype = ctypes.c_int
    lib.gmmrrt_gmm_log_density.argtypes = [ctypes.c_void_p, ctypes.POINTER(ctypes.c_double)]
    lib.gmmrrt_gmm_log_density.restype = ctypes.c_double
    return lib


def c_decode(lib, data):
    model = ctypes.create_string_buffer(MODEL_BYTES)
    err = ctypes.create_string_buffer(256)
    st = lib.gmmrrt_model_decode(data, len(data), model, err, len(err))
    return st, err.value.decode(), model


def check(out=None):
    cmd = [sys.executable, str(REPO / "tools" / "gen_model_vectors.py"), "--check"]
    return subprocess.run(cmd + (["--out", str(out)] if out else []), capture_output=True, text=True)


def test_checked_in_vectors_are_what_the_script_makes():
    r = check()
    assert r.returncode == 0, r.stderr
    assert "6 of 6 files current" in r.stdout, r.stdout


def test_check_fails_on_a_change_a_consumer_could_notice(tmp_path):
    import shutil
    shutil.copytree(VECTORS, tmp_path, dirs_exist_ok=True)
    csv = tmp_path / "xy.csv"
    lines = csv.read_text().splitlines()
    cells = lines[5].split(",")
    cells[-1] = repr(float(cells[-1]) * (1.0 + 1e-9))  # the consumers' own tolerance
    lines[5] = ",".join(cells)
    csv.write_text("\n".join(lines) + "\n")
    r = check(tmp_path)
    assert r.returncode == 1 and "xy.csv differs by" in r.stderr, (r.stdout, r.stderr)

    shutil.copy(VECTORS / "xy.csv", csv)
    gmm = tmp_path / "generic_d4.gmm"
    data = bytearray(gmm.read_bytes())
    data[13] ^= 1  # the task byte of the header (its CRC no longer matches either)
    gmm.write_bytes(bytes(data))
    r = check(tmp_path)
    assert r.returncode == 1 and "generic_d4.gmm" in r.stderr, (r.stdout, r.stderr)


@pytest.mark.parametrize("name", ["features_seam", "xy", "generic_d4"])
def test_vector_file_decodes_in_c_and_reencodes_to_the_same_bytes(core, name):
    data = (VECTORS / (name + ".gmm")).read_bytes()
    st, err, model = c_decode(core, data)
    assert st == 0, err
    out = ctypes.create_string_buffer(len(data))
    n = ctypes.c_size_t(0)
    errbuf = ctypes.create_string_buffer(256)
    assert core.gmmrrt_model_encode(model, out, len(out), ctypes.byref(n), errbuf, len(errbuf)) == 0
    assert out.raw[:n.value] == data


@pytest.mark.parametrize("dim", range(1, 9))
def test_random_models_match_the_scipy_oracle_for_every_dimension(core, dim):
    rng = np.random.default_rng(1000 + dim)
    for trial in range(3):
        k = int(rng.integers(1, 8))
        mask = int(rng.integers(0, 1 << min(dim, 3)))  # up to 3 angle dimensions: 27 images
        angle = [(mask >> j) & 1 for j in range(dim)]
        means = rng.normal(size=(k, dim)) * 2.0
        means[:, np.array(angle, dtype=bool)] = rng.uniform(-np.pi, np.pi, size=(k, sum(angle)))
        scales = np.where(angle, rng.uniform(0.2, 1.0, dim), rng.uniform(0.3, 2.0, dim))
        chols = np.stack([gmv.random_chol(rng, scales) for _ in range(k)])
        weights = rng.dirichlet(np.ones(k))
        data = gmv.encode("generic", "none", "all", mask, 1e-3, weights, means, chols)
        st, err, model = c_decode(core, data)
        assert st == 0, err
        spec = gmv.decode(data)
        points = rng.normal(size=(50, dim)) * 3.0
        for j in range(dim):
            if angle[j]:
                points[:, j] = gmv.wrap(points[:, j])
        want = gmv.expected_log_density(spec, points)
        for p, w in zip(points, want):
            got = core.gmmrrt_gmm_log_density(model, (ctypes.c_double * dim)(*p))
            assert abs(got - w) <= 1e-9 * max(1.0, abs(w)), (dim, trial, p, got, w)
