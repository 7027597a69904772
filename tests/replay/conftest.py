"""Fixtures of the replay tests: gmmrrtd and the test models, from the helpers shared
with tests/fault (tests/common/daemon_fixture.py: where gmmrrtd and the scenarios are, the
replay radii, run_log_clock); GOLDEN is this folder's own."""
import os

from tests.common.daemon_fixture import gmmrrtd, models  # noqa: F401  (pytest finds fixtures by name here)

HERE = os.path.dirname(os.path.abspath(__file__))

GOLDEN = os.path.join(HERE, "golden", "summaries.json")
