"""learner.bic_sweep: `fit --k auto` finds the generating K (+-1) on overlapping components, not
only on well-separated ones. Data: the benchmark's generators (gmmrrt_tools.bench.learner): the
8-component mixture with means in a square of side 7 (separation 0.35), whose components
overlap, and 6 well-separated components; N = 20 000 each (the benchmark runs N = 50 000 and the
19-component mixture, with scikit-learn beside it). The split starts are what makes the
overlapping case work: without them (--split-starts 0) the sweep must still run, and the BIC it
reaches at its chosen K may not be lower than with them. Beside the splits each K screens only
two fresh k-means++ starts (--sweep-restarts, default 2): on these data that must choose the same
K at a BIC no higher than eight fresh starts per K (the setting before), for about half the time.
"""
import os
import subprocess
from pathlib import Path

import pytest

from gmmrrt_tools.bench.learner import make_mixture_points, make_separated_points, write_points_csv

BIN = Path(os.environ.get("GMMRRT_BIN_DIR", "build/bin")) / "gmmrrt-learn"


def sweep(csv, tmp_path, *extra):
    r = subprocess.run([str(BIN), "fit", "--features-csv", str(csv), "--k", "auto", "--seed", "1", "-q",
                        "-o", str(tmp_path / "m.gmm"), *extra], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    chosen = int(r.stdout.split("chosen K = ")[1].split()[0])
    rows = {int(line.split()[0]): float(line.split()[3]) for line in r.stdout.splitlines()
            if line.strip() and line.split()[0].isdigit()}
    return chosen, rows


@pytest.mark.parametrize("case", ["overlapping8", "separated6"])
def test_sweep_finds_the_generating_k(tmp_path, case):
    if case == "overlapping8":
        k_true, pts = 8, make_mixture_points(20000, 8, 101, separation=0.35)
    else:
        k_true, pts = 6, make_separated_points(20000, 6, 1)
    csv = tmp_path / "points.csv"
    write_points_csv(pts, csv)
    chosen, rows = sweep(csv, tmp_path)
    assert abs(chosen - k_true) <= 1, (chosen, rows)
    plain_chosen, plain_rows = sweep(csv, tmp_path, "--split-starts", "0")
    assert rows[chosen] <= plain_rows[plain_chosen] + 1e-6 * abs(plain_rows[plain_chosen]), (rows, plain_rows)
    eight_chosen, eight_rows = sweep(csv, tmp_path, "--sweep-restarts", "8")
    assert chosen == eight_chosen, (rows, eight_rows)
    assert rows[chosen] <= eight_rows[eight_chosen] + 1e-6 * abs(eight_rows[eight_chosen]), (rows, eight_rows)


def test_sweep_restarts_must_be_positive(tmp_path):
    csv = tmp_path / "points.csv"
    write_points_csv(make_separated_points(600, 3, 1), csv)
    r = subprocess.run([str(BIN), "fit", "--features-csv", str(csv), "--k", "auto", "--sweep-restarts", "0",
                        "-q", "-o", str(tmp_path / "m.gmm")], capture_output=True, text=True, timeout=60)
    assert r.returncode != 0
    assert "--sweep-restarts" in r.stderr, r.stderr
    assert not (tmp_path / "m.gmm").exists()
