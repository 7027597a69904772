#!/usr/bin/env python3
"""plot_model.py - look at a learned model: its density as an image with a colour bar, each
component's one-sigma contour, and the training points if given.

  plot_model.py MODEL -o model.png [--points FEATURES.csv] [--extent M]

A (d, theta) model (kind features, what `gmmrrt-learn fit` learns from demonstrations) is drawn
in the person's frame: the person at the origin facing +x', left (theta > 0) up; every grid point
is turned into (d, theta) by the C core's gmmrrt_features_from_xy, scored by gmmrrt_gmm_log_density,
and each component's contour (mu + L (cos a, sin a) in (d, theta)) is mapped back by
gmmrrt_features_to_xy. A generic 2-D model is drawn in its own coordinates. --points: a CSV of
the model's features (as `gmmrrt-learn fit --features-csv` reads them; a header line is
skipped). Other dimensions are refused. Exit status 0; 1 on a bad model or points; 2 on bad usage.
"""
from __future__ import annotations

import argparse
import sys

import numpy as np

from gmmrrt_tools import core
from gmmrrt_tools.learn import GaussianMixture
from gmmrrt_tools.mixture import Model


def person_frame_to_features(xp: np.ndarray, yp: np.ndarray) -> np.ndarray:
    """(d, theta) of person-frame points by the core's one definition."""
    return np.array([core.features_from_xy((0.0, 0.0, 0.0), x, y) for x, y in zip(xp.ravel(), yp.ravel())])


def features_to_person_frame(f: np.ndarray) -> np.ndarray:
    return np.array([core.features_to_xy((0.0, 0.0, 0.0), d, th) for d, th in f])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    ap.add_argument("model")
    ap.add_argument("-o", "--output", required=True, help="image file (PNG, PDF, SVG by its suffix)")
    ap.add_argument("--points", help="training features CSV to draw over the density")
    ap.add_argument("--extent", type=float, default=None,
                    help="half-width of the person-frame view [m] (default: from the components)")
    args = ap.parse_args(argv)
    try:
        kind = Model(args.model).kind
        gm = GaussianMixture.load(args.model)
        pts = None
        if args.points:
            pts = np.loadtxt(args.points, delimiter=",", ndmin=2,
                             skiprows=1 if not _numeric_first_line(args.points) else 0)
    except (ValueError, OSError) as e:
        print(f"plot_model: error: {e}", file=sys.stderr)
        return 1
    if gm.means_.shape[1] != 2:
        print(f"plot_model: error: {args.model}: D = {gm.means_.shape[1]}; only D = 2 models are drawn",
              file=sys.stderr)
        return 1
    if pts is not None and pts.shape[1] != 2:
        print(f"plot_model: error: {args.points}: {pts.shape[1]} columns, the model has 2", file=sys.stderr)
        return 1
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    person_frame = kind == "features"
    a = np.linspace(0, 2 * np.pi, 73)
    contours = []
    for mu, cov in zip(gm.means_, gm.covariances_):
        c = mu + (np.linalg.cholesky(cov) @ np.stack([np.cos(a), np.sin(a)])).T
        contours.append(features_to_person_frame(c) if person_frame else c)
    if person_frame:
        half = args.extent or float(min(8.0, max(1.0, 1.2 * np.max(gm.means_[:, 0] + 2 * np.sqrt(gm.covariances_[:, 0, 0])))))
        gx, gy = np.meshgrid(np.linspace(-half, half, 161), np.linspace(-half, half, 161))
        f = person_frame_to_features(gx, gy)
        xlabel, ylabel = "x' [m] (person faces +x')", "y' [m] (person's left)"
    else:
        allc = np.vstack(contours)
        lo, hi = allc.min(axis=0), allc.max(axis=0)
        pad = 0.15 * (hi - lo)
        gx, gy = np.meshgrid(np.linspace(lo[0] - pad[0], hi[0] + pad[0], 161), np.linspace(lo[1] - pad[1], hi[1] + pad[1], 161))
        f = np.column_stack([gx.ravel(), gy.ravel()])
        xlabel, ylabel = "feature 1", "feature 2"
    dens = np.exp(gm.score_samples(f)).reshape(gx.shape)
    fig, ax = plt.subplots(figsize=(6.4, 5.6))
    im = ax.pcolormesh(gx, gy, dens, shading="auto", cmap="viridis")
    fig.colorbar(im, ax=ax, label="density" + (" p(d, theta)" if person_frame else ""))
    if pts is not None:
        xy = features_to_person_frame(pts) if person_frame else pts
        ax.scatter(xy[:, 0], xy[:, 1], s=1, c="white", alpha=0.3, linewidths=0, label="training points")
    for i, c in enumerate(contours):
        ax.plot(c[:, 0], c[:, 1], color="orange", lw=0.8, label="components (1 sigma)" if i == 0 else None)
    if person_frame:
        ax.plot([0], [0], marker=(3, 0, -90), ms=12, color="red", label="person (facing +x')")
        ax.set_xlim(-half, half)
        ax.set_ylim(-half, half)
    ax.set_aspect("equal")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(f"{args.model}: K = {len(gm.weights_)}, kind {kind}")
    ax.legend(loc="upper right", fontsize=7)
    fig.tight_layout()
    fig.savefig(args.output, dpi=120)
    print(f"plot_model: wrote {args.output}", file=sys.stderr)
    return 0


def _numeric_first_line(path: str) -> bool:
    with open(path) as fh:
        first = fh.readline().lstrip("\ufeff").split(",")[0].strip()
    try:
        float(first)
        return True
    except ValueError:
        return False


if __name__ == "__main__":
    sys.exit(main())
