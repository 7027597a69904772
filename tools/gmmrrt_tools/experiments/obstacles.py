"""The paper's Figs. 5 and 6: an obstacle blocks one homotopy (avoid) / the approach path.
"""
from __future__ import annotations

import math
from typing import Dict, Optional, Tuple

import numpy as np

from gmmrrt_tools import metrics as M
from gmmrrt_tools import runner as R
from gmmrrt_tools import scenes as S

from .common import (
    Ctx, GMM_RRT_BIAS, PERSON_RADIUS_M, draw_scene, classify, demo_scene, demos, fmt_ms, medoid, model, record
)

# ==================================================================== Fig. 5 / Fig. 6

def blocking_wall(scene: R.Scene, demo: S.Episode, width_m: float = 0.6) -> Tuple[float, float, float, float, float]:
    """A wall from the person's disc outwards past the bounds, through the point where `demo` passes
    closest to the person: any path between the demo's start and goal on the demo's side of the person
    crosses it, the other side stays open."""
    px, py = scene.people[0][:2]
    v = demo.xy - np.array([px, py])
    k = int(np.argmin(np.linalg.norm(v, axis=1)))
    u = v[k] / np.linalg.norm(v[k])
    b = scene.bounds
    reach = math.hypot(b[2] - b[0], b[3] - b[1]) + 1.0
    inner = PERSON_RADIUS_M * 0.5           # overlap the person's disc: no gap next to the person
    centre = np.array([px, py]) + u * (inner + reach / 2.0)
    return (float(centre[0]), float(centre[1]), reach, width_m, math.atan2(u[1], u[0]))


def exp_fig5(ctx: Ctx) -> None:
    s = ctx.s
    demo = medoid(demos(ctx)[("avoid", "right")])
    base = demo_scene(ctx, demo)
    scene = R.Scene(base.start, base.goal, base.people, base.bounds, boxes=[blocking_wall(base, demo)])
    runs = [("GMM-RRT*, two-homotopy model", "gmm-rrt-star", model(ctx, "avoid", "all", "features"), s.iterations, s.bias),
            ("GMM-RRT*, right-only model", "gmm-rrt-star", model(ctx, "avoid", "right", "features"), s.iterations, s.bias),
            ("GMM-RRT, right-only x-y model", "gmm-rrt", model(ctx, "avoid", "right", "xy"),
             s.iterations * s.fig5_gmm_rrt_factor, GMM_RRT_BIAS)]
    jobs = [({"planner": label}, ctx.plan(scene, pl, s.seed + i, mdl, it, bias), s.seed + i)
            for label, pl, mdl, it, bias in runs for i in range(s.trials)]
    results = ctx.run_plans(jobs, "fig5")
    _obstacle_report(ctx, "fig5", scene, results, [r[0] for r in runs], ("avoid", None),
                     "Fig. 5: an obstacle blocks one homotopy (avoid task)",
                     f"The avoid/right demonstration {demo.episode_id} (the most typical start and goal) re-planned "
                     "with a wall from the person outwards through the demonstration's closest point: its (right) "
                     f"side is closed, the left side open. GMM-RRT* with the two-homotopy model (bias {s.bias}) and "
                     f"with the right-only model vs the baseline GMM-RRT with the right-only x-y model, which gets "
                     f"{s.fig5_gmm_rrt_factor}x the iterations (the paper: 3 s vs 100 s). 'demo side / other side' "
                     "counts the successful paths passing the person on the demonstration's side (same_homotopy) or "
                     "not.", ref=demo)


FIG6_WIDTHS_M = (1.6, 2.4, 3.2)   # extent of the box across the straight approach


def exp_fig6(ctx: Ctx) -> None:
    """A box across the straight frontal approach, for a few widths (the paper gives no size): how
    often 100 % mixture sampling and the 95 % / 5 % mix find a way round, with the same iteration cap."""
    s = ctx.s
    demo = medoid(demos(ctx)[("approach", "frontal")])
    base = demo_scene(ctx, demo)
    sx, sy = base.start
    gx, gy = base.goal
    mx, my = (sx + gx) / 2.0, (sy + gy) / 2.0
    yaw = math.atan2(gy - sy, gx - sx)
    length = math.hypot(gx - sx, gy - sy)
    mdl = model(ctx, "approach", "frontal", "features")
    mixes = [("100 % mixture", 1.0), (f"{s.bias:.0%} mixture / {1 - s.bias:.0%} uniform", s.bias)]
    jobs, scene_of, labels = [], {}, []
    for width in FIG6_WIDTHS_M:
        box = (mx, my, min(0.6, 0.25 * length), width, yaw)
        scene = R.Scene(base.start, base.goal, base.people, base.bounds, boxes=[box])
        for name, bias in mixes:
            label = f"GMM-RRT*, {name}, box {width:.1f} m"
            labels.append(label)
            scene_of[label] = scene
            jobs += [({"planner": label, "box_width_m": width, "bias": bias},
                      ctx.plan(scene, "gmm-rrt-star", s.seed + i, mdl, s.iterations, bias), s.seed + i)
                     for i in range(s.trials)]
    results = ctx.run_plans(jobs, "fig6")
    _obstacle_report(ctx, "fig6", base, results, labels, ("approach", "frontal"),
                     "Fig. 6: an obstacle on the approach path",
                     f"Frontal approach (demonstration {demo.episode_id}, the most typical start and goal) with a box "
                     f"{min(0.6, 0.25 * length):.2f} m deep across the straight line from start to goal, "
                     f"{', '.join(f'{w:.1f}' for w in FIG6_WIDTHS_M)} m wide (the paper gives no size); the same "
                     "iteration cap for both sampling mixes.", ref=demo, scene_of=scene_of)


def _obstacle_report(ctx, name, scene, results, labels, demo_key, title, what, ref: S.Episode,
                     scene_of: Optional[Dict[str, R.Scene]] = None):
    import matplotlib.pyplot as plt

    records, lines = [], []
    ncols = min(3, len(labels))
    nrows = (len(labels) + ncols - 1) // ncols
    fig, axes = plt.subplots(nrows, ncols, figsize=(4.6 * ncols, 4.4 * nrows), squeeze=False)
    d = demos(ctx)
    scene_default = scene
    for ax, label in zip(axes.flatten(), labels):
        scene = (scene_of or {}).get(label, scene_default)
        rs = [r for t, r in results if t["planner"] == label]
        outs, sides, lens, firsts = [], [], [], []
        for r in rs:
            o = classify(r, scene)
            side = (("demo side" if M.same_homotopy(r.path, ref.xy, scene.people[0]) else "other side")
                    if r.path else None)
            outs.append(o)
            if o == M.SUCCESS:
                sides.append(side)
                lens.append(M.path_length(r.path))
                p = np.asarray(r.path)
                ax.plot(p[:, 0], p[:, 1], color="tab:red", lw=0.8, alpha=0.6)
            if r.stats.get("first_solution_ms") is not None and o == M.SUCCESS:
                firsts.append(r.stats.get("iterations"))
            records.append(record({"planner": label}, r, outcome=o, side=side))
        tag_extra = next((t for t, _ in results if t["planner"] == label), {})
        for rec in records[-len(rs):]:
            rec.update({k: v for k, v in tag_extra.items() if k != "planner"})
        rt = M.rates(outs)
        lm, ls = M.mean_std(lens)
        lines.append(f"| {label} | {rt['success']:.0%} | {rt['collision']:.0%} | {rt['timeout']:.0%} | "
                     f"{rt['failure']:.0%} | {sides.count('demo side')} / {sides.count('other side')} | {fmt_ms(lm, ls, 2)} |")
        if demo_key[1] is None:
            keys = [k for k in d if k[0] == demo_key[0]]
        else:
            keys = [demo_key]
        for k in keys:
            for e in d[k]:
                ax.plot(e.xy[:, 0], e.xy[:, 1], color="tab:green", lw=0.6, alpha=0.5)
        draw_scene(ax, scene)
        ax.set_title(f"{label}\nsuccess {rt['success']:.0%}", fontsize=9)
    md = ctx.header(title, what)
    md += ("| planner | success | collision | no path (timeout) | other failure | demo side / other side | length (m) |\n"
           "|---|---|---|---|---|---|---|\n" + "\n".join(lines) + "\n")
    ctx.write(name, md, records, fig)
