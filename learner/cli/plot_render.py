"""plot_render.py - draws what `gmmrrt-learn plot` computed (cmd_plot.cpp): a density grid with a
colour bar, component contours and training points, read from a JSON file, into an image.
It holds no rule of the model: every number comes from the C core through gmmrrt-learn.

  plot_render.py DATA.json IMAGE      (run by gmmrrt-learn plot with the system's python3)

The image's format is its suffix (png, pdf, svg); it is written to a temporary file beside it
and renamed, so it appears whole or not at all. Exit status 0; 3 when matplotlib is missing;
1 on any other failure, with the reason on stderr.
"""
import json
import os
import sys
import tempfile


def main(argv):
    if len(argv) != 3:
        print("usage: plot_render.py DATA.json IMAGE", file=sys.stderr)
        return 1
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return 3
    data_path, image = argv[1], argv[2]
    with open(data_path, encoding="utf-8") as fh:
        d = json.load(fh)
    fmt = os.path.splitext(image)[1].lstrip(".").lower() or "png"
    fig, ax = plt.subplots(figsize=(6.4, 5.6))
    im = ax.pcolormesh(d["grid_x"], d["grid_y"], d["density"], shading="auto", cmap="viridis")
    fig.colorbar(im, ax=ax, label=d["colorbar"])
    if d["points"]:
        xs, ys = zip(*d["points"])
        ax.scatter(xs, ys, s=1, c="white", alpha=0.3, linewidths=0, label="training points")
    for i, line in enumerate(d["contours"]):
        xs, ys = zip(*line)
        ax.plot(xs, ys, color="orange", lw=0.8, label="components (1 sigma)" if i == 0 else None)
    if d["person_frame"]:
        ax.plot([0], [0], marker=(3, 0, -90), ms=12, color="red", linestyle="none", label="person (facing +x')")
    ax.set_xlim(d["grid_x"][0], d["grid_x"][-1])
    ax.set_ylim(d["grid_y"][0], d["grid_y"][-1])
    if d["person_frame"]:
        ax.set_aspect("equal")
    ax.set_xlabel(d["xlabel"])
    ax.set_ylabel(d["ylabel"])
    ax.set_title(d["title"])
    ax.legend(loc="upper right", fontsize=7)
    fig.tight_layout()
    folder = os.path.dirname(os.path.abspath(image))
    fd, tmp = tempfile.mkstemp(prefix=".plot-", suffix="." + fmt, dir=folder)
    os.close(fd)
    try:
        fig.savefig(tmp, dpi=120, format=fmt)
        os.chmod(tmp, 0o644)
        os.replace(tmp, image)
    except BaseException:
        os.unlink(tmp)
        raise
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv))
    except (OSError, ValueError, KeyError, TypeError) as e:
        print(f"plot_render.py: error: {e}", file=sys.stderr)
        sys.exit(1)
