"""replay.deterministic: every scenario of logs/scenarios/ through gmmrrtd with file:// input
(speed=0) and file:// output, the log clock and an iteration budget, so a replay is the same
every time (docs/daemon.md, "Deterministic replays"). Checks (tools/gmmrrt_tools/replay_check.py):
plans start at the robot, end at the goal, are collision-free, one cycle per period of input
time, the reject counters equal the planted faults; the summary matches the golden one
(tests/replay/golden/summaries.json) within tolerance; two runs give identical output.

Regenerate the golden summaries (after a deliberate planner change, with the reason in the
commit): GMMRRT_UPDATE_GOLDEN=1 ctest --test-dir build -R replay.deterministic
"""
import json
import os

import pytest
from tests.common import daemon_fixture
from conftest import GOLDEN
from tests.common.daemon_fixture import PERSON_RADIUS, ROBOT_RADIUS, ROOT, SCENARIOS

from gmmrrt_tools import replay_check

ITERATIONS = 1000
with open(os.path.join(SCENARIOS, "scenarios.json")) as f:
    INDEX = json.load(f)


def run_log_clock(gmmrrtd, models, scenario, out_path, extra=()):
    """One scenario through gmmrrtd (daemon_fixture.run_log_clock: clean exit, no sanitizer report),
    with the flags its index entry asks for (paths in them relative to the checkout)."""
    args = [os.path.join(ROOT, a) if a.startswith("logs/") else a for a in INDEX[scenario].get("daemon_args", [])]
    daemon_fixture.run_log_clock(gmmrrtd, models, os.path.join(SCENARIOS, INDEX[scenario]["log"]), out_path,
                                 iterations=ITERATIONS, extra=(*args, *extra))
    assert os.path.getsize(out_path) > 0, "gmmrrtd wrote nothing to %s" % out_path


@pytest.fixture(scope="module")
def summaries():
    return {}


@pytest.mark.parametrize("scenario", sorted(INDEX))
def test_scenario_replays_and_passes_the_checks(gmmrrtd, models, tmp_path, scenario, summaries):
    out = str(tmp_path / "out.lcmlog")
    run_log_clock(gmmrrtd, models, scenario, out)
    summary, failures = replay_check.check(
        os.path.join(SCENARIOS, INDEX[scenario]["log"]), out, rate_hz=10.0, robot_radius=ROBOT_RADIUS,
        person_radius=PERSON_RADIUS, expected_rejected=INDEX[scenario]["expected_rejected"])
    assert not failures, "\n".join(failures)
    # Every scenario must actually plan: a daemon that only ever stops would pass the checks above.
    assert summary["plans_nonempty"] >= summary["cycles"] // 3, summary
    summaries[scenario] = summary

    if os.environ.get("GMMRRT_UPDATE_GOLDEN"):
        golden = json.load(open(GOLDEN)) if os.path.exists(GOLDEN) else {}
        golden[scenario] = summary
        with open(GOLDEN, "w") as f:
            json.dump(golden, f, indent=2, sort_keys=True)
            f.write("\n")
        return
    with open(GOLDEN) as f:
        golden = json.load(f)
    assert scenario in golden, "no golden summary for %s (see the module docstring)" % scenario
    diffs = replay_check.compare_golden(summary, golden[scenario])
    assert not diffs, "\n".join(diffs)


def test_two_replays_give_identical_plans(gmmrrtd, models, tmp_path):
    outs = []
    for i in range(2):
        out = str(tmp_path / ("out%d.lcmlog" % i))
        run_log_clock(gmmrrtd, models, "avoid_crowd", out)
        outs.append([(c, d) for _, c, d in replay_check.read_events(out)])
    assert len(outs[0]) == len(outs[1]) > 0
    for k, (a, b) in enumerate(zip(*outs)):
        if a[0] == "PLANNER_STATUS":
            continue  # carries plan_time_ms, wall-clock time
        assert a == b, "message %d (%s) differs between two replays" % (k, a[0])


def test_another_seed_changes_the_plans_but_not_the_checks(gmmrrtd, models, tmp_path):
    """The determinism above is not an accident of a planner that ignores its input."""
    out_a, out_b = str(tmp_path / "a.lcmlog"), str(tmp_path / "b.lcmlog")
    run_log_clock(gmmrrtd, models, "avoid_one_person", out_a)
    run_log_clock(gmmrrtd, models, "avoid_one_person", out_b, extra=("--seed", "8"))
    plans_a = [d for _, c, d in replay_check.read_events(out_a) if c == "PLAN"]
    plans_b = [d for _, c, d in replay_check.read_events(out_b) if c == "PLAN"]
    assert plans_a != plans_b
    summary, failures = replay_check.check(os.path.join(SCENARIOS, "avoid_one_person.lcmlog"), out_b,
                                           expected_rejected={})
    assert not failures, "\n".join(failures)


def test_scenario_logs_match_their_generator():
    """logs/scenarios/ is exactly what tools/make_scenarios.py writes (no hand-edited logs)."""
    import subprocess as sp
    import sys
    res = sp.run([sys.executable, os.path.join(ROOT, "tools", "make_scenarios.py"), "--check", "--out", SCENARIOS],
                 capture_output=True, text=True)
    assert res.returncode == 0, res.stderr
