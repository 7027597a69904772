"""Best cost against time, ours and OMPL's RRTstar, from gmmrrt-bench-ompl's trial
records: the median over trials and the range, one panel per objective.

    .venv/bin/python -m gmmrrt_tools.bench.plot build/bench-raw/ompl_length.jsonl \\
        build/bench-raw/ompl_task.jsonl -o docs/img/benchmarks-ompl-cost.png
"""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from gmmrrt_tools.bench.stats import cost_at  # noqa: E402

LABELS = {"ompl_rrtstar": "OMPL RRTstar (defaults)", "gmmrrt_rrtstar": "gmmrrt RRT*"}
COLORS = {"ompl_rrtstar": "tab:blue", "gmmrrt_rrtstar": "tab:red"}


def plot(jsonl_paths, out: Path) -> None:
    fig, axes = plt.subplots(1, len(jsonl_paths), figsize=(5.5 * len(jsonl_paths), 4.0), squeeze=False)
    for ax, path in zip(axes[0], jsonl_paths):
        records = [json.loads(line) for line in Path(path).read_text().splitlines() if line.strip()]
        if not records:
            raise ValueError(f"{path}: no trial records")
        t_max = max(r["time_ms"] for r in records)
        times = np.logspace(-2, np.log10(t_max), 200)
        objective = records[0]["objective"]
        for planner in ("ompl_rrtstar", "gmmrrt_rrtstar"):
            rs = [r for r in records if r["planner"] == planner]
            if not rs:
                continue
            curves = np.array([[cost_at(r["history"], t) for t in times] for r in rs])
            med = np.median(curves, axis=0)  # inf before half the runs have a path: not drawn
            lo, hi = curves.min(axis=0), curves.max(axis=0)
            ok = np.isfinite(med)
            ax.plot(times[ok], med[ok], color=COLORS[planner], label=f"{LABELS[planner]} (median of {len(rs)})")
            band = np.isfinite(hi) & np.isfinite(lo)
            ax.fill_between(times[band], lo[band], hi[band], color=COLORS[planner], alpha=0.2, linewidth=0)
        ax.set_xscale("log")
        ax.set_xlabel("planning time [ms]")
        ax.set_ylabel("best path cost" + (" [m]" if objective == "length" else " (length + task cost)"))
        ax.set_title(f"disc problem, {objective} objective")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.tight_layout()
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=110)
    plt.close(fig)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("records", nargs="+", type=Path, help="gmmrrt-bench-ompl --out files (JSON lines)")
    ap.add_argument("-o", "--output", type=Path, required=True, help="PNG to write")
    args = ap.parse_args(argv)
    for p in args.records:
        if not p.is_file():
            ap.error(f"{p} does not exist")
    try:
        plot(args.records, args.output)
    except (ValueError, KeyError, json.JSONDecodeError) as e:
        print(f"bench_plot: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
