"""Fixtures of the fault-injection replays: gmmrrtd and the test models, from the
helpers shared with tests/replay (tests/common/daemon_fixture.py, which also holds the
run-and-check step every fault test uses: run_log_clock, daemon_env, assert_clean).

The tests drive the gmmrrtd of the build they are registered in: the Release build in build/
and, in the sanitizer pass of tools/run test, the AddressSanitizer + UBSan build in
build-asan/ (label `fault`, not `python`: only the daemon is instrumented, the venv's Python
just launches it). Every run asserts a clean exit and no sanitizer report, so in build-asan a
leak or memory error anywhere in the daemon fails the test (LeakSanitizer runs at exit).
"""
from tests.common.daemon_fixture import gmmrrtd, models  # noqa: F401  (pytest finds fixtures by name here)
