"""Copies the result tables of docs/results into docs/experiments.md.
"""
from __future__ import annotations

import os
from pathlib import Path

# ==================================================================== docs

REPORT_ORDER = [("table1", "Table 1"), ("fig1", "Fig. 1"), ("fig3", "Fig. 3"), ("fig5", "Fig. 5"), ("fig6", "Fig. 6"),
                ("real_upo_avoid", "Real data: UPO avoid"), ("real_ucy_avoid", "Real data: UCY avoid"),
                ("real_ucy_approach", "Real data: UCY approach"),
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
