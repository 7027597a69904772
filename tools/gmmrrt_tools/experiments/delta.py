"""The task-cost floor study: TDM, l_e, side and passing distance against delta and w_task.
"""
from __future__ import annotations

import math
from pathlib import Path
from typing import Dict, List, Sequence, Tuple

import numpy as np

from gmmrrt_tools import metrics as M
from gmmrrt_tools import runner as R
from gmmrrt_tools import scenes as S

from .common import CLEARANCE_M, Ctx, classify, demo_scene, demos, fmt_ms, homotopies, model, record
from .real import real_dir, real_ucy_avoid, real_upo_avoid

# ==================================================================== the delta study

DELTA_GRID = (0.001, 0.01, 0.05, 0.1, 0.3)   # absolute deltas of c = delta / max(p, delta) [1/(m rad)]
DELTA_QUANTILES = (0.05, 0.25, 0.5)           # data-driven: delta = the q-quantile of p over the training points
W_TASK_GRID = (1.0, 5.0)                      # besides the default 2, at delta 0.001 and 0.05


def training_density_quantiles(model_file: Path, points: Sequence[Tuple[Tuple[float, float, float], np.ndarray]],
                               qs: Sequence[float]) -> Dict[float, float]:
    """q-quantiles of the model density p(f) over its own training points: `points` = (person pose, xy array)
    per episode, features f = (d, theta) from the C core, density from the C mixture (gmmrrt_tools.mixture)."""
    from gmmrrt_tools import core, mixture

    m = mixture.Model(str(model_file))
    f = [core.features_from_xy(tuple(person), float(x), float(y)) for person, xy in points for x, y in xy]
    dens = m.density(np.asarray(f))
    return {q: float(np.quantile(dens, q)) for q in qs}


def _delta_configs(quantiles: Dict[float, float]) -> List[Tuple[str, float, float]]:
    """(label, delta, w_task) of every configuration of the study."""
    cfgs = [(f"δ = {d:g}", d, 2.0) for d in DELTA_GRID]
    cfgs += [(f"δ = q{int(100 * q)} ({v:.3g})", v, 2.0) for q, v in quantiles.items()]
    cfgs += [(f"δ = {d:g}, w_task = {w:g}", d, w) for d in (0.001, 0.05) for w in W_TASK_GRID]
    return cfgs


def _delta_row(label, recs, n, human_min=None):
    ok = [r for r in recs if r.get("outcome") == M.SUCCESS]
    tm, ts = M.mean_std([r["tdm_m"] for r in ok])
    lm, ls = M.mean_std([100 * r["le"] for r in ok])
    dm, ds = M.mean_std([r["min_dist_m"] for r in ok])
    em, es = M.mean_std([abs(r["min_dist_m"] - r["ref_min_dist_m"]) for r in ok])
    side = np.mean([r["same_side"] for r in ok]) if ok else math.nan
    return (f"| {label} | {len(ok)}/{n} | {fmt_ms(tm, ts, 3)} | {fmt_ms(lm, ls, 1)} | {100 * side:.0f} % | "
            f"{fmt_ms(dm, ds, 2)} | {fmt_ms(em, es, 2)} |")


def _score_against(res: R.PlanResult, scene: R.Scene, ref_xy: np.ndarray, person) -> dict:
    out = classify(res, scene)
    extra = {"outcome": out, "ref_min_dist_m": M.min_distance_to_people(ref_xy, [person])}
    if out == M.SUCCESS:
        extra.update(tdm_m=M.tdm_pair(ref_xy, res.path), le=M.length_error_pair(ref_xy, res.path),
                     min_dist_m=M.min_distance_to_people(res.path, [person]),
                     same_side=bool(M.same_homotopy(res.path, ref_xy, person)))
    return extra


def exp_delta(ctx: Ctx) -> None:
    """How delta (and w_task) of the task cost c = delta / max(p, delta) shape GMM-RRT*'s paths: TDM, l_e, side
    and passing distance (closest approach to the person) against (a) the synthetic avoid demonstrations
    (Table 1's protocol, per-homotopy models) and (b) the humans of the UPO avoid test split (model learned on
    the train split; skipped, saying so, without the real data)."""
    s = ctx.s
    d = demos(ctx)
    head = ("| configuration | success | TDM (m) | l_e (%) | same side | passing distance (m) | "
            "abs. passing-distance error (m) |\n|---|---|---|---|---|---|---|\n")
    records: List[dict] = []
    md_parts: List[str] = []
    # (a) synthetic demonstrations
    jobs, scenes_, qinfo = [], {}, []
    for hom in homotopies(ctx, "avoid"):
        ds = d[("avoid", hom)]
        mdl = model(ctx, "avoid", hom, "features")
        qs = training_density_quantiles(mdl, [((0.0, 0.0, 0.0), e.xy) for e in ds], DELTA_QUANTILES)
        qinfo.append(f"{hom}: " + ", ".join(f"q{int(100 * q)} = {v:.3g}" for q, v in qs.items()))
        for label, delta, w in _delta_configs(qs):
            key = label.split(" (")[0]
            for i in range(s.trials):
                demo = ds[i % len(ds)]
                scene = scenes_.setdefault(demo.episode_id, demo_scene(ctx, demo))
                jobs.append(({"part": "demos", "homotopy": hom, "config": key, "delta": delta, "w_task": w,
                              "demo": demo.episode_id},
                             ctx.plan(scene, "gmm-rrt-star", s.seed + i, mdl, None, s.bias,
                                      extra=["--delta", repr(delta), "--w-task", repr(w)]), s.seed + i))
    results = ctx.run_plans(jobs, "delta demos")
    by_id = {e.episode_id: e for es in d.values() for e in es}
    table: Dict[str, List[dict]] = {}
    for tag, res in results:
        rec = record(tag, res, **_score_against(res, scenes_[tag["demo"]], by_id[tag["demo"]].xy, (0.0, 0.0, 0.0)))
        records.append(rec)
        table.setdefault(tag["config"], []).append(rec)
    demo_min = M.mean_std([r["ref_min_dist_m"] for r in table[next(iter(table))]])
    md_parts.append(f"### Synthetic avoid demonstrations (logs/demos)\n\nBoth homotopies pooled, {s.trials} trials each "
                    f"(trial i re-plans demonstration i mod 9 with its homotopy's model and is scored against it). "
                    f"The demonstrations' own passing distance: {fmt_ms(*demo_min, 2)} m. Data-driven δ per model "
                    f"(q-quantile of the model's density over its training points): {'; '.join(qinfo)}.\n\n" + head +
                    "\n".join(_delta_row(k, v, len(v)) for k, v in table.items()) + "\n")
    # (b) real data: every episode of each avoid test split, every standing person, model learned on train
    curves: Dict[str, Dict[str, List[dict]]] = {"synthetic (logs/demos)": dict(table)}
    deltas: Dict[str, Dict[str, float]] = {"synthetic (logs/demos)": {}}
    for label, _d, _w in _delta_configs({}):
        deltas["synthetic (logs/demos)"][label.split(" (")[0]] = _d
    for set_name, build, train_files in (("UPO avoid", real_upo_avoid, ("upo_avoid_episodes.csv", "upo_avoid_index.csv")),
                                         ("UCY avoid", real_ucy_avoid, ("ucy_avoid_episodes.csv", "ucy_index.csv"))):
        try:
            rs = build(ctx)
        except (RuntimeError, ValueError) as exc:
            md_parts.append(f"### Real data: {set_name}\n\nNot run: {exc}\n")
            continue
        mdl = rs.planners[0][2]
        real = real_dir(ctx)
        train = S.read_episodes(str(real / train_files[0]), index=str(real / train_files[1]), split=ctx.train_split)
        qs = training_density_quantiles(mdl, [(e.person, e.xy) for e in train], DELTA_QUANTILES)
        cfgs = [c for c in _delta_configs(qs) if c[2] == 2.0]
        deltas[set_name] = {c[0].split(" (")[0]: c[1] for c in cfgs}
        jobs = []
        for k, (e, scene) in enumerate(zip(rs.episodes, rs.scenes)):
            for label, delta, w in cfgs:
                jobs.append(({"part": set_name, "config": label.split(" (")[0], "delta": delta, "w_task": w,
                              "episode": e.episode_id, "k": k, "people": len(scene.people)},
                             ctx.plan(scene, "gmm-rrt-star", s.seed + k, mdl, None, s.bias,
                                      extra=["--task-cost", "paper", "--delta", repr(delta), "--w-task", repr(w)]),
                             s.seed + k))
        results = ctx.run_plans(jobs, f"delta {set_name}")
        table = {}
        for tag, res in results:
            e, scene = rs.episodes[tag["k"]], rs.scenes[tag["k"]]
            rec = record(tag, res, **_score_against(res, scene, e.xy, e.person))
            records.append(rec)
            table.setdefault(tag["config"], []).append(rec)
        curves[set_name] = table
        human_min = M.mean_std([M.min_distance_to_people(e.xy, [e.person]) for e in rs.episodes])
        n_people = [len(sc.people) for sc in rs.scenes]
        md_parts.append(f"### Real data: {set_name} {ctx.split} split ({len(rs.episodes)} episodes, every standing "
                        f"person: {min(n_people)}-{max(n_people)} per episode, mean {np.mean(n_people):.1f})\n\n"
                        f"Model: all homotopies, learned on the {len(train)} {ctx.train_split} episodes; each "
                        f"{ctx.split} episode re-planned with every standing person of its scene (as in "
                        f"`tools/experiments.py real`; seed base + k, the paper's cost form) and scored against what "
                        f"the human did; passing distance = closest approach to the episode's own person. The "
                        f"humans' passing distance: {fmt_ms(*human_min, 2)} m. Data-driven δ: " +
                        ", ".join(f"q{int(100 * q)} = {v:.3g}" for q, v in qs.items()) +
                        ".\n\n" + head + "\n".join(_delta_row(k, v, len(v)) for k, v in table.items()) + "\n")
    fig = _delta_figure(curves, deltas)
    md = ctx.header("The task-cost floor δ: TDM, l_e, side and passing distance vs δ and w_task",
                    "GMM-RRT* with c = δ / max(p, δ) (paper Sect. 4; the paper's δ = 0.001) for fixed δ, for a "
                    "data-driven δ (the q-quantile of the model's own density over its training points) and for "
                    "w_task = 1, 5 besides the default 2. Passing distance = closest approach of the path to the "
                    "person's centre; its error is against the demonstration / human the plan re-does.")
    md_parts.append("\nThe figure: mean TDM and mean absolute passing-distance error against δ for each data set "
                    "(lines: the fixed δ; markers: the data-driven quantiles at the δ they gave, ★ = q25, the "
                    "default).\n")
    ctx.write("delta", md + "\n".join(md_parts), records, fig=fig)


def _delta_figure(curves: Dict[str, Dict[str, List[dict]]], deltas: Dict[str, Dict[str, float]]):
    """TDM and |passing-distance error| against delta, one line per data set (fixed deltas), the
    quantile configurations as markers at their delta."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    markers = {"δ = q5": "v", "δ = q25": "*", "δ = q50": "^"}
    for ci, (name, table) in enumerate(curves.items()):
        color = f"C{ci}"
        for ax, metric in zip(axes, ("tdm", "err")):
            def value(recs):
                ok = [r for r in recs if r.get("outcome") == M.SUCCESS]
                vals = ([r["tdm_m"] for r in ok] if metric == "tdm" else
                        [abs(r["min_dist_m"] - r["ref_min_dist_m"]) for r in ok])
                return float(np.mean(vals)) if vals else math.nan
            fixed = sorted((deltas[name][k], value(v)) for k, v in table.items()
                           if k in deltas.get(name, {}) and not k.startswith("δ = q") and "w_task" not in k)
            if fixed:
                ax.plot(*zip(*fixed), "o-", color=color, label=name)
            for k, mk in markers.items():
                if k in table and k in deltas.get(name, {}):
                    ax.plot(deltas[name][k], value(table[k]), mk, color=color, ms=13 if mk == "*" else 8,
                            mec="k", mew=0.6)
    for ax, ylabel in zip(axes, ("mean TDM vs the human / demonstration (m)", "mean |passing-distance error| (m)")):
        ax.set_xscale("log")
        ax.set_xlabel("δ of c = δ / max(p, δ)  [1/(m rad)]")
        ax.set_ylabel(ylabel)
        ax.grid(alpha=0.3, which="both")
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    return fig
