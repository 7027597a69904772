"""Fixtures of the replay tests: gmmrrtd and the test models, from the helpers shared
with tests/fault (tests/common/daemon_fixture.py: where gmmrrtd and the scenarios are, the
replay radii, run_log_clock); GOLDEN is this folder's own."""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "common"))

from daemon_fixture import gmmrrtd, models  # noqa: E402,F401  (pytest finds fixtures by name here)

GOLDEN = os.path.join(HERE, "golden", "summaries.json")
