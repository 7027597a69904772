"""gmmrrt_tools.bench.merge_sections - fold a partial benchmark run (tools/bench.py --only ... --results FILE
--no-doc) into bench/results.json and rewrite docs/benchmarks.md from the merged results.

Sections present in the partial run (and its date, host, loads and command) replace the old ones;
sections it did not run are kept from the previous full run and listed under "carried_over" with
that run's date and commit, which the report then states. Used when only the planner changed, so
the learner and daemon figures need not be measured again (see docs/benchmarks.md).

    .venv/bin/python -m gmmrrt_tools.bench.merge_sections build/bench-pp.json
"""
import argparse
import json
import subprocess
import sys
from pathlib import Path

from gmmrrt_tools.bench.report import evaluate_targets, write_markdown

ROOT = Path(__file__).resolve().parents[3]

SECTIONS = ("memory", "ompl", "planners", "social", "learner", "micro", "daemon")


def merge(old: dict, new: dict) -> dict:
    """new's sections, and old's for those new did not run, each of these listed under
    "carried_over" with the date, commit, command and load of the run that measured it (kept from
    old's own list when old had carried it already)."""
    merged = dict(new)
    carried = dict(old.get("carried_over", {}))
    for s in SECTIONS:
        if s not in new and s in old:
            merged[s] = old[s]
            carried.setdefault(s, {"date_utc": old.get("date_utc"), "commit": old.get("host", {}).get("commit"),
                                   "argv": old.get("argv"), "load_before": old.get("load_before"),
                                   "load_after": old.get("load_after")})
            if s in old.get("section_seconds", {}):
                merged.setdefault("section_seconds", {})[s] = old["section_seconds"][s]
        else:
            carried.pop(s, None)
    merged["carried_over"] = carried
    return merged


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("partial", type=Path, help="results JSON of a tools/bench.py --only run")
    ap.add_argument("--results", type=Path, default=ROOT / "bench" / "results.json")
    ap.add_argument("--doc", type=Path, default=ROOT / "docs" / "benchmarks.md")
    args = ap.parse_args()
    try:
        new = json.loads(args.partial.read_text())
        old = json.loads(args.results.read_text())
    except (OSError, ValueError) as e:
        print(f"merge_sections: {e}", file=sys.stderr)
        return 1
    ran = [s for s in SECTIONS if s in new]
    if not ran:
        print(f"merge_sections: {args.partial} holds none of the sections {', '.join(SECTIONS)}", file=sys.stderr)
        return 1
    merged = merge(old, new)
    carried = merged["carried_over"]
    om = merged.get("ompl")
    raw = args.partial.resolve().parent / "bench-raw"
    if "ompl" in new and isinstance(om, dict) and "error" not in om and not om.get("figure"):
        # The cost-over-time figure, as tools/bench.py makes it when it writes the report itself.
        fig = args.doc.resolve().parent / "img" / "benchmarks-ompl-cost.png"
        recs = [raw / "ompl_length.jsonl"] + ([raw / "ompl_task.jsonl"] if "error" not in om.get("task", {}) else [])
        cmd = [sys.executable, "-m", "gmmrrt_tools.bench.plot"] + [str(r) for r in recs] + ["-o", str(fig)]
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
        if proc.returncode == 0:
            om["figure"] = str(fig.relative_to(args.doc.resolve().parent))
            om["figure_command"] = " ".join([".venv/bin/python"] + [str(Path(c).relative_to(ROOT)) if str(c).startswith(str(ROOT)) else c for c in cmd[1:]])
        else:
            print(f"merge_sections: figure not made: {proc.stderr.strip()[-300:]}", file=sys.stderr)
    merged["targets"] = evaluate_targets(merged)
    args.results.write_text(json.dumps(merged, indent=1, allow_nan=False))
    shown = args.results.resolve()
    write_markdown(merged, args.doc, shown.relative_to(ROOT) if ROOT in shown.parents else shown)
    if carried:
        text = args.doc.read_text()
        note = "\n".join(
            [f"- sections **not** re-measured in this run, kept from an earlier run: "
             + "; ".join(f"{s} ({c.get('date_utc')}, commit {c.get('commit')})" for s, c in carried.items()),
             f"- merged with `.venv/bin/python -m gmmrrt_tools.bench.merge_sections {args.partial}` after "
             f"`{new.get('argv')}`", ""])
        text = text.replace("\n## Planner against OMPL RRT*", "\n" + note + "\n## Planner against OMPL RRT*", 1)
        args.doc.write_text(text)
    print(f"merge_sections: ran {', '.join(ran)}; kept {', '.join(carried) or 'nothing'}; wrote {args.results}, {args.doc}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
