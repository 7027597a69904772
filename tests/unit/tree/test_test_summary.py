"""tree.test_summary: the end summary of tools/run test (tools/test_summary.py) on hand-made
CTest JUnit files: a SKIP_RETURN_CODE test is a skip with its pytest reason, a "Not Run" for a
missing executable or a failed fixture is a failure, skips inside passing files are listed,
a pass that was not run shows its reason, and the exit status is 1 exactly when a pass failed."""
import subprocess
import sys
from pathlib import Path

SCRIPT = Path(__file__).resolve().parents[3] / "tools" / "test_summary.py"

JUNIT = """<?xml version="1.0" encoding="UTF-8"?>
<testsuite name="x" tests="4">
  <testcase name="learner.real_data" status="notrun">
    <skipped message="SKIP_RETURN_CODE=77"/>
    <system-out>sss
SKIPPED [3] tests/unit/learner/test_real_data.py:51: real data not found at /nowhere (set GMMRRT_REAL_DATA)
</system-out>
  </testcase>
  <testcase name="metrics.experiments" status="run">
    <system-out>.s
SKIPPED [1] tests/unit/metrics/test_experiments_cli.py:59: real data not found
</system-out>
  </testcase>
  <testcase name="planner.gmm" status="run"><system-out>ok</system-out></testcase>
  <testcase name="planner.alloc" status="notrun">
    <skipped message="SKIP_RETURN_CODE=77"/>
    <system-out>[ RUN      ] test_planning_allocates_nothing
allocation counting is off under the sanitizers
</system-out>
  </testcase>
  <testcase name="daemon.timeguard" status="notrun">
    <skipped message="Unable to find executable"/>
    <system-out>Unable to find executable: tests/test_daemon_timeguard</system-out>
  </testcase>
</testsuite>
"""


def summary(tmp_path, rows):
    tsv = tmp_path / "passes.tsv"
    tsv.write_text("".join("\t".join(r) + "\n" for r in rows))
    return subprocess.run([sys.executable, str(SCRIPT), str(tsv)], capture_output=True, text=True)


def test_skips_failures_and_exit_status(tmp_path):
    junit = tmp_path / "plain.xml"
    junit.write_text(JUNIT)
    r = summary(tmp_path, [["build", "passed", "12", "-", "warnings as errors"],
                           ["plain", "failed", "75", str(junit), "CTest"],
                           ["fuzz", "not run", "0", "-", "GMMRRT_SKIP_FUZZ is set"]])
    assert r.returncode == 1, r.stdout
    plain = next(l for l in r.stdout.splitlines() if l.startswith("plain"))
    assert plain.split()[1:5] == ["FAILED", "2", "1", "2"], plain
    assert "planner.alloc: allocation counting is off under the sanitizers" in r.stdout
    assert "daemon.timeguard (Unable to find executable)" in r.stdout
    assert "learner.real_data x3: test_real_data.py: real data not found at /nowhere" in r.stdout
    assert "metrics.experiments (inside a passing file): test_experiments_cli.py: real data not found" in r.stdout
    assert "GMMRRT_SKIP_FUZZ is set" in r.stdout and "FAILED (plain)" in r.stdout


def test_all_passed_exits_0(tmp_path):
    r = summary(tmp_path, [["build", "passed", "3", "-", ""], ["asan", "not run", "0", "-", "GMMRRT_SKIP_ASAN is set"]])
    assert r.returncode == 0 and "all passes that ran passed" in r.stdout, r.stdout
