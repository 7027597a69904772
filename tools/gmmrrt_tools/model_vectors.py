"""gmmrrt_tools.model_vectors - the one deliberately independent oracle of the model file format and
the mixture density: it encodes models with struct + zlib.crc32 and evaluates log p(f) with numpy/scipy,
sharing no code with the C core (planner/src, planner/io) or the learner, so the C mixture, the C codec
and the learner's Eigen code are all checked against it (tests/unit/gmm, tests/unit/model, the learner's
tests). tools/gen_model_vectors.py is its command line.

Writes into tests/data/model_vectors/ (or --out DIR), for each model NAME:
  NAME.gmm  a model file in the format of docs/model-format.md, encoded here with
            struct + zlib.crc32 (independently of the C encoder)
  NAME.csv  header f0,...,f{D-1},log_density; one point per row; the expected
            log p(f) computed here with numpy/scipy (see expected_log_density)

The C mixture (tests/unit/gmm, CTest planner.gmm) and the learner's Eigen code both
check their log-density against these files (within 1e-9, relative above 1).

Deterministic up to rounding: the covariance factors come from BLAS/LAPACK (matrix products,
Cholesky) and the oracle from scipy, so another CPU or OpenBLAS kernel changes the last bits
of the numbers. The files were made with OpenBLAS's Cooperlake kernel; Prescott gives the same
bytes, Haswell and Zen differ by up to 7.5e-14 relative, SkylakeX by 2.3e-13 (in xy.csv, whose
s dimension has sigma 0.08: the far points' log-densities amplify the factors' last bits).
--check therefore compares the checked-in files with a fresh run field by field: every
integer and header field exactly, every number within CHECK_RTOL relative (absolute below 1).
CHECK_RTOL is 1e-10: 400 times the largest kernel difference seen, and 10 times below the
1e-9 the consumers allow, so a change of the models, the points or the formula that a
consumer could notice still fails --check.

    .venv/bin/python tools/gen_model_vectors.py            # rewrite the checked-in files
    .venv/bin/python tools/gen_model_vectors.py --check    # verify they are up to date
"""
import argparse
import itertools
import os
import struct
import sys
import zlib

import numpy as np
from scipy.special import logsumexp
from scipy.stats import multivariate_normal

MAGIC = b"GMMRRTMD"
VERSION = 1
BOM = 0xFEFF
HEADER = struct.Struct("<8sHHBBBBHHId")  # 32 bytes
KIND = {"features": 1, "xy": 2, "generic": 3}
TASK = {"none": 0, "avoid": 1, "approach": 2}
HOMOTOPY = {"all": 0, "left": 1, "right": 2, "frontal": 3}
CHECK_RTOL = 1e-10  # --check: see the module docstring for why
# The optional provenance trailer after the model's CRC-32 (docs/model-format.md).
PROV_MAGIC = b"GMMRRTPV"
PROV_VERSION = 1
PROV_HEAD = struct.Struct("<8sHHI")  # magic, version, reserved, text length: 16 bytes
PROV_MAX_TEXT = 4096  # GMMRRT_MAX_PROVENANCE_BYTES of limits.h (default)


def encode(kind, task, homotopy, angle_mask, delta, weights, means, chols):
    """Model file bytes: header, weights, means, packed row-major lower triangles, CRC-32."""
    k, d = means.shape
    tri = [chols[i][r, c] for i in range(k) for r in range(d) for c in range(r + 1)]
    body = HEADER.pack(MAGIC, VERSION, BOM, KIND[kind], TASK[task], HOMOTOPY[homotopy], d, k, 0,
                       angle_mask, delta)
    body += struct.pack("<%dd" % k, *weights)
    body += struct.pack("<%dd" % (k * d), *means.ravel())
    body += struct.pack("<%dd" % len(tri), *tri)
    return body + struct.pack("<I", zlib.crc32(body))


def encode_provenance(text):
    """The provenance trailer that follows a model's CRC-32: magic, version, reserved, UTF-8 text
    length, the text, CRC-32 of the trailer's bytes before it."""
    raw = text.encode("utf-8")
    body = PROV_HEAD.pack(PROV_MAGIC, PROV_VERSION, 0, len(raw)) + raw
    return body + struct.pack("<I", zlib.crc32(body))


def _decode_provenance(tail):
    """The text of the trailer `tail` (the bytes after the model's CRC-32); ValueError naming the rule."""
    if len(tail) < 8 and PROV_MAGIC.startswith(tail):
        raise ValueError("provenance trailer truncated")
    if tail[:8] != PROV_MAGIC:
        raise ValueError("length does not match D and K (trailing bytes are not a provenance trailer)")
    if len(tail) < PROV_HEAD.size + 4:
        raise ValueError("provenance trailer truncated")
    _magic, version, reserved, n = PROV_HEAD.unpack_from(tail)
    if version != PROV_VERSION or reserved != 0:
        raise ValueError("provenance trailer version %d / reserved %d not supported" % (version, reserved))
    if n > PROV_MAX_TEXT:
        raise ValueError("provenance text of %d bytes is longer than %d" % (n, PROV_MAX_TEXT))
    if len(tail) < PROV_HEAD.size + n + 4:
        raise ValueError("provenance trailer truncated")
    if len(tail) > PROV_HEAD.size + n + 4:
        raise ValueError("trailing bytes after the provenance trailer")
    if zlib.crc32(tail[:-4]) != struct.unpack_from("<I", tail, len(tail) - 4)[0]:
        raise ValueError("provenance trailer CRC-32 mismatch")
    raw = tail[PROV_HEAD.size:PROV_HEAD.size + n]
    if b"\0" in raw:
        raise ValueError("provenance text holds a NUL byte")
    return raw.decode("utf-8")  # UnicodeDecodeError is a ValueError


def decode(data):
    """The reader of docs/model-format.md (checks magic, version, byte order, size, CRC and the
    provenance trailer's framing only); the result's "provenance" is its text, or None without one."""
    magic, version, bom, kind, task, homotopy, d, k, reserved, mask, delta = HEADER.unpack_from(data)
    if magic != MAGIC or version != VERSION or bom != BOM or reserved != 0:
        raise ValueError("not a version-1 little-endian gmmrrt model")
    ntri = d * (d + 1) // 2
    model_len = HEADER.size + 8 * k * (1 + d + ntri) + 4
    if len(data) < model_len:
        raise ValueError("length does not match D and K (truncated)")
    provenance = _decode_provenance(bytes(data[model_len:])) if len(data) > model_len else None
    if zlib.crc32(data[:model_len - 4]) != struct.unpack_from("<I", data, model_len - 4)[0]:
        raise ValueError("CRC-32 mismatch")
    vals = np.frombuffer(data, dtype="<f8", count=k * (1 + d + ntri), offset=HEADER.size)
    weights, means, tri = vals[:k], vals[k:k + k * d].reshape(k, d), vals[k + k * d:].reshape(k, ntri)
    chols = np.zeros((k, d, d))
    rows, cols = np.tril_indices(d)  # row-major lower triangle: (0,0), (1,0), (1,1), (2,0), ...
    chols[:, rows, cols] = tri
    return dict(kind=kind, task=task, homotopy=homotopy, dim=d, k=k, angle_mask=mask, delta=delta,
                weights=weights, means=means, chols=chols, provenance=provenance)


def wrap(a):
    """Angles into (-pi, pi]."""
    return np.pi - np.mod(np.pi - a, 2.0 * np.pi)


def expected_log_density(model, points):
    """log sum_i w_i sum_{n in {-1,0,1}^A} N(wrap(f - mu_i) + 2 pi n; 0, L_i L_i^T), with the
    wrapped difference taken on angle dimensions only (the convention of gmm.h)."""
    d = model["dim"]
    angle_dims = [j for j in range(d) if (model["angle_mask"] >> j) & 1]
    images = list(itertools.product((-1, 0, 1), repeat=len(angle_dims)))
    terms = []
    for w, mu, chol in zip(model["weights"], model["means"], model["chols"]):
        diff = points - mu
        diff[:, angle_dims] = wrap(diff[:, angle_dims])
        dist = multivariate_normal(mean=np.zeros(d), cov=chol @ chol.T)
        for n in images:
            shift = np.zeros(d)
            shift[angle_dims] = 2.0 * np.pi * np.asarray(n, dtype=float)
            terms.append(np.log(w) + dist.logpdf(diff + shift))
    return logsumexp(np.stack(terms, axis=0), axis=0)


def random_chol(rng, scales, corr=0.6):
    """A lower-triangular factor of a random covariance with the given marginal scales."""
    d = len(scales)
    a = rng.normal(size=(d, d)) * corr + np.eye(d)
    c = a @ a.T
    s = np.sqrt(np.diag(c))
    c = c / np.outer(s, s) * np.outer(scales, scales)
    return np.linalg.cholesky(c)


def sample(model, rng, n):
    k = model["k"]
    comp = rng.choice(k, size=n, p=model["weights"])
    z = rng.normal(size=(n, model["dim"]))
    x = model["means"][comp] + np.einsum("nij,nj->ni", model["chols"][comp], z)
    for j in range(model["dim"]):
        if (model["angle_mask"] >> j) & 1:
            x[:, j] = wrap(x[:, j])
    return x


def features_seam(rng):
    """(d, theta) avoid model; component 0 centred at theta = pi - 0.05 straddles the seam."""
    means = np.array([[1.6, np.pi - 0.05], [2.2, -np.pi + 0.2], [1.2, 0.9], [2.8, -1.3], [3.5, 0.1]])
    scales = [[0.35, 0.45], [0.5, 0.3], [0.25, 0.2], [0.6, 1.2], [0.8, 0.6]]
    chols = np.stack([random_chol(rng, s) for s in scales])
    weights = np.array([0.3, 0.15, 0.2, 0.25, 0.1])
    points = np.concatenate([
        sample(dict(k=5, dim=2, angle_mask=2, weights=weights, means=means, chols=chols), rng, 150),
        # Along the seam, from both sides, and exactly on it.
        np.column_stack([np.linspace(0.5, 4.0, 12), np.full(12, np.pi)]),
        np.column_stack([np.linspace(0.5, 4.0, 12), np.full(12, -np.pi + 1e-12)]),
        np.column_stack([np.linspace(0.5, 4.0, 12), np.full(12, np.pi - 1e-9)]),
        # Far from every component (log-density in the hundreds or thousands below zero).
        np.array([[25.0, 0.0], [60.0, 3.0], [-15.0, -2.0], [200.0, 1.0]]),
    ])
    return dict(kind="features", task="avoid", homotopy="left", angle_mask=0b10, delta=1e-3,
                weights=weights, means=means, chols=chols), points


def xy(rng):
    """(s, x', y') model of the GMM-RRT baseline, components sorted by mean progress s."""
    k = 6
    s = np.linspace(0.05, 0.95, k)
    means = np.column_stack([s, -4.0 + 8.0 * s, 1.5 * np.sin(np.pi * s)])
    chols = np.stack([random_chol(rng, [0.08, 0.6, 0.4]) for _ in range(k)])
    weights = rng.dirichlet(np.full(k, 5.0))
    model = dict(k=k, dim=3, angle_mask=0, weights=weights, means=means, chols=chols)
    points = np.concatenate([sample(model, rng, 180), rng.uniform([-0.5, -10, -6], [1.5, 10, 6], (20, 3))])
    return dict(kind="xy", task="avoid", homotopy="all", angle_mask=0, delta=1e-3, weights=weights,
                means=means, chols=chols), points


def generic_d4(rng):
    """D = 4 user features with dimension 2 an angle (two components near the seam)."""
    k = 4
    means = np.array([[0.0, 1.0, 3.0, -1.0], [1.5, -0.5, -3.05, 0.0], [-1.0, 0.0, 0.4, 2.0],
                      [0.5, 2.0, -1.5, 1.0]])
    chols = np.stack([random_chol(rng, [0.7, 0.5, 0.5, 1.0]), random_chol(rng, [0.4, 0.9, 0.3, 0.5]),
                      random_chol(rng, [1.0, 0.6, 1.1, 0.8]), random_chol(rng, [0.5, 0.5, 0.6, 0.5])])
    weights = np.array([0.4, 0.3, 0.2, 0.1])
    model = dict(k=k, dim=4, angle_mask=0b100, weights=weights, means=means, chols=chols)
    points = np.concatenate([sample(model, rng, 180),
                             np.column_stack([rng.normal(size=(20, 2)), np.full(20, np.pi),
                                              rng.normal(size=20)])])
    return dict(kind="generic", task="none", homotopy="all", angle_mask=0b100, delta=1e-2,
                weights=weights, means=means, chols=chols), points


def build(name, maker, seed):
    rng = np.random.default_rng(seed)
    spec, points = maker(rng)
    data = encode(spec["kind"], spec["task"], spec["homotopy"], spec["angle_mask"], spec["delta"],
                  spec["weights"], spec["means"], spec["chols"])
    model = decode(data)  # the values the file holds, exactly
    logp = expected_log_density(model, points)
    lines = [",".join(["f%d" % j for j in range(model["dim"])] + ["log_density"])]
    lines += [",".join("%.17g" % v for v in row) for row in np.column_stack([points, logp])]
    return {name + ".gmm": data, name + ".csv": ("\n".join(lines) + "\n").encode()}


def deviation(a, b):
    """Largest |a - b| / max(1, |a|) over two equal-shaped arrays."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return float(np.max(np.abs(a - b) / np.maximum(1.0, np.abs(a)))) if a.size else 0.0


def compare(name, old, new):
    """Checked-in bytes `old` against fresh bytes `new` of file `name`: (None or the reason it
    is out of date, largest relative deviation seen)."""
    if name.endswith(".gmm"):
        try:
            a, b = decode(old), decode(new)
        except ValueError as exc:
            return "does not decode (%s)" % exc, 0.0
        for key in ("kind", "task", "homotopy", "dim", "k", "angle_mask", "provenance"):
            if a[key] != b[key]:
                return "%s is %r, the script makes %r" % (key, a[key], b[key]), 0.0
        dev = max(deviation([a["delta"]], [b["delta"]]),
                  *(deviation(a[key], b[key]) for key in ("weights", "means", "chols")))
    else:
        lines_a, lines_b = old.decode().splitlines(), new.decode().splitlines()
        if not lines_a or lines_a[0] != lines_b[0] or len(lines_a) != len(lines_b):
            return "header or number of rows differs", 0.0
        rows_a = np.array([[float(v) for v in line.split(",")] for line in lines_a[1:]])
        rows_b = np.array([[float(v) for v in line.split(",")] for line in lines_b[1:]])
        if rows_a.shape != rows_b.shape:
            return "shape %s, the script makes %s" % (rows_a.shape, rows_b.shape), 0.0
        dev = deviation(rows_a, rows_b)
    if dev > CHECK_RTOL:
        return "differs by %.3g relative (tolerance %g)" % (dev, CHECK_RTOL), dev
    return None, dev


def main(argv=None):
    here = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default=os.path.join(here, "..", "tests", "data", "model_vectors"),
                    help="output folder (default: tests/data/model_vectors)")
    ap.add_argument("--check", action="store_true",
                    help="compare with the files in --out within %g relative, write nothing" % CHECK_RTOL)
    args = ap.parse_args(argv)
    files = {}
    files.update(build("features_seam", features_seam, 20261121))
    files.update(build("xy", xy, 20261122))
    files.update(build("generic_d4", generic_d4, 20261123))
    if args.check:
        stale, worst = 0, 0.0
        for n, b in files.items():
            path = os.path.join(args.out, n)
            if not os.path.isfile(path):
                reason, dev = "is missing", 0.0
            else:
                with open(path, "rb") as f:
                    reason, dev = compare(n, f.read(), b)
            worst = max(worst, dev)
            if reason:
                stale += 1
                print("gen_model_vectors: %s %s" % (path, reason), file=sys.stderr)
        print("gen_model_vectors: %d of %d files current (largest deviation %.3g relative, tolerance %g)"
              % (len(files) - stale, len(files), worst, CHECK_RTOL))
        return 1 if stale else 0
    os.makedirs(args.out, exist_ok=True)
    for n, b in files.items():
        tmp = os.path.join(args.out, n + ".tmp")
        with open(tmp, "wb") as f:
            f.write(b)
        os.replace(tmp, os.path.join(args.out, n))
        print("wrote %s (%d bytes)" % (os.path.join(args.out, n), len(b)))
    return 0
