"""The paper's Fig. 3: TDM and l_e against the planning budget (avoid task).
"""
from __future__ import annotations


import numpy as np

from gmmrrt_tools import metrics as M
from .common import Ctx, GMM_RRT_BIAS, classify, demo_scene, demos, fmt_ms, homotopies, model, record

# ==================================================================== Fig. 3

def exp_fig3(ctx: Ctx) -> None:
    """As Table 1 (trial i re-plans demonstration i mod 9 and is scored against it), avoid task, both
    homotopies pooled, for a range of iteration caps."""
    s = ctx.s
    d = demos(ctx)
    jobs, scenes_ = [], {}
    for hom in homotopies(ctx, "avoid"):
        ds = d[("avoid", hom)]
        for planner, kind, label in (("gmm-rrt-star", "features", "GMM-RRT*"), ("gmm-rrt", "xy", "GMM-RRT")):
            mdl = model(ctx, "avoid", hom, kind)
            for budget in s.fig3_budgets:
                for i in range(s.trials):
                    demo = ds[i % len(ds)]
                    scene = scenes_.setdefault(demo.episode_id, demo_scene(ctx, demo))
                    jobs.append(({"homotopy": hom, "planner": label, "budget": budget, "demo": demo.episode_id},
                                 ctx.plan(scene, planner, s.seed + i, mdl, budget,
                                          s.bias if planner == "gmm-rrt-star" else GMM_RRT_BIAS), s.seed + i))
    results = ctx.run_plans(jobs, "fig3")
    by_id = {e.episode_id: e for es in d.values() for e in es}
    records, table = [], {}
    for tag, res in results:
        out = classify(res, scenes_[tag["demo"]])
        extra = {"outcome": out}
        if out == M.SUCCESS:
            demo = by_id[tag["demo"]]
            extra.update(tdm_m=M.tdm_pair(demo.xy, res.path), le=M.length_error_pair(demo.xy, res.path))
        rec = record(tag, res, **extra)
        records.append(rec)
        table.setdefault((tag["planner"], tag["budget"]), []).append(rec)
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8))
    lines = []
    for label, color in (("GMM-RRT*", "tab:red"), ("GMM-RRT", "tab:blue")):
        tm, ts, lm, ls, ok_n = [], [], [], [], []
        for b in s.fig3_budgets:
            recs = table.get((label, b), [])
            ok = [r for r in recs if "tdm_m" in r]
            a, b_ = M.mean_std([r["tdm_m"] for r in ok])
            c, d_ = M.mean_std([100 * r["le"] for r in ok])
            tm.append(a); ts.append(b_); lm.append(c); ls.append(d_); ok_n.append(len(ok))
            lines.append(f"| {label} | {b} | {len(ok)}/{len(recs)} | {fmt_ms(a, b_)} | {fmt_ms(c, d_, 2)} |")
        x = np.arange(len(s.fig3_budgets)) + (-0.1 if label == "GMM-RRT*" else 0.1)
        axes[0].errorbar(x, tm, yerr=ts, fmt="o", color=color, label=label, capsize=3)
        axes[1].errorbar(x, lm, yerr=ls, fmt="o", color=color, label=label, capsize=3)
    for ax, yl in zip(axes, ("TDM (m)", "l_e (%)")):
        ax.set_xticks(np.arange(len(s.fig3_budgets)))
        ax.set_xticklabels([str(b) for b in s.fig3_budgets])
        ax.set_xlabel("iteration cap")
        ax.set_ylabel(yl)
        ax.grid(alpha=0.3)
        ax.legend()
    fig.suptitle("Avoid task: metrics vs planning budget (cf. paper Fig. 3)")
    md = ctx.header("Fig. 3: TDM and l_e vs planning budget (avoid task)",
                    "Protocol of Table 1 (trial i re-plans demonstration i mod 9 of its homotopy and is scored against it), "
                    "both homotopies pooled, each with its own model; budget = iteration cap. GMM-RRT stops at its "
                    "first solution, so its cap only matters when it has not found one.")
    md += "| planner | iteration cap | success | TDM (m) | l_e (%) |\n|---|---|---|---|---|\n" + "\n".join(lines) + "\n"
    ctx.write("fig3", md, records, fig)
