"""Shared helpers of the fault-injection replays (issue 9): where gmmrrtd is, test models, and
the run-and-check step every fault test uses.

The tests drive the gmmrrtd of the build they are registered in: the Release build in build/
and, in the sanitizer pass of tools/run test, the AddressSanitizer + UBSan build in
build-asan/ (label `fault`, not `python`: only the daemon is instrumented, the venv's Python
just launches it). Every run asserts a clean exit and no sanitizer report, so in build-asan a
leak or memory error anywhere in the daemon fails the test (LeakSanitizer runs at exit).
"""
import os
import re
import subprocess
import sys

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "tools"))

ROBOT_RADIUS, PERSON_RADIUS = 0.3, 0.25
SANITIZER_REPORT = re.compile(r"ERROR: (AddressSanitizer|LeakSanitizer)|runtime error:|SUMMARY: UndefinedBehavior")


def gmmrrtd_path():
    bindir = os.environ.get("GMMRRT_BIN_DIR", os.path.join(ROOT, "build", "bin"))
    return os.path.join(bindir, "gmmrrtd")


def daemon_env():
    env = dict(os.environ)
    # Leaks and memory errors end the daemon with a distinct code and a report on stderr.
    env["ASAN_OPTIONS"] = "detect_leaks=1:exitcode=86:abort_on_error=0"
    env["UBSAN_OPTIONS"] = "print_stacktrace=1:halt_on_error=1:exitcode=87"
    return env


def assert_clean(returncode, stderr, what="gmmrrtd"):
    m = SANITIZER_REPORT.search(stderr)
    assert m is None, "%s: sanitizer report:\n%s" % (what, stderr[-6000:])
    assert returncode == 0, "%s exited %d:\n%s" % (what, returncode, stderr[-4000:])


@pytest.fixture(scope="session")
def gmmrrtd():
    path = gmmrrtd_path()
    if not os.access(path, os.X_OK):
        pytest.fail("gmmrrtd not found at %s (build first: tools/run build)" % path)
    return path


@pytest.fixture(scope="session")
def models(tmp_path_factory):
    from gmmrrt_tools.scenario_models import write_models
    return write_models(str(tmp_path_factory.mktemp("models")))


def run_log_clock(gmmrrtd, models, in_log, out_log, iterations=300, extra=(), wrapper=(), timeout=600):
    """gmmrrtd over a file:// log (speed=0, log clock) into a file:// output; returns stderr."""
    cmd = [*wrapper, gmmrrtd, "--lcm-url", "file://%s?speed=0" % in_log, "--lcm-out-url", "file://%s?mode=w" % out_log,
           "--exit-at-eof", "--model-avoid", models["avoid"], "--model-approach", models["approach"],
           "--budget-ms", "0", "--budget-iterations", str(iterations), "--seed", "7",
           "--robot-radius", str(ROBOT_RADIUS), "--person-radius", str(PERSON_RADIUS), "--log-level", "warn", *extra]
    res = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=daemon_env())
    assert_clean(res.returncode, res.stderr)
    return res.stderr
