"""Shared helpers of the replay tests: where gmmrrtd and the scenarios are, test models."""
import os
import sys

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "tools"))
SCENARIOS = os.path.join(ROOT, "logs", "scenarios")
GOLDEN = os.path.join(os.path.dirname(__file__), "golden", "summaries.json")

# The settings every replay uses (the golden summaries were made with them).
ROBOT_RADIUS, PERSON_RADIUS = 0.3, 0.25


def gmmrrtd_path():
    bindir = os.environ.get("GMMRRT_BIN_DIR", os.path.join(ROOT, "build", "bin"))
    return os.path.join(bindir, "gmmrrtd")


def venv_bin(name):
    return os.path.join(os.path.dirname(sys.executable), name)


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
