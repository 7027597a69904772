"""The paper's Fig. 1: solution cost against iterations, mixture bias 100 % and 0 %.
"""
from __future__ import annotations

import shlex
from typing import List, Optional, Sequence

import numpy as np

from gmmrrt_tools import metrics as M
from gmmrrt_tools import runner as R
from .common import Ctx, classify, fmt_ms, homotopies, model, record, task_scene

# ==================================================================== Fig. 1

def fig1_checkpoints(cap: int) -> List[int]:
    grid = [100, 200, 300, 500, 750, 1000, 1500, 2000, 3000, 4000, 6000, 8000, 12000, 16000]
    return [c for c in grid if c < cap] + [cap]


def cost_at(history: Sequence[Sequence[float]], n: int) -> Optional[float]:
    """The best cost after n iterations from a gmmrrt-plan cost history ([iteration, cost] at every
    improvement, iterations increasing): the last entry with iteration <= n; None before the first."""
    best = None
    for it, c in history:
        if it > n:
            break
        best = float(c)
    return best


def exp_fig1(ctx: Ctx) -> None:
    """Best cost after N iterations, for N on a grid: one run per (bias, trial seed), capped at the largest
    N, read at every N from its cost history (gmmrrt-plan --json stats.cost_history)."""
    s = ctx.s
    scene = task_scene(ctx, "avoid", homotopies(ctx, "avoid")[0])
    mdl = model(ctx, "avoid", "all", "features")
    cps = fig1_checkpoints(s.fig1_iterations)
    jobs = []
    for bias in (1.0, 0.0):
        for i in range(s.trials):
            jobs.append(({"bias": bias, "iterations_cap": s.fig1_iterations},
                         ctx.plan(scene, "gmm-rrt-star", s.seed + i, mdl, s.fig1_iterations, bias), s.seed + i))
    results = ctx.run_plans(jobs, "fig1")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    lines, records = [], []
    for t, r in results:
        hist = r.stats.get("cost_history")
        if hist is None and r.status == "ok":
            raise R.ToolFailed("gmmrrt-plan --json printed no stats.cost_history: rebuild it (tools/run build)\n"
                               f"  command: {shlex.join(r.argv)}")
        if r.stats.get("cost_history_complete") is False:
            raise R.ToolFailed(f"the cost history of seed {r.seed} is truncated (more improvements than the CLI "
                               f"keeps): lower the iteration cap\n  command: {shlex.join(r.argv)}")
        ok = classify(r, scene) == M.SUCCESS
        records.append(record(t, r, outcome=classify(r, scene), cost_history=hist or [],
                              cost_at={n: (cost_at(hist or [], n) if ok else None) for n in cps}))
    for bias, color in ((1.0, "tab:red"), (0.0, "tab:blue")):
        means, stds = [], []
        for n in cps:
            costs = [r["cost_at"][n] for r in records if r["bias"] == bias and r["cost_at"][n] is not None]
            m_, s_ = M.mean_std(costs)
            means.append(m_)
            stds.append(s_)
            lines.append(f"| {bias:.0%} | {n} | {len(costs)}/{s.trials} | {fmt_ms(m_, s_, 3)} |")
        means, stds = np.array(means), np.array(stds)
        ax.plot(cps, means, "o-", color=color, ms=3, label=f"mixture bias {bias:.0%} (mean ± std)")
        ax.fill_between(cps, means - stds, means + stds, color=color, alpha=0.2)
    ax.set_xscale("log")
    ax.set_xlabel("iterations (samples drawn)")
    ax.set_ylabel("best path cost")
    ax.set_title("Avoid task, GMM-RRT*: cost vs iterations (cf. paper Fig. 1)", fontsize=10)
    ax.legend()
    ax.grid(alpha=0.3, which="both")
    md = ctx.header("Fig. 1: solution cost vs iterations, mixture bias 100 % and 0 %",
                    "GMM-RRT* (length + task cost) on the avoid scene with the two-homotopy model; bias = fraction of "
                    "samples drawn from the mixture, the rest uniform. One run per trial (seed base + i), capped at "
                    f"{s.fig1_iterations} iterations; each point is that run's best cost after N iterations, read from "
                    "its cost history (`gmmrrt-plan --json`, stats.cost_history). Mean ± std over the trials that have "
                    "a path by N; 'solved' = how many.")
    md += "| bias | iterations | solved | best cost |\n|---|---|---|---|\n" + "\n".join(lines) + "\n"
    ctx.write("fig1", md, records, fig)
