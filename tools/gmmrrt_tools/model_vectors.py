"""Shared test vectors for the mixture: model files + points with their expected log-density.

THE DELIBERATELY INDEPENDENT ORACLE of the model file format and the mixture density: it
encodes with struct + zlib.crc32 and evaluates with numpy/scipy, sharing no code with the C core
(planner/src/model.c, gmm.c) or the learner, so that they are checked against code that does not
share their bugs. It is the only second implementation of the format that the project keeps
(docs/architecture.md); tools that write models use the core (gmmrrt_tools.core).

Writes into tests/data/model_vectors/ (or --out DIR), for each model NAME:
  NAME.gmm  a model file in the format of docs/model-format.md, encoded here with
            struct + zlib.crc32 (independently of the C encoder)
  NAME.csv  header f0,...,f{D-1},log_density; one point per row; the expected
            log p(f) computed here with numpy/scipy (see expected_log_density)

The C mixture (tests/unit/gmm, CTest planner.gmm) and the learner's Eigen code both
check their log-density against these files. Deterministic: same script, same bytes.

    .venv/bin/python tools/gen_model_vectors.py            # rewrite the checked-in files
    .venv/bin/python tools/gen_model_vectors.py --check    # verify they are up to date
(tools/gen_model_vectors.py is the entry point of this module's main.)
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


def decode(data):
    """The reader of docs/model-format.md (checks magic, version, byte order, size, CRC only)."""
    magic, version, bom, kind, task, homotopy, d, k, reserved, mask, delta = HEADER.unpack_from(data)
    if magic != MAGIC or version != VERSION or bom != BOM or reserved != 0:
        raise ValueError("not a version-1 little-endian gmmrrt model")
    ntri = d * (d + 1) // 2
    if len(data) != HEADER.size + 8 * k * (1 + d + ntri) + 4:
        raise ValueError("length does not match D and K")
    if zlib.crc32(data[:-4]) != struct.unpack_from("<I", data, len(data) - 4)[0]:
        raise ValueError("CRC-32 mismatch")
    vals = np.frombuffer(data, dtype="<f8", count=k * (1 + d + ntri), offset=HEADER.size)
    weights, means, tri = vals[:k], vals[k:k + k * d].reshape(k, d), vals[k + k * d:].reshape(k, ntri)
    chols = np.zeros((k, d, d))
    rows, cols = np.tril_indices(d)  # row-major lower triangle: (0,0), (1,0), (1,1), (2,0), ...
    chols[:, rows, cols] = tri
    return dict(kind=kind, task=task, homotopy=homotopy, dim=d, k=k, angle_mask=mask, delta=delta,
                weights=weights, means=means, chols=chols)


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


# --check tolerances. The vectors come from numpy/scipy (random Cholesky factors, log-sum-exp), whose
# last bits depend on the CPU and the BLAS: a file made on another machine is current when its
# header and shape are the same and every number agrees within these bounds (values are O(1)).
CHECK_ABS_GMM = 1e-12             # model parameters
CHECK_REL_CSV, CHECK_ABS_CSV = 1e-9, 1e-12  # points and expected log-densities


def same_within_tolerance(name, made, stored):
    """True when `stored` (bytes of a checked-in file) is `made` up to the CHECK_* tolerances."""
    if made == stored:
        return True
    if name.endswith(".gmm"):
        if len(made) != len(stored) or made[:HEADER.size] != stored[:HEADER.size]:
            return False
        a = np.frombuffer(made[HEADER.size:-4], dtype="<f8")
        b = np.frombuffer(stored[HEADER.size:-4], dtype="<f8")
        return bool(np.all(np.abs(a - b) <= CHECK_ABS_GMM)) and decode_ok(stored)
    made_lines, stored_lines = made.decode().splitlines(), stored.decode().splitlines()
    if len(made_lines) != len(stored_lines) or made_lines[:1] != stored_lines[:1]:
        return False
    a = np.array([[float(v) for v in ln.split(",")] for ln in made_lines[1:]])
    b = np.array([[float(v) for v in ln.split(",")] for ln in stored_lines[1:]])
    return a.shape == b.shape and bool(np.all(np.abs(a - b) <= CHECK_ABS_CSV + CHECK_REL_CSV * np.abs(b)))


def decode_ok(data):
    try:
        decode(data)
    except ValueError:
        return False
    return True


def main():
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default=os.path.join(root, "tests", "data", "model_vectors"),
                    help="output folder (default: tests/data/model_vectors)")
    ap.add_argument("--check", action="store_true", help="compare with the files in --out, write nothing")
    args = ap.parse_args()
    files = {}
    files.update(build("features_seam", features_seam, 20261121))
    files.update(build("xy", xy, 20261122))
    files.update(build("generic_d4", generic_d4, 20261123))
    if args.check:
        stale = [n for n, b in files.items()
                 if not os.path.isfile(os.path.join(args.out, n))
                 or not same_within_tolerance(n, b, open(os.path.join(args.out, n), "rb").read())]
        for n in stale:
            print("gen_model_vectors: %s is missing or out of date" % os.path.join(args.out, n),
                  file=sys.stderr)
        return 1 if stale else 0
    os.makedirs(args.out, exist_ok=True)
    for n, b in files.items():
        tmp = os.path.join(args.out, n + ".tmp")
        with open(tmp, "wb") as f:
            f.write(b)
        os.replace(tmp, os.path.join(args.out, n))
        print("wrote %s (%d bytes)" % (os.path.join(args.out, n), len(b)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
