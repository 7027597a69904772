"""architecture.layers: the source tree keeps the layers of docs/architecture.md.

The rules are read from the "Layers" table of docs/architecture.md (the document is the rule, so
it cannot drift from what is checked): for each module, the folders of its sources, the headers it
must not include (a prefix when it ends with "/", else a whole header name) and the functions it
must not call. Every C/C++ source folder of planner/, learner/ and lcmtypes/ must belong to a
module of the table. The checker itself is tested on planted violations, so it can fail.
"""
import re
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
DOC = REPO / "docs" / "architecture.md"
SOURCE_SUFFIXES = {".c", ".h", ".cpp", ".hpp", ".inc"}
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^>"]+)[>"]', re.M)


def layers(text):
    """{module: (folders, forbidden includes, forbidden calls)} from the Layers table."""
    section = text.split("## Layers", 1)[1].split("\n## ", 1)[0]
    rows = [ln for ln in section.splitlines() if ln.startswith("|")]
    head = [c.strip() for c in rows[0].strip("|").split("|")]
    assert head == ["module", "sources", "must not include", "must not call"], head
    out = {}
    for ln in rows[2:]:
        cells = [c.strip() for c in ln.strip().strip("|").split("|")]
        ticks = [re.findall(r"`([^`]+)`", c) for c in cells[1:]]
        out[cells[0]] = tuple(ticks)
    return out


def strip_comments_and_strings(src):
    src = re.sub(r"/\*.*?\*/", " ", src, flags=re.S)
    src = re.sub(r"//[^\n]*", " ", src)
    return re.sub(r'"(?:\\.|[^"\\\n])*"', '""', src)


def violations(files, forbidden_includes, forbidden_calls):
    """One line per forbidden include or call in `files` (paths)."""
    found = []
    calls = re.compile(r"(?<![\w.>:])(" + "|".join(map(re.escape, forbidden_calls)) + r")\s*\(") \
        if forbidden_calls else None
    for path in files:
        text = Path(path).read_text(errors="replace")
        for inc in INCLUDE.findall(text):
            for bad in forbidden_includes:
                hit = inc.startswith(bad) if bad.endswith("/") or bad.endswith("_") else \
                    (inc == bad or inc.endswith("/" + bad))
                if hit:
                    found.append(f"{path}: includes <{inc}> (forbidden: {bad})")
        if calls:
            code = strip_comments_and_strings(text)
            for m in calls.finditer(code):
                line = code.count("\n", 0, m.start()) + 1
                found.append(f"{path}:{line}: calls {m.group(1)}()")
    return found


def sources(folder):
    return sorted(p for p in (REPO / folder).rglob("*") if p.suffix in SOURCE_SUFFIXES and p.is_file())


RULES = layers(DOC.read_text())


def test_the_table_lists_the_modules():
    assert {"core", "model files", "messages", "planner CLI", "daemon", "learner"} <= set(RULES)


@pytest.mark.parametrize("module", sorted(RULES))
def test_no_module_includes_or_calls_what_its_layer_forbids(module):
    folders, bad_includes, bad_calls = RULES[module]
    files = [p for f in folders for p in sources(f)]
    assert files, f"{module}: no sources in {folders}"
    found = violations(files, bad_includes, bad_calls)
    assert not found, "docs/architecture.md, Layers:\n" + "\n".join(str(v) for v in found)


def test_every_source_folder_belongs_to_a_module():
    listed = {REPO / f for folders, _, _ in RULES.values() for f in folders}
    unlisted = set()
    for top in ("planner", "learner", "lcmtypes"):
        for p in sources(top):
            if not any(p.is_relative_to(d) for d in listed):
                unlisted.add(str(p.parent.relative_to(REPO)))
    assert not unlisted, f"source folders missing from docs/architecture.md's Layers table: {sorted(unlisted)}"


def test_the_checker_catches_planted_violations(tmp_path):
    bad = tmp_path / "bad.c"
    bad.write_text('#include <lcm/lcm.h>\n#include "gmmrrt/gmmrrt_pose2d_t.h"\n#include "daemon.h"\n'
                   '/* fopen(x) in a comment is fine */\nstatic const char *s = "printf(";\n'
                   'void f(void) { FILE *fp = fopen("x", "r"); (void)fp; }\n')
    _, inc, calls = RULES["core"]
    found = violations([bad], inc, calls)
    assert any("<lcm/lcm.h>" in v for v in found)
    assert any("gmmrrt_pose2d_t.h" in v for v in found)
    assert any("<daemon.h>" in v for v in found)
    assert [v for v in found if "calls" in v] == [f"{bad}:6: calls fopen()"]
    good = tmp_path / "good.c"
    good.write_text('#include "gmmrrt/features.h"\n#include <math.h>\nint my_fopen(void);\n')
    assert violations([good], inc, calls) == []
