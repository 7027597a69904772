#!/usr/bin/env python3
"""The end summary of `tools/run test`: one line per pass, then every skip with its reason.

    python3 tools/test_summary.py PASSES.tsv

PASSES.tsv has one line per pass, tab-separated: name, state (passed / failed / not run),
seconds, the JUnit file CTest wrote for it (or -), a note (why it was not run, which kernel...).
From each JUnit file: tests passed, failed (a CTest "Not Run" other than a skip is a failure:
a missing executable or a failed fixture) and skipped (SKIP_RETURN_CODE / SKIP_REGULAR_EXPRESSION),
with the reason of each skip: pytest's "SKIPPED [n] file:line: reason" lines (-rs), a C test's
"SKIP..." line, else its last line of output. Skips inside files that passed are listed too.
Exit status: 1 if any pass failed, else 0. Standard library only (runs without the venv).
"""
import re
import sys
import xml.etree.ElementTree as ET

PYTEST_SKIP = re.compile(r"^SKIPPED \[(\d+)\] ([^:]+):\d+: (.*)$")


def skip_reasons(out):
    """Reasons found in one test's output, as (text, count) pairs."""
    found = {}
    for line in out.splitlines():
        m = PYTEST_SKIP.match(line.strip())
        if m:
            key = "%s: %s" % (m.group(2).rsplit("/", 1)[-1], m.group(3))
            found[key] = found.get(key, 0) + int(m.group(1))
        elif line.strip().upper().startswith("SKIP") and not m:
            found[line.strip()] = found.get(line.strip(), 0) + 1
    return sorted(found.items())


def read_junit(path):
    counts = {"passed": 0, "failed": 0, "skipped": 0}
    failed, skips = [], []
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as exc:
        return None, ["no test results (%s)" % exc], []
    for case in root.iter("testcase"):
        name = case.get("name")
        out = (case.findtext("system-out") or "")
        skipped = case.find("skipped")
        status = case.get("status")
        if skipped is not None and (skipped.get("message") or "").startswith(("SKIP_", "Disabled")):
            counts["skipped"] += 1
            reasons = skip_reasons(out)
            if not reasons:
                last = [l for l in out.splitlines() if l.strip()]
                reasons = [(last[-1].strip() if last else skipped.get("message"), 1)]
            skips += [(name, n, r) for r, n in reasons]
        elif status == "run":
            counts["passed"] += 1
            skips += [(name + " (inside a passing file)", n, r) for r, n in skip_reasons(out)]
        else:
            counts["failed"] += 1
            why = skipped.get("message") if skipped is not None else "failed"
            failed.append("%s (%s)" % (name, why or "failed"))
    return counts, failed, skips


def duration(s):
    s = int(float(s))
    return "%dm%02ds" % (s // 60, s % 60) if s >= 60 else "%ds" % s


def main():
    rows = [line.rstrip("\n").split("\t") for line in open(sys.argv[1]) if line.strip()]
    bar = "=" * 78
    print(bar)
    print("tools/run test: summary")
    print("%-8s %-8s %7s %7s %8s %7s  %s" % ("pass", "result", "passed", "failed", "skipped", "time", "note"))
    all_skips, any_failed, failures = [], [], []
    for name, state, secs, junit, note in rows:
        counts, failed, skips = (None, [], []) if junit in ("", "-") else read_junit(junit)
        if state == "failed":
            any_failed.append(name)
        c = counts or {}
        cells = [str(c[k]) if counts else "-" for k in ("passed", "failed", "skipped")]
        shown = "FAILED" if state == "failed" else state
        print("%-8s %-8s %7s %7s %8s %7s  %s" % (name, shown, *cells, duration(secs) if state != "not run" else "-", note))
        failures += ["%s: %s" % (name, f) for f in failed]
        all_skips += [(name, *s) for s in skips]
    if failures:
        print("failed tests:")
        for f in failures[:20]:
            print("  " + f)
        if len(failures) > 20:
            print("  ... and %d more (see each pass's output above)" % (len(failures) - 20))
    if all_skips:
        print("skips (the only allowed: optional real data, benchmark-only peers, checks a build cannot run):")
        for pass_name, test, n, reason in all_skips:
            print("  %-7s %s%s: %s" % (pass_name, test, " x%d" % n if n > 1 else "", reason))
    print("result: %s" % ("FAILED (%s)" % ", ".join(any_failed) if any_failed else "all passes that ran passed"))
    print(bar)
    return 1 if any_failed else 0


if __name__ == "__main__":
    sys.exit(main())
