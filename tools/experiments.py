#!/usr/bin/env python3
"""Reproduces the paper's Table 1 and Figs. 1, 3, 5, 6 (Sect. 5.3) with gmmrrt, plus a real-data study.

Every number comes from the project's executables (gmmrrt-plan, gmmrrt-learn) driven through
gmmrrt_tools.runner; metrics are gmmrrt_tools.metrics (paper Sect. 5.2, eqs. (2)-(4)). Outputs go to
docs/results/ (markdown table + PNG + JSON of every run with its seed and command line).

Budgets are iteration caps (one iteration = one sample drawn, as OMPL counts them), not seconds as in
the paper: an iteration cap makes a seeded run reproducible on any machine. A wall-clock cap
(--budget-ms 60000) is passed too, only as a safety net; every run's time_ms is in the JSON (the
longest run of the committed results took 2.4 s).

    tools/experiments.py all [--quick] [--jobs 2]
    tools/experiments.py table1|fig1|fig3|fig5|fig6|real|delta [--quick] ...

This file is the command line only; each study is a module of tools/gmmrrt_tools/experiments/
(table1, fig1, fig3, obstacles (Figs. 5, 6), real, delta, report; common: what they share).
"""
from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path
from typing import Callable, Dict, Optional, Sequence

from gmmrrt_tools import metrics as M  # noqa: E402
from gmmrrt_tools import runner as R  # noqa: E402
from gmmrrt_tools.experiments.common import ROOT, Ctx  # noqa: E402
from gmmrrt_tools.experiments.delta import exp_delta  # noqa: E402
from gmmrrt_tools.experiments.fig1 import exp_fig1  # noqa: E402
from gmmrrt_tools.experiments.fig3 import exp_fig3  # noqa: E402
from gmmrrt_tools.experiments.obstacles import exp_fig5, exp_fig6  # noqa: E402
from gmmrrt_tools.experiments.real import REAL_SETS, exp_real  # noqa: E402
from gmmrrt_tools.experiments.report import write_report  # noqa: E402
from gmmrrt_tools.experiments.table1 import exp_table1  # noqa: E402

EXPERIMENTS: Dict[str, Callable[[Ctx], None]] = {
    "table1": exp_table1, "fig1": exp_fig1, "fig3": exp_fig3, "fig5": exp_fig5, "fig6": exp_fig6, "real": exp_real,
    "delta": exp_delta,
}


def main(argv: Optional[Sequence[str]] = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("experiment", choices=list(EXPERIMENTS) + ["all", "report"],
                    help="an experiment, all of them, or report (copy docs/results/*.md into docs/experiments.md)")
    ap.add_argument("--quick", action="store_true", help="small settings for a smoke run (minutes); outputs get a -quick suffix")
    ap.add_argument("--trials", type=int, help="trials per cell (default 25, quick 5)")
    ap.add_argument("--iterations", type=int, help="iteration cap per run (default 4000, quick 1500)")
    ap.add_argument("--seed", type=int, help="base seed: trial i uses seed + i (default 1)")
    ap.add_argument("--jobs", type=int, help="planner runs in parallel (default 1)")
    ap.add_argument("--max-episodes", type=int,
                    help="real data: at most this many episodes per data set, evenly spread (default all, quick 12)")
    ap.add_argument("--out", default=str(ROOT / "docs" / "results"), help="where tables and plots go (default docs/results)")
    ap.add_argument("--work", default=str(ROOT / "out" / "experiments"), help="scratch folder for models (default out/experiments)")
    ap.add_argument("--bin-dir", default=os.environ.get("GMMRRT_BIN_DIR"), help="folder of gmmrrt-plan and gmmrrt-learn")
    ap.add_argument("--demos-dir", default=str(ROOT / "logs" / "demos"), help="demonstration logs (default logs/demos)")
    ap.add_argument("--real-data", default=os.environ.get("GMMRRT_REAL_DATA", str(ROOT.parent / "shared" / "data" / "real")),
                    help="folder of the real episodes (default $GMMRRT_REAL_DATA or ../shared/data/real)")
    ap.add_argument("--split", default="test", help="real data: the split evaluated (default test)")
    ap.add_argument("--train-split", default="train", help="real data: the split models are learned on (default train)")
    ap.add_argument("--drivable", action="store_true",
                    help="score the drivable path gmmrrtd publishes instead of the tree's path (the paper's)")
    ap.add_argument("--real-k", help="real data: components of the learned avoid models, a number or auto (BIC "
                                     "sweep); default: gmmrrt-learn fit's (19, the paper's)")
    ap.add_argument("--real-sets", default="upo_avoid,ucy_avoid,ucy_approach",
                    help="real data: comma-separated studies of `real` (upo_avoid, ucy_avoid, ucy_approach)")
    args = ap.parse_args(argv)
    bad = [x for x in args.real_sets.split(",") if x not in REAL_SETS]
    if bad:
        ap.error(f"--real-sets: unknown {', '.join(bad)} (choose from {', '.join(REAL_SETS)})")
    if args.real_k is not None and args.real_k != "auto" and not (args.real_k.isdigit() and int(args.real_k) >= 1):
        ap.error(f"--real-k must be a number >= 1 or auto, got {args.real_k}")
    for k in ("trials", "iterations", "jobs", "max_episodes"):
        v = getattr(args, k)
        if v is not None and v < 1:
            ap.error(f"--{k.replace('_', '-')} must be >= 1, got {v}")
    if args.experiment == "report":
        write_report(Path(args.out), ROOT / "docs" / "experiments.md")
        return 0
    ctx = Ctx(args)
    names = list(EXPERIMENTS) if args.experiment == "all" else [args.experiment]
    failed = []
    for name in names:
        t0 = time.time()
        try:
            EXPERIMENTS[name](ctx)
            print(f"{name}: done in {time.time() - t0:.0f} s")
        except (R.MissingTool, R.ToolFailed, RuntimeError, ValueError) as exc:
            print(f"{name}: NOT RUN: {exc}", file=sys.stderr)
            failed.append(name)
    if failed:
        print(f"experiments not run: {', '.join(failed)}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
