"""Planner benchmarks (docs/benchmarks.md), run through the C++ benchmark programs and summarised here.

- OMPL comparison (gmmrrt-bench-ompl): our RRT* and OMPL's RRTstar on the disc problem, runs
  interleaved inside the program; medians, and ratios against OMPL measured in the same run.
- Social tasks (gmmrrt-bench-social): GMM-RRT* with bias 0.95, time to first solution and to
  within 1 % of the converged cost, avoid and approach.
- Memory (gmmrrt-bench-memory): bytes per node, the default block, allocations while planning.
- Task models: learned from the real demonstrations with gmmrrt-learn when they are there,
  else hand-built mixtures imported with gmmrrt-learn import (the report says which).
"""
from __future__ import annotations

import json
import math
import os
import re
import subprocess
import time
from pathlib import Path
from typing import Dict, List, Optional

from gmmrrt_tools.bench.stats import INF, cost_at, median, quantile, ratio, time_to_cost

CHECKPOINTS_MS = (10.0, 100.0, 1000.0)


class BenchError(RuntimeError):
    """A benchmark program failed; the message names the command and its error output."""


def _run(cmd: List[str], timeout_s: float) -> str:
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout_s)
    if proc.returncode != 0:
        raise BenchError(f"{' '.join(cmd)} exited {proc.returncode}: {proc.stderr.strip()[-600:]}")
    return proc.stdout


def _json_lines(text: str) -> List[dict]:
    return [json.loads(line) for line in text.splitlines() if line.strip()]


# ------------------------------------------------------------------------------------ models
HAND_BUILT = {
    # (d [m], theta [rad]) mixtures like the planner's tests: passing on either side at ~1.2 m
    # (avoid), arriving in front of the person at ~1.2 m (approach).
    "avoid": {
        "priors": [0.1] * 10,
        "means": [[1.2, s * k * math.pi / 6] for s in (1, -1) for k in range(1, 6)],
        "covs": [[[0.04, 0.0], [0.0, 0.0625]]] * 10,
    },
    "approach": {
        "priors": [0.2] * 5,
        "means": [[1.2, 0.0], [2.0, 0.6], [2.0, -0.6], [3.0, 1.5], [3.0, -1.5]],
        "covs": [[[0.09, 0.0], [0.0, 0.09]]] * 5,
    },
}


def ensure_models(bin_dir: Path, out_dir: Path, real_data: Optional[Path]) -> Dict[str, object]:
    """Model files for the avoid and approach tasks, made once into out_dir.

    With the real data: avoid learned from the UPO robot demonstrations (train split, K = 19),
    approach from the UCY approach episodes (train split, K = 19). Without: hand-built
    mixtures (HAND_BUILT). Returns {"avoid": path, "approach": path, "source": text,
    "commands": [...]}.
    """
    learn = bin_dir / "gmmrrt-learn"
    if not learn.is_file():
        raise BenchError(f"{learn} is missing: build the learner (tools/run build)")
    out_dir.mkdir(parents=True, exist_ok=True)
    have_real = real_data is not None and (real_data / "upo_avoid_episodes.csv").is_file() \
        and (real_data / "ucy_approach_episodes.csv").is_file()
    tag = "real" if have_real else "hand"
    paths = {t: out_dir / f"{t}-{tag}.gmm" for t in ("avoid", "approach")}
    commands = []
    for task, path in paths.items():
        if have_real:
            rd = real_data
            episodes, index = (("upo_avoid_episodes.csv", "upo_avoid_index.csv") if task == "avoid"
                               else ("ucy_approach_episodes.csv", "ucy_index.csv"))
            cmd = [str(learn), "fit", "--input", str(rd / episodes), "--index", str(rd / index),
                   "--split", "train", "--task", task, "-k", "19", "--max-iter", "150", "--tol", "1e-4",
                   "--quiet", "-o", str(path)]
        else:
            js = out_dir / f"{task}-hand.json"
            js.write_text(json.dumps(HAND_BUILT[task]))
            cmd = [str(learn), "import", "--json", str(js), "--task", task, "-o", str(path)]
        commands.append(" ".join(cmd))
        # Made again when the learner was rebuilt since (the format or the fit may have changed).
        if not path.is_file() or path.stat().st_mtime < learn.stat().st_mtime:
            _run(cmd, timeout_s=1800)
    source = ("learned with gmmrrt-learn from the real demonstrations (train split; avoid: UPO robot, "
              "approach: UCY walkers), K = 19" if have_real else
              "hand-built (d, theta) mixtures (no real data found; set GMMRRT_REAL_DATA)")
    return {"avoid": str(paths["avoid"]), "approach": str(paths["approach"]), "source": source,
            "commands": commands}


# ------------------------------------------------------------------------------------ OMPL
def summarize_ompl(trials: List[dict], time_ms: float) -> dict:
    """Medians per planner and ratios (ours / OMPL) from gmmrrt-bench-ompl's trial records."""
    by = {"ompl_rrtstar": [], "gmmrrt_rrtstar": []}
    for r in trials:
        by.setdefault(r["planner"], []).append(r)
    out: Dict[str, object] = {"time_ms": time_ms, "planners": {}}
    for name, rs in by.items():
        if not rs:
            continue
        ips = [r["iterations"] / (r["time_ms"] / 1000.0) for r in rs]
        cpu = [r["iterations"] / (r["cpu_ms"] / 1000.0) for r in rs if r.get("cpu_ms")]
        first = [INF if r["first_solution_ms"] in (None, -1) or r["first_solution_ms"] < 0
                 else r["first_solution_ms"] for r in rs]
        cps = {f"{int(c)}": median(cost_at(r["history"], c) for r in rs) for c in CHECKPOINTS_MS if c <= time_ms}
        out["planners"][name] = {
            "trials": len(rs),
            "iterations_per_s_median": median(ips),
            "iterations_per_s_min": min(ips),
            "iterations_per_s_max": max(ips),
            "iterations_per_cpu_s_median": median(cpu) if cpu else None,
            "cpu_share_median": median(r["cpu_ms"] / r["time_ms"] for r in rs if r.get("cpu_ms")) if cpu else None,
            "first_solution_ms_median": median(first),
            "solved": sum(1 for r in rs if r["final_cost"] is not None and r["final_cost"] >= 0),
            "cost_at_ms_median": cps,
            "final_cost_median": median(cost_at(r["history"], INF) for r in rs),
            "nodes_median": median(r["nodes"] for r in rs),
            "setup_ms_median": median(r["setup_ms"] for r in rs),
            "statuses": sorted({r["status"] for r in rs}),
        }
    o, g = by.get("ompl_rrtstar", []), by.get("gmmrrt_rrtstar", [])
    if o and g:
        out["ratios"], out["ompl_reference"] = _compare(o, g, out["planners"]["ompl_rrtstar"],
                                                        out["planners"]["gmmrrt_rrtstar"], time_ms)
    # Extra pairs, when those planners ran: ours without informed sampling against OMPL's
    # default (the same algorithm as OMPL's RRTstar), and ours against OMPL's RRTstar with
    # informed sampling (the same trick on both sides).
    extra = {}
    for key, (peer, mine) in {"plain_vs_ompl": ("ompl_rrtstar", "gmmrrt_rrtstar_plain"),
                              "ours_vs_ompl_informed": ("ompl_rrtstar_informed", "gmmrrt_rrtstar")}.items():
        po_rs, pg_rs = by.get(peer, []), by.get(mine, [])
        if po_rs and pg_rs:
            ratios, ref = _compare(po_rs, pg_rs, out["planners"][peer], out["planners"][mine], time_ms)
            extra[key] = {"peer": peer, "ours": mine, "ratios": ratios, "reference": ref}
    if extra:
        out["pairs"] = extra
    return out


def _compare(o: List[dict], g: List[dict], po: dict, pg: dict, time_ms: float):
    """Ratios of planner g's trials against peer o's, and g's time to o's median cost at 1 s."""
    # Paired by trial index: neighbours in time, so they saw the same machine load.
    pairs: Dict[int, dict] = {}
    for r in o:
        pairs.setdefault(r["trial"], {})["o"] = r
    for r in g:
        pairs.setdefault(r["trial"], {})["g"] = r
    paired = [p["g"]["iterations"] / p["g"]["time_ms"] / (p["o"]["iterations"] / p["o"]["time_ms"])
              for p in pairs.values() if "o" in p and "g" in p and p["o"]["iterations"] > 0]
    t_ref = min(1000.0, time_ms)
    ompl_ref_cost = median(cost_at(r["history"], t_ref) for r in o)
    ours_times = [time_to_cost(r["history"], ompl_ref_cost) for r in g]
    t_ours = median(ours_times)
    ratios = {
        "iterations_per_s": ratio(pg["iterations_per_s_median"], po["iterations_per_s_median"]),
        "iterations_per_s_paired_median": median(paired) if paired else None,
        "iterations_per_cpu_s": ratio(pg["iterations_per_cpu_s_median"], po["iterations_per_cpu_s_median"]),
        "first_solution_speedup": ratio(po["first_solution_ms_median"], pg["first_solution_ms_median"]),
    }
    reference = {
        "time_ms": t_ref,
        "ompl_median_cost": ompl_ref_cost,
        "ours_median_time_to_that_cost_ms": t_ours,
        "ours_reached": sum(1 for t in ours_times if math.isfinite(t)),
        "speedup": ratio(t_ref, t_ours),
    }
    return ratios, reference


def run_ompl_comparison(bin_dir: Path, objective: str, trials: int, time_ms: float, seed: int,
                        model: Optional[str], raw_out: Path, ompl_log: Optional[Path]) -> dict:
    """Runs gmmrrt-bench-ompl once (interleaved trials) and summarises it. The length
    objective also runs ours without informed sampling and OMPL's RRTstar with it."""
    exe = bin_dir / "gmmrrt-bench-ompl"
    if not exe.is_file():
        raise BenchError(f"{exe} is missing: OMPL (libompl-dev) not found at configure time, or not built")
    lineup = "ompl,gmmrrt,gmmrrt-plain,ompl-informed" if objective == "length" else "ompl,gmmrrt"
    cmd = [str(exe), "--objective", objective, "--trials", str(trials), "--time-ms", str(time_ms),
           "--seed", str(seed), "--planners", lineup, "--out", str(raw_out)]
    if model:
        cmd += ["--model", model]
    if ompl_log:
        cmd += ["--ompl-log", str(ompl_log)]
    budget_s = 120 + trials * time_ms / 1000.0 * (len(lineup.split(",")) + (2 if ompl_log else 0)) * 3
    _run(cmd, timeout_s=budget_s)
    records = _json_lines(raw_out.read_text())
    summary = summarize_ompl(records, time_ms)
    summary["command"] = " ".join(cmd)
    summary["objective"] = objective
    return summary


# ------------------------------------------------------------------------------------ social
def summarize_social(trials: List[dict], time_ms: float) -> dict:
    """Time to first solution and to within 1 % of the converged cost (the lowest final cost
    over all trials of the task) from gmmrrt-bench-social's records."""
    first = [INF if r["first_solution_ms"] is None or r["first_solution_ms"] < 0 else r["first_solution_ms"]
             for r in trials]
    finals = [cost_at(r["history"], INF) for r in trials]
    converged = min(finals) if finals else INF
    within = [time_to_cost(r["history"], 1.01 * converged) for r in trials] if math.isfinite(converged) else []
    # Each run against its own final cost: when did it get within 1 % of where it ended?
    within_own = [time_to_cost(r["history"], 1.01 * f) for r, f in zip(trials, finals) if math.isfinite(f)]
    return {
        "trials": len(trials),
        "time_ms": time_ms,
        "solved": sum(1 for f in first if math.isfinite(f)),
        "first_solution_ms_median": median(first),
        "first_solution_ms_p90": quantile(first, 0.9),
        "first_solution_ms_max": max(first) if first else None,
        "converged_cost": converged,
        "final_cost_median": median(finals),
        "within_1pct_ms_median": median(within) if within else None,
        "within_1pct_reached": sum(1 for t in within if math.isfinite(t)),
        "within_1pct_of_own_final_ms_median": median(within_own) if within_own else None,
        "iterations_per_s_median": median(r["iterations"] / (r["time_ms"] / 1000.0) for r in trials),
        "cpu_share_median": (median(r["cpu_ms"] / r["time_ms"] for r in trials if r.get("cpu_ms"))
                             if any(r.get("cpu_ms") for r in trials) else None),
        "statuses": sorted({r["status"] for r in trials}),
        "paper_first_solution_ms": 1500.0,
        "speedup_vs_paper": ratio(1500.0, median(first)),
    }


def run_social(bin_dir: Path, task: str, model: str, trials: int, time_ms: float, seed: int,
               raw_out: Path) -> dict:
    exe = bin_dir / "gmmrrt-bench-social"
    if not exe.is_file():
        raise BenchError(f"{exe} is missing: build with -DGMMRRT_BUILD_BENCH=ON (tools/run bench)")
    cmd = [str(exe), "--task", task, "--model", model, "--trials", str(trials), "--time-ms", str(time_ms),
           "--seed", str(seed)]
    text = _run(cmd, timeout_s=120 + trials * time_ms / 1000.0 * 3)
    raw_out.write_text(text)
    summary = summarize_social(_json_lines(text), time_ms)
    summary["command"] = " ".join(cmd)
    return summary


# ------------------------------------------------------------------------------------ memory
def run_memory(bin_dir: Path, time_ms: float) -> dict:
    exe = bin_dir / "gmmrrt-bench-memory"
    if not exe.is_file():
        raise BenchError(f"{exe} is missing: build with -DGMMRRT_BUILD_BENCH=ON (tools/run bench)")
    cmd = [str(exe), str(time_ms)]
    result = json.loads(_run(cmd, timeout_s=120 + time_ms / 100.0))
    result["command"] = " ".join(cmd)
    return result


def find_executable(build_dir: Path, name: str) -> Optional[Path]:
    """A benchmark executable in build/bin or build/bench (the planner's micro-benchmarks)."""
    for sub in ("bin", "bench", "tests"):
        p = build_dir / sub / name
        if p.is_file() and os.access(p, os.X_OK):
            return p
    return None


ALL_PLANNERS_BUDGETS_MS = (1.0, 10.0, 100.0, 1000.0)
# gmmrrt-bench-all runs twice, on disjoint budgets, so that every figure of a (problem, planner,
# budget) cell comes from one run and every planner of a cell is measured over the same trials:
# - the seeded run: SEEDED_TRIALS trials at each of SEEDED_BUDGETS_MS. A first path's time and a
#   short budget's cost are heavy-tailed over seeds (on the floor plan our iterations to the first
#   path range over several times their median, and a 1 ms run's cost depends on whether its first
#   path came inside the budget), so a few seeds would be a sample of those seeds, not of the planner.
# - the long run: LONG_TRIALS trials at the other budgets (1000 ms), where SEEDED_TRIALS would
#   multiply the bench's longest part by five (the report says by how much).
# First paths and set-up times are read from the seeded run's FIRST_PATH_BUDGET_MS runs only: a
# shorter run that ended without a path has no first-path time.
SEEDED_TRIALS = 15
SEEDED_BUDGETS_MS = (1.0, 10.0, 100.0)
LONG_TRIALS = 3
FIRST_PATH_BUDGET_MS = 100.0
# gmmrrt-bench-all runs trial t of our planner with seed FIRST_SEED + t (its first_seed); OMPL's
# planners draw from OMPL's own generator, which the program does not seed.
FIRST_SEED = 1


def _median_or_none(values: List[float]) -> Optional[float]:
    return median(values) if values else None


def summarize_all_planners(records: List[dict], first_path_budget_ms: float = FIRST_PATH_BUDGET_MS) -> Dict[str, dict]:
    """Per problem, from gmmrrt-bench-all's records of one or more runs on disjoint budgets.

    Every statistic is a median over the trials of one budget, the same trials for every planner:
    cost @ b over the runs of budget b (a run without an exactly free path counts as infinite),
    set-up and first path (set-up included) over the runs of first_path_budget_ms (a run without a
    path counts as infinite; a run with a path but no first-path time is left out; none left:
    infinite). Returns {problem: {"first_ms", "fastest_ompl",
    "fastest_ompl_first_ms", "first_ratio", "first_ms_by_planner", "first_trials", "cost": {"<b>":
    {"ours", "best_ompl", "best_ompl_planner", "met", "trials"}}, "table": [one row per planner in
    the program's order: {"planner", "setup_ms", "first_ms", "cost": {"<b>": median}}]}}.
    BenchError when a (problem, planner, budget, trial) appears twice (two runs on one budget) or
    when the planners of a cell ran different numbers of trials.
    """
    seen = set()
    for r in records:
        key = (r["problem"], r["planner"], r["budget_ms"], r["trial"])
        if key in seen:
            raise BenchError(f"two records of problem {key[0]}, planner {key[1]}, budget {key[2]:g} ms, trial "
                             f"{key[3]}: the runs' budgets must be disjoint")
        seen.add(key)
    problems: Dict[str, dict] = {}
    for name in sorted({r["problem"] for r in records}):
        mine = [r for r in records if r["problem"] == name]
        planners = list(dict.fromkeys(r["planner"] for r in mine))  # the program's order, gmmrrt first
        budgets = sorted({r["budget_ms"] for r in mine})
        cell = {(p, b): [r for r in mine if r["planner"] == p and r["budget_ms"] == b]
                for p in planners for b in budgets}
        trials = {}
        for b in budgets:
            counts = {p: len(cell[p, b]) for p in planners}
            if len(set(counts.values())) != 1:
                raise BenchError(f"problem {name}, budget {b:g} ms: the planners ran different numbers of "
                                 f"trials ({counts})")
            trials[b] = counts[planners[0]]
        cost = {(p, b): median(INF if r["cost"] is None else r["cost"] for r in cell[p, b])
                for p in planners for b in budgets}
        first_runs = {p: cell.get((p, first_path_budget_ms), []) for p in planners}
        # A run with no path counts as never (infinite), as stats.median keeps it; only a run that
        # found a path without reporting when (a planner without the callback) is left out, and a
        # planner all of whose runs are such reports no first path.
        first = {p: median([INF if r["cost"] is None else r["first_ms"] for r in rs
                            if r["cost"] is None or r["first_ms"] is not None] or [INF])
                 for p, rs in first_runs.items() if rs}
        setup = {p: _median_or_none([r["setup_ms"] for r in rs if r["setup_ms"] is not None])
                 for p, rs in first_runs.items()}
        ompl_first = {p: f for p, f in first.items() if p != "gmmrrt" and math.isfinite(f)}
        fastest = min(ompl_first, key=ompl_first.get) if ompl_first else None
        out = {"first_ms": first.get("gmmrrt"), "fastest_ompl": fastest,
               "fastest_ompl_first_ms": ompl_first.get(fastest) if fastest else None,
               "first_ms_by_planner": {p: (f if math.isfinite(f) else None) for p, f in sorted(first.items())},
               "first_trials": trials.get(first_path_budget_ms), "cost": {}}
        out["first_ratio"] = (out["first_ms"] / out["fastest_ompl_first_ms"]) if fastest else None
        for b in budgets:
            ompl = {p: cost[p, b] for p in planners if p != "gmmrrt"}
            best = min(ompl, key=ompl.get) if ompl else None
            ours = cost.get(("gmmrrt", b))
            out["cost"]["%g" % b] = {"ours": ours, "best_ompl": ompl.get(best), "best_ompl_planner": best,
                                     "met": None if best is None or ours is None else (math.isfinite(ours) and ours <= ompl[best]),
                                     "trials": trials[b]}
        out["table"] = [{"planner": p, "setup_ms": setup.get(p), "first_ms": out["first_ms_by_planner"].get(p),
                         "cost": {"%g" % b: cost[p, b] for b in budgets}} for p in planners]
        problems[name] = out
    return problems


def problem_descriptions(text: str) -> Dict[str, str]:
    """What gmmrrt-bench-all's headings say each problem is ("### Problem A (problem_A.txt, 3 trials)"
    gives {"A": "problem_A.txt"}), so the report names the problems as the program does."""
    return {m.group(1): m.group(2) for m in re.finditer(r"^### Problem (\S+) \((.*), \d+ trials\)$", text, re.M)}


def run_all_planners(bin_dir: Path, quick: bool, raw: Path, avoid_model: Optional[str] = None,
                     approach_model: Optional[str] = None, map_yaml: Optional[Path] = None,
                     arena_dir: Optional[Path] = None) -> dict:
    """gmmrrt-bench-all: our RRT* and every OMPL planner of the comparison on the problems of
    tests/data/bench_problems (path length, point robot), exact motion checks and set-up counted on
    both sides. Targets: our first path (set-up included) <= 0.5x the fastest OMPL planner's, and our
    best cost at each moment <= the best OMPL planner's (medians over trials: see SEEDED_TRIALS for
    which budgets run how many). With avoid_model, also the social avoid scene (problem "S", task
    cost) of gmmrrt-bench-ompl; with approach_model, the social approach scene ("AP"); with map_yaml,
    the floor-plan scene ("MAP", robot radius 0.3 m). With arena_dir, the Planner Arena logs (one per
    problem and budget, each from the run that ran that budget) go there; each is read back and its
    runs counted against the JSON records, so a log Planner Arena would misread fails here. quick:
    one trial at the seeded run's budgets, no long run."""
    exe = bin_dir / "gmmrrt-bench-all"
    if not exe.is_file():
        raise BenchError(f"{exe} not built (OMPL missing?)")
    root = Path(__file__).resolve().parents[3]  # the repository (this file is tools/gmmrrt_tools/bench/)
    long_budgets = () if quick else tuple(b for b in ALL_PLANNERS_BUDGETS_MS if b not in SEEDED_BUDGETS_MS)
    seeded_raw = raw.with_name(raw.stem + "_seeds" + raw.suffix)
    runs = [("seeded", 1 if quick else SEEDED_TRIALS, SEEDED_BUDGETS_MS, seeded_raw),
            ("long", LONG_TRIALS, long_budgets, raw)]
    # The scenes' arguments, as run and as shown (paths relative to the repository).
    scene, scene_shown = [], []
    for flag, path, shown_path in (("--model", avoid_model, lambda q: q.name),
                                   ("--approach-model", approach_model, lambda q: q.name),
                                   ("--map", map_yaml, lambda q: "logs/maps/" + q.name)):
        if path:
            scene += [flag, str(path)]
            scene_shown += [flag, shown_path(Path(path))]
    arena_args, arena_shown = [], []
    if arena_dir:
        arena_dir.mkdir(parents=True, exist_ok=True)
        for old in arena_dir.glob("*.log"):
            old.unlink()
        arena_args, arena_shown = ["--arena", str(arena_dir)], ["--arena", "build/" + arena_dir.name]
    problems_dir = str(root / "tests" / "data" / "bench_problems")
    shown_exe = [str(exe.relative_to(root)) if root in exe.parents else str(exe), "--problems", "tests/data/bench_problems"]
    t0 = time.time()
    recs: List[dict] = []
    done: List[dict] = []
    descriptions: Dict[str, str] = {}
    for role, n_trials, budgets, json_path in runs:
        if not budgets:
            continue
        args = ["--trials", str(n_trials), "--budgets", ",".join("%g" % b for b in budgets), "--json"]
        t_run = time.time()
        text = _run([str(exe), "--problems", problems_dir] + args + [str(json_path)] + scene + arena_args, 3600)
        recs += _json_lines(json_path.read_text())
        descriptions.update(problem_descriptions(text))
        done.append({"role": role, "trials": n_trials, "budgets_ms": list(budgets),
                     "seconds": round(time.time() - t_run, 1),
                     "command": " ".join(shown_exe + args + [json_path.name] + scene_shown + arena_shown)})
    out = {"runs": done, "first_path_budget_ms": FIRST_PATH_BUDGET_MS, "first_seed": FIRST_SEED,
           "descriptions": descriptions, "problems": summarize_all_planners(recs),
           "seconds": round(time.time() - t0, 1)}
    if arena_dir:
        out["arena_logs"] = check_arena_logs(arena_dir, recs)
    return out


def check_arena_logs(arena_dir: Path, recs: List[dict]) -> List[dict]:
    """Reads every Planner Arena log gmmrrt-bench-all wrote (the header lines and run tables that
    ompl_benchmark_statistics.py reads, in its order) and checks that each (problem, budget) log
    holds, per planner, as many runs and solved runs as the JSON records. Returns one entry per log
    (name, bytes, planners, runs); BenchError on a mismatch or a malformed log."""
    out = []
    for path in sorted(arena_dir.glob("*.log")):
        lines = path.read_text().splitlines()
        pos = 0

        def take() -> str:
            nonlocal pos
            if pos >= len(lines):
                raise BenchError(f"{path}: ends early (line {pos + 1})")
            pos += 1
            return lines[pos - 1]
        if not take().startswith("OMPL version ") or not take().startswith("Experiment "):
            raise BenchError(f"{path}: not an OMPL benchmark log")
        for _ in range(int(take().split()[0])):  # experiment properties
            take()
        take(), take()  # Running on, Starting at
        for _ in range(2):  # set-up and CPU blocks
            if take() != "<<<|":
                raise BenchError(f"{path}:{pos}: expected '<<<|'")
            while take() != "|>>>":
                pass
        seed, _limit, _mem, _runs, _total = (take().split()[0] for _ in range(5))
        for _ in range(int(take().split()[0])):  # enums
            take()
        problem, budget = path.stem.rsplit("_", 1)
        budget_ms = float(budget[:-2])
        planners = {}
        for _ in range(int(take().split()[0])):
            name = take().removeprefix("geometric_")
            for _ in range(int(take().split()[0])):  # common properties
                take()
            props = [" ".join(take().split()[:-1]) for _ in range(int(take().split()[0]))]
            runs = [take().split("; ")[:-1] for _ in range(int(take().split()[0]))]
            if take() != ".":
                raise BenchError(f"{path}:{pos}: expected '.' after planner {name}")
            if any(len(r) != len(props) for r in runs):
                raise BenchError(f"{path}: planner {name}: a run with other than {len(props)} values")
            solved = sum(1 for r in runs if r[props.index("solved")] == "1")
            want = [r for r in recs if r["problem"] == problem and r["planner"] == name and r["budget_ms"] == budget_ms]
            if len(runs) != len(want) or solved != sum(1 for r in want if r["cost"] is not None):
                raise BenchError(f"{path}: planner {name}: {len(runs)} runs ({solved} solved), the JSON records "
                                 f"{len(want)} ({sum(1 for r in want if r['cost'] is not None)} solved)")
            planners[name] = len(runs)
        out.append({"log": path.name, "bytes": path.stat().st_size, "planners": len(planners),
                    "runs": sum(planners.values()), "seed": int(seed)})
    if not out:
        raise BenchError(f"{arena_dir}: gmmrrt-bench-all wrote no Planner Arena log")
    return out
