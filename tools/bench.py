#!/usr/bin/env python3
"""gmmrrt benchmarks: planner against OMPL RRT*, social tasks, memory, learner against
scikit-learn, plus the mixture/planner micro-benchmarks and the daemon latency script when they
are built. Every figure is a median over interleaved runs and, where there is a peer, a ratio
against the peer measured in the same run (the machine is shared: absolute times are context).
Nothing is asserted; targets are reported as met or not.

    tools/run bench                  # builds with -DGMMRRT_BUILD_BENCH=ON, then runs this
    tools/run bench --quick          # smoke run: few, short trials; small learner data
    .venv/bin/python tools/bench.py --only ompl,memory --trials 5

Writes bench/results.json and docs/benchmarks.md; with --quick, <build>/bench-results-quick.json
and no Markdown unless --doc is given. Raw per-trial records go to <build>/bench-raw/.
"""
from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "BLIS_NUM_THREADS",
             "NUMEXPR_NUM_THREADS", "VECLIB_MAXIMUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import datetime  # noqa: E402
import json  # noqa: E402
import platform  # noqa: E402
import shutil  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
import traceback  # noqa: E402
from pathlib import Path  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent

from gmmrrt_tools.bench import planner as bp  # noqa: E402
from gmmrrt_tools.bench.report import evaluate_targets, write_markdown  # noqa: E402
from gmmrrt_tools.bench.stats import clean  # noqa: E402

SECTIONS = ("memory", "ompl", "planners", "social", "learner", "micro", "daemon")


def host_info() -> dict:
    model = "unknown"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    try:
        commit = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"], capture_output=True,
                                text=True, timeout=10).stdout.strip()
        dirty = bool(subprocess.run(["git", "-C", str(ROOT), "status", "--porcelain", "--untracked-files=no"],
                                    capture_output=True, text=True, timeout=10).stdout.strip())
    except (OSError, subprocess.SubprocessError):
        commit, dirty = "unknown", False
    return {"cpu": model, "nproc": os.cpu_count(), "kernel": platform.release(),
            "python": platform.python_version(), "commit": commit + ("+dirty" if dirty else "")}


def load_average() -> list:
    try:
        return [round(x, 2) for x in os.getloadavg()]
    except OSError:
        return []


def run_micro(build_dir: Path, quick: bool) -> dict:
    """The mixture and planner micro-benchmarks (other areas' programs: text output kept as is)."""
    out = {}
    for name in ("bench_gmm", "bench_planner", "bench_world"):
        exe = bp.find_executable(build_dir, name)
        if exe is None:
            out[name] = {"error": f"{name} not built (its tests/bench/ folder is not in this tree)"}
            continue
        t0 = time.time()
        proc = subprocess.run([str(exe)], capture_output=True, text=True, timeout=900)
        out[name] = {"command": str(exe.relative_to(build_dir.parent)) if build_dir.parent in exe.parents else str(exe),
                     "exit": proc.returncode, "seconds": round(time.time() - t0, 1),
                     "text": proc.stdout.strip() or proc.stderr.strip()}
    return out


def run_daemon(quick: bool, raw: Path) -> dict:
    js = raw / "daemon.json"
    cmd = [sys.executable, "-m", "gmmrrt_tools.bench.daemon", "--seconds", "3" if quick else "20", "--json", str(js)]
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    if proc.returncode != 0 or not js.is_file():
        return {"error": f"gmmrrt_tools.bench.daemon exited {proc.returncode}: {proc.stderr.strip()[-500:]}",
                "command": " ".join(cmd)}
    return {"command": " ".join(cmd), "results": json.loads(js.read_text()), "text": proc.stdout.strip()}


def relative_paths(obj):
    """Paths inside the repository written relative to it, so the report reads the same anywhere."""
    if isinstance(obj, str):
        return obj.replace(str(ROOT) + "/", "")
    if isinstance(obj, dict):
        return {k: relative_paths(v) for k, v in obj.items()}
    if isinstance(obj, list):
        return [relative_paths(v) for v in obj]
    return obj


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    ap.add_argument("--quick", action="store_true", help="smoke run: few, short trials, small learner data")
    ap.add_argument("--only", default=",".join(SECTIONS), help=f"comma list of sections ({', '.join(SECTIONS)})")
    ap.add_argument("--build-dir", type=Path, default=Path(os.environ.get("GMMRRT_BUILD_DIR", ROOT / "build")))
    ap.add_argument("--trials", type=int, help="planner trials per planner (default 20, quick 3)")
    ap.add_argument("--time-ms", type=float, help="planning time per trial, ms (default 1000, quick 200)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--results", type=Path, help="results JSON (default bench/results.json; quick: <build>/bench-results-quick.json)")
    ap.add_argument("--doc", type=Path, help="Markdown report (default docs/benchmarks.md; none with --quick)")
    ap.add_argument("--no-doc", action="store_true", help="do not write the Markdown report")
    ap.add_argument("--real-data", type=Path, default=os.environ.get("GMMRRT_REAL_DATA"),
                    help="real demonstrations for the task models (default $GMMRRT_REAL_DATA)")
    ap.add_argument("--hand-built-models", action="store_true",
                    help="use the hand-built task models even when the real data is there (fast: the smoke test)")
    args = ap.parse_args(argv)

    only = [s.strip() for s in args.only.split(",") if s.strip()]
    bad = [s for s in only if s not in SECTIONS]
    if bad:
        ap.error(f"--only: unknown section(s) {', '.join(bad)}; known: {', '.join(SECTIONS)}")
    if args.trials is not None and not 1 <= args.trials <= 10000:
        ap.error("--trials must be in 1..10000")
    if args.time_ms is not None and not 0 < args.time_ms <= 600000:
        ap.error("--time-ms must be in (0, 600000]")
    trials = args.trials or (3 if args.quick else 20)
    time_ms = args.time_ms or (200.0 if args.quick else 1000.0)
    build = args.build_dir.resolve()
    results_path = args.results or (build / "bench-results-quick.json" if args.quick else ROOT / "bench" / "results.json")
    doc_path = None if args.no_doc else (args.doc or (None if args.quick else ROOT / "docs" / "benchmarks.md"))
    bin_dir = build / "bin"
    if not bin_dir.is_dir():
        print(f"bench: {bin_dir} does not exist: build first (tools/run bench)", file=sys.stderr)
        return 2
    raw = build / "bench-raw"
    raw.mkdir(parents=True, exist_ok=True)
    real = args.real_data if args.real_data and Path(args.real_data).is_dir() else None
    if args.hand_built_models:
        real = None
    elif args.real_data and real is None:
        print(f"bench: real data folder {args.real_data} not found: hand-built task models are used",
              file=sys.stderr)

    res = {"date_utc": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
           "mode": "quick" if args.quick else "full", "host": host_info(), "load_before": load_average(),
           "argv": " ".join(["tools/bench.py"] + (argv if argv is not None else sys.argv[1:])),
           "settings": {"trials": trials, "time_ms": time_ms, "seed": args.seed}}
    t_start = time.time()

    def section(name, fn):
        if name not in only:
            return
        print(f"bench: {name} ...", file=sys.stderr, flush=True)
        t0 = time.time()
        try:
            res[name] = fn()
        except (bp.BenchError, subprocess.SubprocessError, OSError, ValueError) as e:
            res[name] = {"error": str(e)}
            print(f"bench: {name} failed: {e}", file=sys.stderr)
        except Exception as e:  # a bug in the harness: keep the other sections
            res[name] = {"error": f"{type(e).__name__}: {e}", "traceback": traceback.format_exc()}
            print(f"bench: {name} failed: {e}", file=sys.stderr)
        res.setdefault("section_seconds", {})[name] = round(time.time() - t0, 1)

    models = {}

    def get_models():
        if not models:
            models.update(bp.ensure_models(bin_dir, build / "bench-models", real))
        return models

    section("memory", lambda: bp.run_memory(bin_dir, time_ms))

    def ompl():
        out = {"length": bp.run_ompl_comparison(bin_dir, "length", trials, time_ms, args.seed, None,
                                                raw / "ompl_length.jsonl",
                                                None if args.quick else ROOT / "bench" / "ompl_length.log")}
        try:  # the length comparison stands even when the task model cannot be made
            m = get_models()
            out["task"] = bp.run_ompl_comparison(bin_dir, "task", trials, time_ms, args.seed, m["avoid"],
                                                 raw / "ompl_task.jsonl", None)
            out["task"]["model_source"] = m["source"]
        except (bp.BenchError, subprocess.SubprocessError, OSError) as e:
            out["task"] = {"error": str(e)}
        return out
    section("ompl", ompl)
    if doc_path and isinstance(res.get("ompl"), dict) and "error" not in res["ompl"]:
        # The cost-over-time figure next to the report (docs/img/).
        fig = doc_path.parent / "img" / "benchmarks-ompl-cost.png"
        recs = [raw / "ompl_length.jsonl"] + ([raw / "ompl_task.jsonl"] if "error" not in res["ompl"].get("task", {})
                                              else [])
        cmd = [sys.executable, "-m", "gmmrrt_tools.bench.plot"] + [str(r) for r in recs] + ["-o", str(fig)]
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
        if proc.returncode == 0:
            res["ompl"]["figure"] = str(fig.relative_to(doc_path.parent))
            res["ompl"]["figure_command"] = " ".join([".venv/bin/python"] + cmd[1:])
        else:
            res["ompl"]["figure_error"] = proc.stderr.strip()[-300:]

    def planners():
        try:  # the social scenes need the models; the geometric problems and the map do not
            m = get_models()
            avoid, approach = m["avoid"], m["approach"]
        except (bp.BenchError, subprocess.SubprocessError, OSError):
            avoid = approach = None
        out = bp.run_all_planners(bin_dir, args.quick, raw / "all_planners.jsonl", avoid, approach,
                                  ROOT / "logs" / "maps" / "floor.yaml", build / "bench-arena")
        if not args.quick:  # one scene's Planner Arena logs kept as the committed example (tens of KB)
            example = ROOT / "bench" / "arena"
            example.mkdir(exist_ok=True)
            for old in example.glob("*.log"):
                old.unlink()
            for log in sorted((build / "bench-arena").glob("MAP_*.log")):
                shutil.copyfile(log, example / log.name)
            out["arena_example"] = "bench/arena/" + ", ".join(sorted(p.name for p in example.glob("*.log")))
        return out
    section("planners", planners)

    def social():
        m = get_models()
        out = {"models": m}
        for task in ("avoid", "approach"):
            out[task] = bp.run_social(bin_dir, task, m[task], trials, time_ms, args.seed, raw / f"social_{task}.jsonl")
        return out
    section("social", social)

    def learner():
        from gmmrrt_tools.bench import learner as bench_learner  # numpy/scikit-learn only when needed
        return bench_learner.run_learner(bin_dir, build / "bench-data", args.quick, args.seed,
                                         Path(args.real_data) if args.real_data else None)
    section("learner", learner)
    section("micro", lambda: run_micro(build, args.quick))
    section("daemon", lambda: run_daemon(args.quick, raw))

    res["load_after"] = load_average()
    res["total_seconds"] = round(time.time() - t_start, 1)
    res["targets"] = evaluate_targets(res)
    res = relative_paths(clean(res))

    results_path.parent.mkdir(parents=True, exist_ok=True)
    with tempfile.NamedTemporaryFile("w", dir=results_path.parent, delete=False, suffix=".tmp") as f:
        json.dump(res, f, indent=1, allow_nan=False)
        tmp = f.name
    os.replace(tmp, results_path)
    print(f"bench: wrote {results_path}", file=sys.stderr)
    if doc_path:
        shown = results_path.resolve()
        write_markdown(res, doc_path, shown.relative_to(ROOT) if ROOT in shown.parents else shown)
        print(f"bench: wrote {doc_path}", file=sys.stderr)
    for t in res["targets"]:
        print(f"  {t['status']:>8}  {t['name']}: {t['value_text']} (target {t['target']})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
