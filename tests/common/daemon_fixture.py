"""Shared by the tests that drive gmmrrtd (tests/replay; tests/fault): where the
daemon is, the scenario test models, the sanitizer-aware environment and exit check, and one
deterministic replay (file:// in and out, speed=0, log clock, iteration budget; docs/daemon.md,
"Deterministic replays").

Each folder's conftest.py imports the fixtures `gmmrrtd` and `models` from here, so pytest finds
them; the test modules import the helpers (`from tests.common.daemon_fixture import
run_log_clock`): `tests` is a namespace package of the repository root, where pytest runs. The daemon under test is the one in
$GMMRRT_BIN_DIR (set by CTest: build/bin, or build-asan/bin in the sanitizer pass), else
build/bin of this checkout.
"""
import os
import re
import subprocess
import sys

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SCENARIOS = os.path.join(ROOT, "logs", "scenarios")

# Radii every replay uses, m (the golden summaries of tests/replay were made with them).
ROBOT_RADIUS, PERSON_RADIUS = 0.3, 0.25
SANITIZER_REPORT = re.compile(r"ERROR: (AddressSanitizer|LeakSanitizer)|runtime error:|SUMMARY: UndefinedBehavior")


def gmmrrtd_path():
    bindir = os.environ.get("GMMRRT_BIN_DIR", os.path.join(ROOT, "build", "bin"))
    return os.path.join(bindir, "gmmrrtd")


def venv_bin(name):
    """An executable of the venv that runs the tests (lcm-logger, lcm-logplayer)."""
    return os.path.join(os.path.dirname(sys.executable), name)


def daemon_env():
    """The environment for gmmrrtd: in a sanitizer build, leaks and memory errors end the daemon
    with a distinct code and a report on stderr; a plain build ignores these variables."""
    env = dict(os.environ)
    env["ASAN_OPTIONS"] = "detect_leaks=1:exitcode=86:abort_on_error=0"
    env["UBSAN_OPTIONS"] = "print_stacktrace=1:halt_on_error=1:exitcode=87"
    return env


def assert_clean(returncode, stderr, what="gmmrrtd"):
    """Fails on any sanitizer report in stderr or a non-zero exit."""
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
    """gmmrrtd over the file:// log in_log (speed=0, log clock, seed 7, `iterations` per plan) into
    the file:// log out_log; asserts a clean exit (no sanitizer report), returns stderr.
    extra: more daemon flags (a later flag wins); wrapper: a command to run the daemon under."""
    cmd = [*wrapper, gmmrrtd, "--lcm-url", "file://%s?speed=0" % in_log, "--lcm-out-url", "file://%s?mode=w" % out_log,
           "--exit-at-eof", "--model-avoid", models["avoid"], "--model-approach", models["approach"],
           "--budget-ms", "0", "--budget-iterations", str(iterations), "--seed", "7",
           "--robot-radius", str(ROBOT_RADIUS), "--person-radius", str(PERSON_RADIUS), "--log-level", "warn", *extra]
    res = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=daemon_env())
    assert_clean(res.returncode, res.stderr)
    return res.stderr
