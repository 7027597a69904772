"""gmmrrt_tools.bench.first_paths - iterations and time to the first path over many seeds, with
gmmrrt-plan at the all-planner benchmark's settings (RRT*, uniform sampling, goal bias 0.05, OMPL's
range 0.2 and motion-check resolution 0.01 times the bounds' diagonal, goal tolerance 1e-6).

The iterations to the first path are exact for a seed (the search is deterministic); the time is
gmmrrt-plan's `first_solution_ms` (set-up excluded, caches warm: the process has just loaded the
problem), so it moves with the machine's load. A first path's iterations are heavy-tailed over seeds,
which is why this prints the median, the 90th percentile and the slowest seed.

Usage:
  python -m gmmrrt_tools.bench.first_paths --problem tests/data/bench_problems/problem_C.txt --seeds 300
  python -m gmmrrt_tools.bench.first_paths --map logs/maps/floor.yaml --bounds=-11,-7,11,7 \\
      --start=-9,-2 --goal 8,4 --robot-radius 0.3 --seeds 100 -- --connect-domains 0
Everything after `--` goes to gmmrrt-plan as it is. Prints one JSON object.
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys
from pathlib import Path
from typing import List, Optional

from gmmrrt_tools.bench.stats import clean, median, quantile


def problem_args(path: Path) -> List[str]:
    """gmmrrt-plan's arguments for a benchmark problem file (tests/data/bench_problems/README.md):
    bounds, start, goal, circles and boxes, a point robot, the step and resolution from the extent."""
    bounds = start = goal = None
    obstacles: List[str] = []
    for n, line in enumerate(path.read_text().splitlines(), 1):
        t = line.split()
        if not t or t[0] == "name":
            continue
        try:
            values = [float(v) for v in t[1:]]
        except ValueError:
            raise SystemExit(f"{path}:{n}: a value of '{line}' is not a number")
        want = {"bounds": 4, "start": 2, "goal": 2, "circle": 3, "box": 5}.get(t[0])
        if want is None or len(values) != want:
            raise SystemExit(f"{path}:{n}: expected 'bounds', 'start', 'goal', 'circle' or 'box' with its "
                             f"values, got '{line}'")
        if t[0] == "bounds":
            bounds = values
        elif t[0] == "start":
            start = values
        elif t[0] == "goal":
            goal = values
        else:
            obstacles += ["--obstacle", t[0] + ":" + ",".join(t[1:])]
    if bounds is None or start is None or goal is None:
        raise SystemExit(f"{path}: needs a 'bounds', a 'start' and a 'goal' line")
    return (["--bounds=" + ",".join("%g" % v for v in bounds), "--start=%g,%g" % tuple(start),
             "--goal=%g,%g" % tuple(goal), "--robot-radius", "0"] + obstacles)


def extent_args(bounds: List[float]) -> List[str]:
    """OMPL's defaults on the bounds, as the all-planner benchmark gives both sides."""
    extent = math.hypot(bounds[2] - bounds[0], bounds[3] - bounds[1])
    return ["--step", repr(0.2 * extent), "--edge-resolution", repr(0.01 * extent)]


def first_path(plan: str, args: List[str], seed: int, iterations: int) -> Optional[dict]:
    """One run: the first path's iteration and time, or None when the run has no path."""
    cmd = [plan, "--planner", "rrt-star", "--goal-bias", "0.05", "--gmm-bias", "0", "--goal-tolerance", "1e-6",
           "--json", "--seed", str(seed), "--iterations", str(iterations)] + args
    proc = subprocess.run(cmd, capture_output=True, text=True)
    if proc.returncode != 0 or not proc.stdout.strip():
        if "no path" in proc.stderr:
            return None
        raise SystemExit(f"gmmrrt-plan failed (exit {proc.returncode}): {proc.stderr.strip()}\n  {' '.join(cmd)}")
    stats = json.loads(proc.stdout)["stats"]
    history = stats.get("cost_history") or []
    if not history:
        return None
    return {"iteration": history[0][0], "ms": stats["first_solution_ms"]}


def summarise(runs: List[Optional[dict]]) -> dict:
    """Median, 90th percentile (nearest rank) and slowest of the iterations, median and mean of the
    time; a run without a path counts as never (infinite, as every benchmark statistic does:
    stats.median), so these are JSON null when it weighs in."""
    its = [None if r is None else r["iteration"] for r in runs]
    ms = [None if r is None else r["ms"] for r in runs]
    found = [r for r in runs if r is not None]
    return clean({"seeds": len(runs), "with_path": len(found), "iterations_median": median(its),
                  "iterations_p90": quantile(its, 0.9), "iterations_max": quantile(its, 1.0),
                  "first_solution_ms_median": median(ms),
                  "first_solution_ms_mean": statistics.mean(r["ms"] for r in found) if len(found) == len(runs) else None})


def main(argv: Optional[List[str]] = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    extra: List[str] = []
    if "--" in argv:
        extra = argv[argv.index("--") + 1:]
        argv = argv[:argv.index("--")]
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--plan", default=os.path.join(os.environ.get("GMMRRT_BIN_DIR", "build/bin"), "gmmrrt-plan"),
                    help="gmmrrt-plan to run (default: $GMMRRT_BIN_DIR or build/bin)")
    ap.add_argument("--problem", type=Path, help="a benchmark problem file (point robot)")
    ap.add_argument("--map", type=Path, help="a map_server YAML (with --bounds, --start, --goal, --robot-radius)")
    ap.add_argument("--bounds", help="xmin,ymin,xmax,ymax with --map")
    ap.add_argument("--start", help="x,y with --map")
    ap.add_argument("--goal", help="x,y with --map")
    ap.add_argument("--robot-radius", type=float, default=0.3, help="m, with --map (default 0.3)")
    ap.add_argument("--seeds", type=int, default=100, help="seeds 1..N (default 100)")
    ap.add_argument("--iterations", type=int, default=20000, help="iteration budget of each run (default 20000)")
    a = ap.parse_args(argv)
    if a.seeds < 1 or a.iterations < 1:
        ap.error("--seeds and --iterations must be >= 1")
    if (a.problem is None) == (a.map is None):
        ap.error("give one of --problem and --map")
    if a.problem is not None:
        args = problem_args(a.problem)
        bounds = [float(v) for v in args[0].split("=", 1)[1].split(",")]
    else:
        if not (a.bounds and a.start and a.goal):
            ap.error("--map needs --bounds, --start and --goal")
        try:
            bounds = [float(v) for v in a.bounds.split(",")]
        except ValueError:
            ap.error(f"--bounds {a.bounds}: not four numbers")
        if len(bounds) != 4:
            ap.error(f"--bounds {a.bounds}: not four numbers")
        args = ["--map", str(a.map), "--bounds=" + a.bounds, "--start=" + a.start, "--goal=" + a.goal,
                "--robot-radius", "%g" % a.robot_radius]
    args = args + extent_args(bounds) + extra
    runs = [first_path(a.plan, args, s, a.iterations) for s in range(1, a.seeds + 1)]
    print(json.dumps(summarise(runs)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
