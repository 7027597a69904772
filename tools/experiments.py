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
    tools/experiments.py table1|fig1|fig3|fig5|fig6|real [--quick] ...
"""
from __future__ import annotations

import argparse
import concurrent.futures as cf
import datetime as _dt
import json
import math
import os
import shlex
import subprocess
import sys
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np

from gmmrrt_tools import metrics as M  # noqa: E402
from gmmrrt_tools import runner as R  # noqa: E402
from gmmrrt_tools import scenes as S  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]

# The paper's Table 1 (TDM [m], l_e [%]; mean ± std over 25 trials). None = not reported.
PAPER_TABLE1 = {
    ("avoid", "right", "GMM-RRT*"): ((0.0565, 0.0152), (3.66, 2.64)),
    ("avoid", "right", "GMM-RRT"): ((0.0803, 0.0205), (4.00, 2.51)),
    ("avoid", "left", "GMM-RRT*"): ((0.0484, 0.0109), (4.96, 2.37)),
    ("avoid", "left", "GMM-RRT"): ((0.0676, 0.0169), (4.31, 3.1)),
    ("approach", "right", "GMM-RRT*"): ((0.0906, 0.0176), (3.69, 2.54)),
    ("approach", "right", "GMM-RRT"): ((0.0917, 0.0161), (4.96, 3.45)),
    ("approach", "left", "GMM-RRT*"): ((0.0612, 0.0218), (4.22, 2.50)),
    ("approach", "left", "GMM-RRT"): ((0.0666, 0.0169), (4.56, 3.62)),
    ("approach", "frontal", "GMM-RRT*"): ((0.0376, 0.0141), (11.35, 5.35)),
    ("approach", "frontal", "GMM-RRT"): ((0.0337, 0.0184), (8.55, 3.34)),
}

# Collision check radii = the planner's documented defaults (planner/src/config.c); they are also
# passed explicitly so the two cannot drift apart.
ROBOT_RADIUS_M = 0.3
PERSON_RADIUS_M = 0.25
# The GMM-RRT baseline samples only from its mixture: the paper (Sect. 5.3) says the mixed 95/5
# sampling "is only applicable to the GMM-RRT* planner presented in this paper".
GMM_RRT_BIAS = 1.0
# A path counts as colliding when it overlaps an obstacle or person disc by more than this: the
# planner checks edges every 5 cm (edge_resolution_m), so a chord can graze a box corner by a
# fraction of a millimetre (seen: 0.2 mm) without being a collision in any practical sense.
COLLISION_TOLERANCE_M = 0.01
# The lab's approach models, set 'tasks' (the lab's main set). Its two-homotopy entries (3-90 .. 7-90)
# store two one-homotopy mixtures side by side with priors summing to 2; gmmrrt-learn import reads
# them as their equal-weight union (docs/learner.md).
UPO_APPROACH_SET = "tasks"
# Real episodes: a start or goal closer than this to the person is pushed out to it (valid problem).
CLEARANCE_M = ROBOT_RADIUS_M + PERSON_RADIUS_M + 0.05


@dataclass
class Settings:
    trials: int = 25
    iterations: int = 4000          # Table 1 / Fig. 5 / Fig. 6 / real: iteration cap per run
    gmm_rrt_iterations: int = 4000  # the baseline RRT stops at its first solution anyway
    fig1_iterations: int = 8000
    fig3_budgets: Tuple[int, ...] = (250, 500, 1000, 2000, 4000, 8000)
    fig5_gmm_rrt_factor: int = 10   # paper: 3 s for GMM-RRT* vs 100 s for GMM-RRT
    real_max_episodes: int = 0      # 0 = every test episode
    budget_ms: int = 60000          # safety net only
    bias: float = 0.95
    seed: int = 1
    jobs: int = 1
    quick: bool = False


QUICK = dict(trials=5, iterations=1500, gmm_rrt_iterations=1500, fig1_iterations=2000,
             fig3_budgets=(250, 500, 1000, 2000), real_max_episodes=12)


class Ctx:
    """Settings, paths and the command line that made the outputs."""

    def __init__(self, args: argparse.Namespace):
        s = Settings()
        if args.quick:
            for k, v in QUICK.items():
                setattr(s, k, v)
            s.quick = True
        if getattr(args, "max_episodes", None) is not None:
            s.real_max_episodes = args.max_episodes
        for k in ("trials", "iterations", "seed", "jobs"):
            v = getattr(args, k, None)
            if v is not None:
                setattr(s, k, v)
        self.s = s
        self.out = Path(args.out)
        self.out.mkdir(parents=True, exist_ok=True)
        self.work = Path(args.work)
        self.work.mkdir(parents=True, exist_ok=True)
        self.bin_dir = args.bin_dir
        self.demos_dir = args.demos_dir
        self.real = Path(args.real_data) if args.real_data else None
        global _REAL_DIR
        _REAL_DIR = str(self.real) if self.real else None
        self.command = "tools/experiments.py " + " ".join(shlex.quote(a) for a in sys.argv[1:])
        self.suffix = "-quick" if s.quick else ""
        try:
            self.commit = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"],
                                         capture_output=True, text=True).stdout.strip()
        except OSError:
            self.commit = "?"

    # ---------------------------------------------------------------- running
    def run_plans(self, jobs: List[Tuple[dict, List[str], int]], desc: str) -> List[Tuple[dict, R.PlanResult]]:
        """Runs gmmrrt-plan for each (tag, argv, seed) with a progress bar; results in input order."""
        from tqdm import tqdm

        results: List[Optional[Tuple[dict, R.PlanResult]]] = [None] * len(jobs)
        with cf.ThreadPoolExecutor(max_workers=max(1, self.s.jobs)) as ex:
            futs = {ex.submit(R.run_plan, argv, seed): i for i, (_, argv, seed) in enumerate(jobs)}
            for fut in tqdm(cf.as_completed(futs), total=len(futs), desc=desc, unit="run", file=sys.stderr):
                i = futs[fut]
                results[i] = (jobs[i][0], fut.result())
        errors = [r for _, r in results if r.status.startswith("error")]  # type: ignore[union-attr]
        if errors and len(errors) == len(results):
            raise R.ToolFailed(f"every gmmrrt-plan run of {desc} failed; the first: {errors[0].status}\n"
                               f"  command: {shlex.join(errors[0].argv)}")
        if errors:
            print(f"{desc}: {len(errors)} of {len(results)} runs ended without a result (recorded as failures; "
                  f"first: {errors[0].status})", file=sys.stderr)
        return results  # type: ignore[return-value]

    def plan(self, scene: R.Scene, planner: str, seed: int, model: Optional[Path] = None,
             iterations: Optional[int] = None, bias: Optional[float] = None,
             extra: Sequence[str] = ()) -> List[str]:
        return R.plan_argv(scene, planner, seed, model=str(model) if model else None,
                           iterations=iterations or self.s.iterations, budget_ms=self.s.budget_ms,
                           bias=bias, robot_radius_m=ROBOT_RADIUS_M, extra=extra, bin_dir=self.bin_dir)

    # ---------------------------------------------------------------- outputs
    def header(self, title: str, what: str) -> str:
        s = self.s
        return (f"# {title}\n\n{what}\n\nMade by `{self.command}` at commit {self.commit} on "
                f"{_dt.datetime.utcnow():%Y-%m-%d %H:%M} UTC ({'quick' if s.quick else 'full'} settings: "
                f"{s.trials} trials, base seed {s.seed}, iteration cap {s.iterations}, robot radius "
                f"{ROBOT_RADIUS_M} m). Seeds and the command line of every run are in the JSON next to this file.\n\n")

    def write(self, name: str, markdown: str, records: list, fig=None) -> None:
        base = self.out / (name + self.suffix)
        if fig is not None:
            fig.savefig(str(base) + ".png", dpi=110, bbox_inches="tight")
            markdown += f"\n![{name}]({base.name}.png)\n"
        tmp = Path(str(base) + ".md.tmp")
        tmp.write_text(markdown)
        tmp.replace(str(base) + ".md")
        jt = Path(str(base) + ".json.tmp")
        jt.write_text(json.dumps({"command": self.command, "commit": self.commit, "settings": asdict(self.s),
                                  "runs": records}, separators=(",", ":"), default=_json_default))
        jt.replace(str(base) + ".json")
        print(f"wrote {base}.md" + (f", {base}.png" if fig is not None else "") + f", {base}.json")


def _json_default(o):
    if isinstance(o, (np.floating, np.integer)):
        return o.item()
    if isinstance(o, np.ndarray):
        return o.tolist()
    if isinstance(o, tuple):
        return list(o)
    raise TypeError(type(o))


def fmt_ms(mean: float, std: float, digits: int = 4) -> str:
    if not np.isfinite(mean):
        return "–"
    return f"{mean:.{digits}f} ± {std:.{digits}f}"


def record(tag: dict, res: R.PlanResult, **extra) -> dict:
    st = res.stats
    return {**tag, "seed": res.seed, "status": res.status, "path_points": len(res.path),
            **{k: st.get(k) for k in ("iterations", "nodes", "first_solution_ms", "best_cost", "time_ms")},
            "argv": portable(" ".join(shlex.quote(a) for a in res.argv[1:])), **extra}


def portable(text: str) -> str:
    """Paths in recorded command lines relative to the repository, real data as $GMMRRT_REAL_DATA."""
    if _REAL_DIR:
        for form in {str(Path(_REAL_DIR).resolve()), str(_REAL_DIR).rstrip("/")}:
            text = text.replace(form + "/", "$GMMRRT_REAL_DATA/")
    return text.replace(str(ROOT) + "/", "")


_REAL_DIR: Optional[str] = None


def classify(res: R.PlanResult, scene: R.Scene) -> str:
    return M.outcome(res.status, res.path, scene.goal, circles=scene.circles, boxes=scene.boxes,
                     people=scene.people, robot_radius_m=ROBOT_RADIUS_M, person_radius_m=PERSON_RADIUS_M,
                     tolerance_m=COLLISION_TOLERANCE_M)


# ==================================================================== demonstrations and models

_DEMOS: Optional[Dict[Tuple[str, str], List[S.Episode]]] = None


def demos(ctx: Ctx) -> Dict[Tuple[str, str], List[S.Episode]]:
    """logs/demos/ in the person frame, grouped by (task, homotopy)."""
    global _DEMOS
    if _DEMOS is None:
        eps = [S.to_person_frame(e) for e in S.load_demo_logs(ctx.demos_dir)]
        _DEMOS = {}
        for e in eps:
            _DEMOS.setdefault((e.task, e.homotopy), []).append(e)
    return _DEMOS


def demo_logs(ctx: Ctx, task: str) -> List[str]:
    """The task's logs (logs/demos/<task>_*.lcmlog), or every log when none is named so; the learner
    keeps the episodes labelled with the task either way."""
    logs = sorted(str(p) for p in Path(ctx.demos_dir).glob(f"{task}_*.lcmlog"))
    return logs or sorted(str(p) for p in Path(ctx.demos_dir).glob("*.lcmlog"))


def model(ctx: Ctx, task: str, homotopy: str = "all", kind: str = "features") -> Path:
    """The learner's model for task/homotopy/kind, fitted from logs/demos/ into the work folder."""
    out = ctx.work / "models" / f"demos_{task}_{homotopy}_{kind}.gmm"
    return R.fit_model(out, task, demo_logs(ctx, task), homotopy=homotopy, kind=kind, seed=ctx.s.seed,
                       bin_dir=ctx.bin_dir)


def demo_scene(ctx: Ctx, demo: S.Episode) -> R.Scene:
    """The problem the demonstrator solved, in the person frame: from its first to its last point
    (pushed out to CLEARANCE_M from the person if closer), bounds around all demonstrations of the
    task plus 1 m."""
    every = [e for (t, _), es in demos(ctx).items() if t == demo.task for e in es]
    sc = S.episode_scene(demo, margin_m=1.0, clearance_m=CLEARANCE_M)
    pts = np.vstack([e.xy for e in every] + [np.zeros((1, 2))])
    return R.Scene(sc.start, sc.goal, sc.people, S.bounds_of(pts, 1.0))


def medoid(ds: List[S.Episode]) -> S.Episode:
    """The demonstration whose start and goal are closest to the mean start and goal of `ds`."""
    ms, mg = np.mean([e.xy[0] for e in ds], axis=0), np.mean([e.xy[-1] for e in ds], axis=0)
    return min(ds, key=lambda e: float(np.linalg.norm(e.xy[0] - ms) + np.linalg.norm(e.xy[-1] - mg)))


def task_scene(ctx: Ctx, task: str, homotopy: str) -> R.Scene:
    """The scene of the homotopy's most typical demonstration (see medoid)."""
    return demo_scene(ctx, medoid(demos(ctx)[(task, homotopy)]))


def homotopies(ctx: Ctx, task: str) -> List[str]:
    order = {"right": 0, "left": 1, "frontal": 2}
    return sorted({h for (t, h) in demos(ctx) if t == task}, key=lambda h: order.get(h, 9))


# ==================================================================== Table 1

PLANNERS_T1 = [  # label, planner, model homotopy ("row" = the row's homotopy, "all" = the task model), kind
    ("GMM-RRT*", "gmm-rrt-star", "row", "features"),
    ("GMM-RRT* (task model)", "gmm-rrt-star", "all", "features"),
    ("GMM-RRT", "gmm-rrt", "row", "xy"),
    ("RRT*", "rrt-star", None, None),
]


def exp_table1(ctx: Ctx) -> None:
    """Trial i of a (task, homotopy, planner) cell re-plans demonstration i mod 9 of that homotopy: its
    start, goal and person (person frame), scored against that demonstration (eqs. (2)-(4) with
    |D| = |P| = 1). The synthetic demonstrations vary start, goal and person pose, so one fixed scene
    scored against all nine (the paper's set-up, where the nine were recorded in one set-up) would
    measure the spread of the demonstrations rather than the planner."""
    s = ctx.s
    d = demos(ctx)
    jobs, scenes_ = [], {}
    for task in ("avoid", "approach"):
        for hom in homotopies(ctx, task):
            ds = d[(task, hom)]
            for label, planner, mh, kind in PLANNERS_T1:
                mdl = model(ctx, task, hom if mh == "row" else "all", kind) if mh else None
                iters = s.gmm_rrt_iterations if planner == "gmm-rrt" else s.iterations
                for i in range(s.trials):
                    demo = ds[i % len(ds)]
                    scene = scenes_.setdefault(demo.episode_id, demo_scene(ctx, demo))
                    seed = s.seed + i
                    tag = {"task": task, "homotopy": hom, "planner": label, "demo": demo.episode_id}
                    jobs.append((tag, ctx.plan(scene, planner, seed, mdl, iters,
                                               s.bias if planner == "gmm-rrt-star" else GMM_RRT_BIAS), seed))
    results = ctx.run_plans(jobs, "table1")
    by_id = {e.episode_id: e for es in d.values() for e in es}
    records, cells = [], {}
    for tag, res in results:
        scene = scenes_[tag["demo"]]
        demo = by_id[tag["demo"]]
        out = classify(res, scene)
        extra = {"outcome": out}
        if res.path:
            side = M.passing_side(res.path, (0.0, 0.0, 0.0))
            extra.update(side=side, same_homotopy=M.same_homotopy(res.path, demo.xy, (0.0, 0.0, 0.0)),
                         tdm_m=M.tdm_pair(demo.xy, res.path), le=M.length_error_pair(demo.xy, res.path))
        rec = record(tag, res, **extra)
        records.append(rec)
        cells.setdefault((tag["task"], tag["homotopy"], tag["planner"]), []).append(rec)

    lines = ["| Homotopy | Planner | Avoid TDM (m) | Avoid l_e (%) | Approach TDM (m) | Approach l_e (%) | "
             "success (avoid / approach) | same side as the demo (avoid / approach) | paper avoid TDM, l_e (%) | "
             "paper approach TDM, l_e (%) |", "|---|---|---|---|---|---|---|---|---|---|"]
    for hom in ("right", "left", "frontal"):
        for label, *_ in PLANNERS_T1:
            row = [hom.capitalize(), label]
            succ, side, paper = [], [], []
            any_cell = False
            for task in ("avoid", "approach"):
                recs = cells.get((task, hom, label), [])
                any_cell = any_cell or bool(recs)
                ok = [r for r in recs if r["outcome"] == M.SUCCESS]
                tm, ts = M.mean_std([r["tdm_m"] for r in ok])
                lm, ls = M.mean_std([100.0 * r["le"] for r in ok])
                row += [fmt_ms(tm, ts), fmt_ms(lm, ls, 2)]
                succ.append(f"{len(ok)}/{len(recs)}" if recs else "–")
                side.append(f"{sum(bool(r['same_homotopy']) for r in ok)}/{len(ok)}" if recs else "–")
                p = PAPER_TABLE1.get((task, hom, label))
                paper.append(f"{p[0][0]:.4f} ± {p[0][1]:.4f}, {p[1][0]:.2f} ± {p[1][1]:.2f}" if p else "–")
            if any_cell:
                lines.append("| " + " | ".join(row + [" / ".join(succ), " / ".join(side)] + paper) + " |")
    md = ctx.header(
        "Table 1: trajectory quality, GMM-RRT* vs GMM-RRT vs RRT*",
        "Synthetic demonstrations of logs/demos/ (9 per task and homotopy), in the person's frame. Trial i of each "
        "cell re-plans demonstration i mod 9 (its start, goal and person) and is scored against it: TDM (eq. (2), "
        "the mean distance from the demonstration's points to the planned polyline) and l_e (eq. (4)); mean ± std "
        "over the successful trials. The paper's nine demonstrations share one set-up, ours vary start, goal and "
        "person pose, hence one demonstration per trial instead of all nine (see docs/experiments.md). GMM-RRT* "
        "uses the features model of the row's homotopy and bias 0.95; 'GMM-RRT* (task model)' one model of all "
        "the task's homotopies (the paper's Sect. 5.1: one model per task); GMM-RRT the x-y model of the row's "
        "homotopy; RRT* no model. Models are learned from the same demonstrations, as in the paper (no hold-out). "
        "'same side' = the plan passes the person on the same side as the demonstration (swept bearing angles "
        "within pi, metrics.same_homotopy). Smaller is better.")
    md += "\n".join(lines) + "\n"
    ctx.write("table1", md, records, fig=_table1_figure(ctx, results, scenes_))


def _table1_figure(ctx, results, scenes_):
    import matplotlib.pyplot as plt

    keys = sorted({(t["task"], t["homotopy"]) for t, _ in results}, key=lambda k: (k[0] != "avoid", k[1]))
    fig, axes = plt.subplots(1, len(keys), figsize=(4.2 * len(keys), 4.2), squeeze=False)
    colors = {"GMM-RRT*": "tab:red", "GMM-RRT": "tab:blue", "RRT*": "tab:gray", "GMM-RRT* (task model)": "tab:orange"}
    d = demos(ctx)
    for ax, key in zip(axes[0], keys):
        for e in d[key]:
            ax.plot(e.xy[:, 0], e.xy[:, 1], color="tab:green", lw=1.0, alpha=0.8)
        for tag, res in results:
            if (tag["task"], tag["homotopy"]) == key and res.path and tag["planner"] in ("GMM-RRT*", "GMM-RRT"):
                p = np.asarray(res.path)
                ax.plot(p[:, 0], p[:, 1], color=colors[tag["planner"]], lw=0.7, alpha=0.5)
        _draw_scene(ax, demo_scene(ctx, medoid(d[key])), endpoints=False)
        ax.set_title(f"{key[0]} / {key[1]}")
    axes[0][0].legend(handles=_legend([("demonstrations", "tab:green"), ("GMM-RRT*", "tab:red"),
                                       ("GMM-RRT", "tab:blue")]), loc="best", fontsize=8)
    fig.suptitle("Demonstrated (green) and planned paths, person frame (cf. paper Fig. 2)")
    return fig


def _legend(items):
    from matplotlib.lines import Line2D
    return [Line2D([0], [0], color=c, lw=2, label=l) for l, c in items]


def _draw_scene(ax, scene: R.Scene, endpoints: bool = True):
    import matplotlib.patches as mp

    for (x, y, yaw) in scene.people:
        ax.add_patch(mp.Circle((x, y), PERSON_RADIUS_M, color="k", fill=False))
        tri = np.array([[0.35, 0.0], [-0.15, 0.2], [-0.15, -0.2]])
        c, s_ = math.cos(yaw), math.sin(yaw)
        pts = tri @ np.array([[c, s_], [-s_, c]]) + [x, y]
        ax.add_patch(mp.Polygon(pts, closed=True, color="k"))
    for (cx, cy, w, h, yaw) in scene.boxes:
        ax.add_patch(mp.Rectangle((cx - w / 2, cy - h / 2), w, h, angle=math.degrees(yaw),
                                  rotation_point="center", color="0.6", alpha=0.6))
    for (x, y, r) in scene.circles:
        ax.add_patch(mp.Circle((x, y), r, color="0.6", alpha=0.6))
    if endpoints:
        ax.plot(*scene.start, "ko", ms=5)
        ax.plot(*scene.goal, "k*", ms=9)
    b = scene.bounds
    ax.set_xlim(b[0], b[2])
    ax.set_ylim(b[1], b[3])
    ax.set_aspect("equal")
    ax.grid(alpha=0.3)


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
        _draw_scene(ax, scene)
        ax.set_title(f"{label}\nsuccess {rt['success']:.0%}", fontsize=9)
    md = ctx.header(title, what)
    md += ("| planner | success | collision | no path (timeout) | other failure | demo side / other side | length (m) |\n"
           "|---|---|---|---|---|---|---|\n" + "\n".join(lines) + "\n")
    ctx.write(name, md, records, fig)


# ==================================================================== real data

def _real(ctx: Ctx) -> Path:
    if ctx.real is None or not (ctx.real / "upo_avoid_episodes.csv").is_file():
        raise RuntimeError(f"real data not found at {ctx.real} (set GMMRRT_REAL_DATA or --real-data to the folder "
                           f"of ../shared/data/real): the real-data experiment is skipped")
    return ctx.real


def _social_row(paths, people_of, human_of=None, sides=None, true_sides=None, approach=False):
    vals: Dict[str, List[float]] = {}
    for i, p in enumerate(paths):
        if p is None:
            continue
        sm = M.social_metrics(p, [people_of[i]])
        for k, v in sm.items():
            vals.setdefault(k, []).append(v)
        if human_of is not None:
            vals.setdefault("tdm_m", []).append(M.tdm_pair(human_of[i], p))
            vals.setdefault("le", []).append(100 * M.length_error_pair(human_of[i], p))
        if sides is not None and human_of is not None:
            vals.setdefault("same_side", []).append(
                1.0 if M.same_homotopy(p, human_of[i], people_of[i]) else 0.0)
        if approach:
            vals.setdefault("final_heading_err_deg", []).append(
                math.degrees(M.approach_end(p, people_of[i]).heading_error_rad))
            vals.setdefault("final_dist_m", []).append(M.approach_end(p, people_of[i]).final_distance_m)
    return vals


def _plan_episodes(ctx, eps, planners, desc):
    jobs = []
    for k, e in enumerate(eps):
        scene = S.episode_scene(e, clearance_m=CLEARANCE_M)
        for label, planner, mdl, bias in planners:
            seed = ctx.s.seed + k
            jobs.append(({"episode": e.episode_id, "planner": label, "k": k}, ctx.plan(scene, planner, seed, mdl,
                                                                                      None, bias), seed))
    return ctx.run_plans(jobs, desc)


def _real_table(ctx, eps, results, labels, approach):
    people = [e.person for e in eps]
    human = [e.xy for e in eps]
    true_sides = [e.homotopy for e in eps]
    rows, records = {}, []
    by_label = {l: [None] * len(eps) for l in labels}
    outcomes = {l: [] for l in labels}
    for tag, res in results:
        scene = S.episode_scene(eps[tag["k"]], clearance_m=CLEARANCE_M)
        o = classify(res, scene)
        outcomes[tag["planner"]].append(o)
        if o in (M.SUCCESS, M.COLLISION) and res.path:
            by_label[tag["planner"]][tag["k"]] = res.path
        records.append(record(tag, res, outcome=o))
    straight = []
    for e in eps:
        sc = S.episode_scene(e, clearance_m=CLEARANCE_M)
        straight.append(np.array([sc.start, sc.goal]))
    cols = [("success", None)]
    table = []
    metrics_cols = (["tdm_m", "le"] + ([] if approach else ["same_side"]) + ["min_dist_person_m", "frac_within_0.45m",
                    "frac_within_1.2m", "smoothness_rad", "length_m"] + (["final_dist_m", "final_heading_err_deg"] if approach else []))

    def side_list(paths):
        return [M.passing_side(p, eps[i].person) if p is not None else None for i, p in enumerate(paths)]

    series = [("human (reference)", human, None)]
    for l in labels:
        series.append((l, by_label[l], M.rates(outcomes[l])))
    series.append(("straight line", straight, None))
    for name, paths, rt in series:
        v = _social_row(paths, people, None if name.startswith("human") else human,
                        None if approach else side_list(paths), true_sides, approach)
        cells = [name, f"{rt['success']:.0%} ({rt['collision']:.0%} coll.)" if rt else
                 ("–" if name.startswith("human") else f"{100 * np.mean([M.path_collides(p, people=[eps[i].person], robot_radius_m=ROBOT_RADIUS_M, person_radius_m=PERSON_RADIUS_M, tolerance_m=COLLISION_TOLERANCE_M) for i, p in enumerate(paths)]):.0f} % coll.")]
        for c in metrics_cols:
            m_, s_ = M.mean_std(v.get(c, []))
            if c == "same_side":
                cells.append("–" if not np.isfinite(m_) else f"{100 * m_:.0f} %")
            elif c.startswith("frac"):
                cells.append(fmt_ms(100 * m_, 100 * s_, 1))
            else:
                cells.append(fmt_ms(m_, s_, 3 if c in ("tdm_m",) else 2))
        table.append("| " + " | ".join(cells) + " |")
    head = ["planner", "success"] + [{"tdm_m": "TDM vs human (m)", "le": "l_e vs human (%)", "same_side": "same side",
                                      "min_dist_person_m": "min dist. person (m)", "frac_within_0.45m": "% path < 0.45 m",
                                      "frac_within_1.2m": "% path < 1.2 m", "smoothness_rad": "heading change (rad)",
                                      "length_m": "length (m)", "final_dist_m": "final dist. (m)",
                                      "final_heading_err_deg": "final heading err. (deg)"}[c] for c in metrics_cols]
    md = "| " + " | ".join(head) + " |\n|" + "---|" * len(head) + "\n" + "\n".join(table) + "\n"
    return md, records, by_label, straight


def exp_real(ctx: Ctx) -> None:
    s = ctx.s
    real = _real(ctx)
    ep_csv, idx = str(real / "upo_avoid_episodes.csv"), str(real / "upo_avoid_index.csv")
    mdl = R.fit_model(ctx.work / "models" / "upo_avoid_train_all.gmm", "avoid", [ep_csv], homotopy="all",
                      seed=s.seed, index=idx, split="train", bin_dir=ctx.bin_dir)
    eps = S.read_episodes(ep_csv, index=idx, split="test")
    if s.real_max_episodes:
        eps = eps[:: max(1, len(eps) // s.real_max_episodes)][: s.real_max_episodes]
    planners = [("GMM-RRT*", "gmm-rrt-star", mdl, s.bias), ("RRT*", "rrt-star", None, None)]
    results = _plan_episodes(ctx, eps, planners, "real upo avoid")
    md_tab, records, by_label, straight = _real_table(ctx, eps, results, [p[0] for p in planners], approach=False)
    md = ctx.header("Real data: UPO avoid, learned on the train split, evaluated on the test split",
                    f"Avoid model (all homotopies, features) fitted by `gmmrrt-learn fit --index upo_avoid_index.csv "
                    f"--split train` on $GMMRRT_REAL_DATA/upo_avoid_episodes.csv; for each of the {len(eps)} test episodes, plans from the mover's first "
                    "to its last position around the episode's person (other people ignored), compared with what the "
                    "human drove: TDM (human points to the planned polyline), l_e, whether the plan passes the person "
                    "on the same side as the human, social metrics. Straight line = start to goal. 'coll.' = within "
                    f"robot ({ROBOT_RADIUS_M} m) + person ({PERSON_RADIUS_M} m) radius of the person.")
    md += md_tab
    fig = _real_figure(eps, by_label, "UPO avoid test episodes (person frame)")
    ctx.write("real_upo_avoid", md, records, fig)
    _real_ucy_approach(ctx)


def _real_ucy_approach(ctx: Ctx) -> None:
    s = ctx.s
    real = _real(ctx)
    gmms = real / "upo_approach_gmms.json"
    eps = S.read_episodes(str(real / "ucy_approach_episodes.csv"), index=str(real / "ucy_index.csv"))
    models = {}
    for e in eps:
        name = (e.meta or {}).get("upo_task") or ""
        if not name:
            continue
        if name not in models:
            out = ctx.work / "models" / f"upo_approach_{name}.gmm"
            if not out.exists():
                out.parent.mkdir(parents=True, exist_ok=True)
                R.learn(["import", "--json", str(gmms), "--set", UPO_APPROACH_SET, "--task-name", name, "--task", "approach",
                         "-o", str(out)], ctx.bin_dir)
            models[name] = out
    eps = [e for e in eps if (e.meta or {}).get("upo_task") in models]
    if s.real_max_episodes:
        eps = eps[:: max(1, len(eps) // s.real_max_episodes)][: s.real_max_episodes]
    jobs = []
    for k, e in enumerate(eps):
        scene = S.episode_scene(e, clearance_m=CLEARANCE_M)
        for label, planner, bias in (("GMM-RRT* (lab's model)", "gmm-rrt-star", s.bias), ("RRT*", "rrt-star", None)):
            mdl = models[e.meta["upo_task"]] if planner == "gmm-rrt-star" else None
            jobs.append(({"episode": e.episode_id, "planner": label, "k": k},
                          ctx.plan(scene, planner, s.seed + k, mdl, None, bias), s.seed + k))
    results = ctx.run_plans(jobs, "real ucy approach")
    md_tab, records, by_label, _ = _real_table(ctx, eps, results, ["GMM-RRT* (lab's model)", "RRT*"], approach=True)
    md = ctx.header("Real data: the lab's published approach models against the UCY approach episodes",
                    f"{gmms.name} (set {UPO_APPROACH_SET}; its two-homotopy mixtures, priors summing to 2, are imported as "
                    f"the equal-weight union) imported with `gmmrrt-learn import`, one model per approach direction (the index's "
                    f"upo_task column); all {len(eps)} UCY approach episodes are held-out data for these models (they were "
                    "learned by the UPO lab on their robot data). Final heading error = angle between the path's last "
                    "segment and the bearing to the person.")
    md += md_tab
    fig = _real_figure(eps, by_label, "UCY approach episodes (person frame)")
    ctx.write("real_ucy_approach", md, records, fig)


def _real_figure(eps, by_label, title, n=6):
    import matplotlib.pyplot as plt
    from gmmrrt_tools import core

    pick = eps[:: max(1, len(eps) // n)][:n]
    fig, axes = plt.subplots(1, len(pick), figsize=(3.4 * len(pick), 3.6), squeeze=False)
    colors = {"GMM-RRT*": "tab:red", "GMM-RRT* (lab's model)": "tab:red", "RRT*": "tab:gray"}
    for ax, e in zip(axes[0], pick):
        k = eps.index(e)
        def pf(p):
            return np.array([core.world_to_person(e.person, x, y) for x, y in p])
        h = pf(e.xy)
        ax.plot(h[:, 0], h[:, 1], color="tab:green", lw=1.5)
        for l, paths in by_label.items():
            if paths[k] is not None:
                p = pf(paths[k])
                ax.plot(p[:, 0], p[:, 1], color=colors.get(l, "tab:blue"), lw=1)
        ax.add_patch(__import__("matplotlib.patches", fromlist=["Circle"]).Circle((0, 0), PERSON_RADIUS_M, fill=False))
        ax.arrow(0, 0, 0.4, 0, head_width=0.12, color="k")
        ax.set_aspect("equal")
        ax.set_title(e.episode_id, fontsize=8)
        ax.grid(alpha=0.3)
    axes[0][0].legend(handles=_legend([("human", "tab:green"), ("GMM-RRT*", "tab:red"), ("RRT*", "tab:gray")]),
                      fontsize=7)
    fig.suptitle(title)
    return fig


# ==================================================================== docs

REPORT_ORDER = [("table1", "Table 1"), ("fig1", "Fig. 1"), ("fig3", "Fig. 3"), ("fig5", "Fig. 5"), ("fig6", "Fig. 6"),
                ("real_upo_avoid", "Real data: UPO avoid"), ("real_ucy_approach", "Real data: UCY approach"),
                ("delta", "The task-cost floor δ")]
REPORT_MARK = "<!-- RESULTS (tools/experiments.py report writes everything below this line) -->"


def write_report(out_dir: Path, doc: Path) -> None:
    """Copies the result tables of out_dir (docs/results) into doc (docs/experiments.md) below
    REPORT_MARK, headings demoted, figures linked: the docs quote only numbers the runs wrote."""
    text = doc.read_text()
    if REPORT_MARK not in text:
        raise RuntimeError(f"{doc}: no line '{REPORT_MARK}' to write the results under")
    parts = [text.split(REPORT_MARK)[0] + REPORT_MARK + "\n"]
    rel = os.path.relpath(out_dir, doc.parent)
    missing = []
    for name, title in REPORT_ORDER:
        md = out_dir / f"{name}.md"
        if not md.is_file():
            missing.append(name)
            continue
        body = md.read_text().replace(f"]({name}.png)", f"]({rel}/{name}.png)")
        body = "\n".join(("##" + line) if line.startswith("# ") else line for line in body.splitlines())
        parts.append("\n" + body.strip() + "\n")
    if missing:
        parts.append("\nNot run yet: " + ", ".join(missing) + "\n")
    tmp = doc.with_suffix(".md.tmp")
    tmp.write_text("".join(parts))
    tmp.replace(doc)
    print(f"wrote the results section of {doc}" + (f" (missing: {', '.join(missing)})" if missing else ""))


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
    # (b) real data
    try:
        real = _real(ctx)
    except RuntimeError as exc:
        md_parts.append(f"### Real data\n\nNot run: {exc}\n")
        real = None
    if real is not None:
        ep_csv, idx = str(real / "upo_avoid_episodes.csv"), str(real / "upo_avoid_index.csv")
        mdl = R.fit_model(ctx.work / "models" / "upo_avoid_train_all.gmm", "avoid", [ep_csv], homotopy="all",
                          seed=s.seed, index=idx, split="train", bin_dir=ctx.bin_dir)
        train = S.read_episodes(ep_csv, index=idx, split="train")
        qs = training_density_quantiles(mdl, [(e.person, e.xy) for e in train], DELTA_QUANTILES)
        eps = S.read_episodes(ep_csv, index=idx, split="test")
        if s.real_max_episodes:
            eps = eps[:: max(1, len(eps) // s.real_max_episodes)][: s.real_max_episodes]
        cfgs = [c for c in _delta_configs(qs) if c[2] == 2.0]
        jobs = []
        for k, e in enumerate(eps):
            scene = S.episode_scene(e, clearance_m=CLEARANCE_M)
            for label, delta, w in cfgs:
                jobs.append(({"part": "real", "config": label.split(" (")[0], "delta": delta, "w_task": w,
                              "episode": e.episode_id, "k": k},
                             ctx.plan(scene, "gmm-rrt-star", s.seed + k, mdl, None, s.bias,
                                      extra=["--delta", repr(delta), "--w-task", repr(w)]), s.seed + k))
        results = ctx.run_plans(jobs, "delta real")
        table = {}
        for tag, res in results:
            e = eps[tag["k"]]
            rec = record(tag, res, **_score_against(res, S.episode_scene(e, clearance_m=CLEARANCE_M), e.xy, e.person))
            records.append(rec)
            table.setdefault(tag["config"], []).append(rec)
        human_min = M.mean_std([M.min_distance_to_people(e.xy, [e.person]) for e in eps])
        md_parts.append(f"### Real data: UPO avoid test split ({len(eps)} episodes)\n\nModel: all homotopies, learned "
                        f"on the {len(train)} train episodes; each test episode re-planned (seed base + k) and scored "
                        f"against what the human drove. The humans' passing distance: {fmt_ms(*human_min, 2)} m. "
                        f"Data-driven δ: " + ", ".join(f"q{int(100 * q)} = {v:.3g}" for q, v in qs.items()) +
                        ".\n\n" + head + "\n".join(_delta_row(k, v, len(v)) for k, v in table.items()) + "\n")
    md = ctx.header("The task-cost floor δ: TDM, l_e, side and passing distance vs δ and w_task",
                    "GMM-RRT* with c = δ / max(p, δ) (paper Sect. 4; the paper's δ = 0.001) for fixed δ, for a "
                    "data-driven δ (the q-quantile of the model's own density over its training points) and for "
                    "w_task = 1, 5 besides the default 2. Passing distance = closest approach of the path to the "
                    "person's centre; its error is against the demonstration / human the plan re-does.")
    ctx.write("delta", md + "\n".join(md_parts), records)


# ==================================================================== CLI

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
    args = ap.parse_args(argv)
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
