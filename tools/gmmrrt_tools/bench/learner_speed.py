"""Learner speed, before and after: interleaved CPU-time runs of two gmmrrt-learn
binaries and of single-threaded scikit-learn on one CSV of 2-D points, medians.

Times are CPU seconds of each run (user + sys of the child, or process_time for scikit-learn),
not wall time: the development machine is shared, so only ratios measured in one run mean much.
The learner's times include reading the CSV (about 0.1 s for 200 000 points); scikit-learn's do
not. Each learner run's mean log-likelihood is the one its `fit` summary prints.

    .venv/bin/python -m gmmrrt_tools.bench.learner_speed --data big.csv --k 19 --reps 3 \\
        --bin before=/tmp/gmmrrt-learn.before --bin after=build/bin/gmmrrt-learn [-- --tol 1e-3]
"""
from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_v] = "1"

import argparse  # noqa: E402
import re  # noqa: E402
import resource  # noqa: E402
import statistics  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402


def run_learner(exe: str, data: str, k: int, seed: int, extra: list) -> tuple:
    with tempfile.TemporaryDirectory() as tmp:
        cmd = [exe, "fit", "--features-csv", data, "--k", str(k), "--seed", str(seed), "-o", f"{tmp}/m.gmm"] + extra
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        p = subprocess.run(cmd, capture_output=True, text=True)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if p.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed: {p.stderr[-300:]}")
    m = re.search(r"iterations=(\d+).*mean_log_likelihood=(\S+)", p.stderr)
    if not m:
        sys.exit(f"{exe}: no fit summary on stderr")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return cpu, float(m.group(2)), int(m.group(1))


def run_sklearn(x: np.ndarray, k: int, seed: int) -> tuple:
    from sklearn.mixture import GaussianMixture
    from threadpoolctl import threadpool_limits
    with threadpool_limits(limits=1):
        t0 = time.process_time()
        gm = GaussianMixture(k, covariance_type="full", random_state=seed).fit(x)
        cpu = time.process_time() - t0
    return cpu, float(gm.score(x)), int(gm.n_iter_)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--data", required=True, help="CSV of points, one per line (no header)")
    ap.add_argument("--k", type=int, default=19)
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--bin", action="append", default=[], help="NAME=PATH of a gmmrrt-learn (repeatable)")
    ap.add_argument("--no-sklearn", action="store_true")
    ap.add_argument("extra", nargs="*", help="options passed to every gmmrrt-learn fit (after --)")
    a = ap.parse_args()
    bins = [b.split("=", 1) for b in a.bin]
    if any(len(b) != 2 or not os.access(b[1], os.X_OK) for b in bins):
        ap.error("--bin takes NAME=PATH of an executable")
    x = None if a.no_sklearn else np.loadtxt(a.data, delimiter=",", ndmin=2)
    names = [b[0] for b in bins] + ([] if a.no_sklearn else ["scikit-learn"])
    res = {n: [] for n in names}
    for rep in range(a.reps):
        order = names[rep % len(names):] + names[:rep % len(names)]
        for n in order:
            if n == "scikit-learn":
                res[n].append(run_sklearn(x, a.k, a.seed + rep))
            else:
                res[n].append(run_learner(dict(bins)[n], a.data, a.k, a.seed + rep, a.extra))
            print(f"rep {rep} {n}: {res[n][-1][0]:.2f} s, LL {res[n][-1][1]:.5f}, {res[n][-1][2]} it", file=sys.stderr)
    ref = statistics.median(r[0] for r in res["scikit-learn"]) if "scikit-learn" in res else None
    print(f"{'run':14s} {'CPU s':>8s} {'mean LL':>10s} {'iters':>6s} {'sklearn/run':>12s}")
    for n in names:
        cpu = statistics.median(r[0] for r in res[n])
        print(f"{n:14s} {cpu:8.2f} {statistics.median(r[1] for r in res[n]):10.5f} "
              f"{statistics.median(r[2] for r in res[n]):6.0f} {(ref / cpu if ref else float('nan')):12.1f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
