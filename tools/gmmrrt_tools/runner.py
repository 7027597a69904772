"""Drives the project's executables from Python: gmmrrt-plan and gmmrrt-learn.

No planning or learning happens here: every number comes from the C/C++ programs, called with the
command lines their --help documents. Executables are looked up in $GMMRRT_BIN_DIR, then
<repo>/build/bin, then PATH; a missing one raises MissingTool naming what to build.
"""
from __future__ import annotations

import json
import os
import shlex
import shutil
import subprocess
from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, List, Optional, Sequence, Tuple

_REPO = Path(__file__).resolve().parents[2]


class MissingTool(RuntimeError):
    """An executable the experiments need is not built (or not on PATH)."""


class ToolFailed(RuntimeError):
    """An executable ran and failed; the message carries its command line and stderr."""


def find_tool(name: str, bin_dir: Optional[str] = None) -> str:
    """Absolute path of executable `name` (see module doc for the search order)."""
    dirs = [bin_dir, os.environ.get("GMMRRT_BIN_DIR"), str(_REPO / "build" / "bin")]
    for d in dirs:
        if d and (Path(d) / name).is_file() and os.access(Path(d) / name, os.X_OK):
            return str(Path(d) / name)
    found = shutil.which(name)
    if found:
        return found
    raise MissingTool(f"{name} not found in {', '.join(d for d in dirs if d)} or PATH: "
                      f"build it with `tools/run build`")


@dataclass
class Scene:
    """One planning problem, in metres and radians (world frame of the caller)."""
    start: Tuple[float, float]
    goal: Tuple[float, float]
    people: List[Tuple[float, float, float]]          # (x, y, yaw) each
    # xmin, ymin, xmax, ymax: the scene's workspace; None: the core's rule (core.problem_bounds),
    # the box gmmrrtd would plan in.
    bounds: Optional[Tuple[float, float, float, float]]
    circles: List[Tuple[float, float, float]] = field(default_factory=list)          # x, y, r
    boxes: List[Tuple[float, float, float, float, float]] = field(default_factory=list)  # cx, cy, w, h, yaw


@dataclass
class PlanResult:
    status: str
    path: List[Tuple[float, float]]
    stats: Dict
    seed: int
    argv: List[str]
    # --side either: {"left": {"status", "cost", "length_m", "path"}, "right": {...}} (docs/planner.md)
    sides: Dict = field(default_factory=dict)


def _fmt(v: float) -> str:
    return repr(float(v))


def plan_argv(scene: Scene, planner: str, seed: int, model: Optional[str] = None,
              iterations: Optional[int] = None, budget_ms: Optional[int] = None,
              bias: Optional[float] = None, robot_radius_m: Optional[float] = None,
              extra: Sequence[str] = (), bin_dir: Optional[str] = None,
              settings: Optional[Dict[str, object]] = None) -> List[str]:
    """The gmmrrt-plan command line for one run (docs/planner.md). `bias` and `robot_radius_m` are
    the planner settings gmm_bias and robot_radius_m; `settings` gives any other by its name in the
    core's table (docs/settings.md), turned into its flag by gmmrrt_tools.core.planner_flags."""
    from gmmrrt_tools import core
    argv = [find_tool("gmmrrt-plan", bin_dir)]
    if model:
        argv += ["--model", str(model)]
    bounds = scene.bounds if scene.bounds is not None else core.problem_bounds(scene.start, scene.goal)
    argv += ["--planner", planner, "--seed", str(int(seed)),
             "--start", ",".join(map(_fmt, scene.start)), "--goal", ",".join(map(_fmt, scene.goal)),
             "--bounds", ",".join(map(_fmt, bounds))]
    for p in scene.people:
        argv += ["--person", ",".join(map(_fmt, p))]
    for c in scene.circles:
        argv += ["--obstacle", "circle:" + ",".join(map(_fmt, c))]
    for b in scene.boxes:
        argv += ["--obstacle", "box:" + ",".join(map(_fmt, b))]
    if iterations is not None:
        argv += ["--iterations", str(int(iterations))]
    if budget_ms is not None:
        argv += ["--budget-ms", str(int(budget_ms))]
    named = dict(settings or {})
    if bias is not None:
        named["gmm_bias"] = float(bias)
    if robot_radius_m is not None:
        named["robot_radius_m"] = float(robot_radius_m)
    argv += core.planner_flags(named)
    argv += list(extra)
    argv.append("--json")
    return argv


def run_plan(argv: List[str], seed: int, timeout_s: float = 600.0) -> PlanResult:
    """Runs gmmrrt-plan and parses its --json object. A non-zero exit that still printed a JSON
    object (e.g. no path within the budget) is a result with that status; a run that printed none
    (e.g. goal in collision) is a result with status "error: <last stderr line>" and no path."""
    proc = subprocess.run(argv, capture_output=True, text=True, timeout=timeout_s)
    out = proc.stdout.strip()
    obj = None
    if out:
        try:
            obj = json.loads(out.splitlines()[-1] if not out.startswith("{") else out)
        except json.JSONDecodeError:
            obj = None
    if obj is None:
        # No result object: keep the run (as status "error: ...") so one bad problem does not sink
        # an experiment; callers abort when every run fails (see Ctx.run_plans).
        msg = (proc.stderr.strip().splitlines() or [f"exit {proc.returncode}, no output"])[-1]
        return PlanResult(f"error: {msg}", [], {"exit_code": proc.returncode}, int(seed), argv)
    path = [tuple(map(float, p)) for p in (obj.get("path") or [])]
    return PlanResult(str(obj.get("status", "")), path, dict(obj.get("stats") or {}), int(seed), argv,
                      dict(obj.get("sides") or {}))


def learn(args: Sequence[str], bin_dir: Optional[str] = None, timeout_s: float = 900.0) -> str:
    """Runs `gmmrrt-learn ARGS...` and returns its stdout; raises ToolFailed on a non-zero exit."""
    argv = [find_tool("gmmrrt-learn", bin_dir)] + [str(a) for a in args]
    proc = subprocess.run(argv, capture_output=True, text=True, timeout=timeout_s)
    if proc.returncode != 0:
        raise ToolFailed(f"gmmrrt-learn failed (exit {proc.returncode}): {shlex.join(argv)}\n"
                         f"{proc.stderr.strip()[-2000:]}")
    return proc.stdout


def fit_model(out: Path, task: str, inputs: Sequence[str], homotopy: str = "all", kind: str = "features",
              k: Optional[str] = None, seed: int = 1, index: Optional[str] = None,
              split: Optional[str] = None, bin_dir: Optional[str] = None, background: bool = False) -> Path:
    """`gmmrrt-learn fit` into `out` (skipped when `out` exists and is newer than every input and than the
    gmmrrt-learn executable, so a rebuilt learner with other defaults refits); background: with the
    task model's background in the file (`--background straight`, for `gmmrrt-plan --task-cost background`)."""
    out = Path(out)
    learner = Path(find_tool("gmmrrt-learn", bin_dir))
    if out.exists() and all(out.stat().st_mtime >= Path(i).stat().st_mtime for i in [*inputs, learner]):
        return out
    out.parent.mkdir(parents=True, exist_ok=True)
    args = ["fit", "--input", *inputs, "--task", task, "--homotopy", homotopy, "--kind", kind,
            "--seed", str(seed), "--quiet", "-o", str(out)]
    if k:
        args += ["--k", str(k)]
    if index:
        args += ["--index", index]
    if split:
        args += ["--split", split]
    if background:
        args += ["--background", "straight"]
    learn(args, bin_dir)
    return out


__all__ = ["MissingTool", "ToolFailed", "find_tool", "Scene", "PlanResult", "plan_argv", "run_plan",
           "learn", "fit_model"]
