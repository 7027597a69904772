"""Shared by every study of tools/experiments.py: settings, the run context (paths, the command line,
running gmmrrt-plan in parallel, writing the outputs), scoring, the synthetic demonstrations and their
models, drawing helpers.
"""
from __future__ import annotations

import argparse
import concurrent.futures as cf
import datetime as _dt
import json
import math
import shlex
import subprocess
import sys
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Dict, List, Optional, Sequence, Tuple

import numpy as np

from gmmrrt_tools import metrics as M
from gmmrrt_tools import runner as R
from gmmrrt_tools import scenes as S

ROOT = Path(__file__).resolve().parents[3]  # the repository (tools/gmmrrt_tools/experiments/common.py)

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
    # The paper scores the planner's trajectory: the tree's path (gmmrrt-plan --raw-path). With
    # --drivable the studies score what gmmrrtd publishes instead (shortcuts, turning-radius arcs,
    # the arrival heading; docs/planner.md), which moves some cells (docs/experiments.md).
    drivable: bool = False


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
        s.drivable = bool(getattr(args, "drivable", False))
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
        self.split = getattr(args, "split", None) or "test"
        self.train_split = getattr(args, "train_split", None) or "train"
        self.real_k = getattr(args, "real_k", None)  # K of the real-data models (None: the learner's default)
        self.real_sets = [x for x in (getattr(args, "real_sets", None) or "upo_avoid,ucy_avoid,ucy_approach").split(",")]
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
                           bias=bias, robot_radius_m=ROBOT_RADIUS_M,
                           extra=list(extra) + ([] if self.s.drivable else ["--raw-path"]), bin_dir=self.bin_dir)

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


def model(ctx: Ctx, task: str, homotopy: str = "all", kind: str = "features", background: bool = False) -> Path:
    """The learner's model for task/homotopy/kind, fitted from logs/demos/ into the work folder; with
    background, the file also carries the background of the same demonstrations (their straight lines,
    `gmmrrt-learn fit --background straight`) for the background cost."""
    out = ctx.work / "models" / f"demos_{task}_{homotopy}_{kind}{'_bg' if background else ''}.gmm"
    return R.fit_model(out, task, demo_logs(ctx, task), homotopy=homotopy, kind=kind, seed=ctx.s.seed,
                       bin_dir=ctx.bin_dir, background=background)


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


def legend_handles(items):
    from matplotlib.lines import Line2D
    return [Line2D([0], [0], color=c, lw=2, label=l) for l, c in items]


def draw_scene(ax, scene: R.Scene, endpoints: bool = True):
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
