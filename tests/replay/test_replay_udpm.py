"""replay.udpm: the scenario with planted faults played by the real tools. lcm-logplayer
plays logs/scenarios/faults.lcmlog in real time into a running gmmrrtd (live clock, time
budget) over UDP multicast on a private port with ttl=0; lcm-logger records every channel (the
inputs as the daemon received them and its PLAN and PLANNER_STATUS, in one order);
tools/gmmrrt_tools/replay_check.py checks the recording. Which goal, people and obstacles a plan
was made with is read from that order (between the pose it names and the plan), not from a time
window, so a stalled lcm-logplayer cannot make the check fail: plans collision-free,
starting at the robot, ending at the goal, a status every period (median interval within
15 %), and the reject counters equal to the planted faults, plus one more pose gap: after the
log ends the daemon must publish stops (status GMMRRT_STOP_POSE_STALE), never an old plan.
Then SIGTERM must end the daemon cleanly (exit 0).
"""
import json
import os
import signal
import subprocess
import time

from tests.common.daemon_fixture import PERSON_RADIUS, ROBOT_RADIUS, SCENARIOS, venv_bin

from gmmrrt import waypoints_t
from gmmrrt_tools import replay_check
from gmmrrt_tools.lcm_url import private_url

GMMRRT_STOP_POSE_STALE = 50  # gmmrrtd's stop code (planner/daemon/stop.h)
# Longer than the 0.5 s of the log-clock tests: on a loaded shared machine lcm-logplayer itself can
# stall for a few hundred ms, which a 0.5 s limit would count as an extra pose gap. The planted gap
# is 1.5 s, so it still counts exactly once.
POSE_TIMEOUT_MS = 1000


def wait_for_line(proc_err_path, text, timeout_s=10.0):
    end = time.monotonic() + timeout_s
    while time.monotonic() < end:
        with open(proc_err_path) as f:
            if text in f.read():
                return True
        time.sleep(0.05)
    return False


def test_logplayer_into_gmmrrtd_over_udpm(gmmrrtd, models, tmp_path):
    play_and_check(gmmrrtd, models, tmp_path, stalls_s=())


def test_logplayer_stalled_twice_mid_play(gmmrrtd, models, tmp_path):
    """What a loaded machine does to lcm-logplayer, on purpose: SIGSTOP for 0.4 s, twice. The
    old checker's 300 ms time window then lost the goal in force; reading the recorded order
    it cannot. The stalls stay below every timeout (pose 1 s, people 1 s), so the counters stay
    the planted ones."""
    play_and_check(gmmrrtd, models, tmp_path, stalls_s=(2.0, 4.5))


def play_and_check(gmmrrtd, models, tmp_path, stalls_s):
    url = private_url()
    rec = str(tmp_path / "recorded.lcmlog")
    err_path = str(tmp_path / "gmmrrtd.stderr")
    with open(os.path.join(SCENARIOS, "scenarios.json")) as f:
        expected = dict(json.load(f)["faults"]["expected_rejected"])
    expected["REJECT_POSE_STALE"] = expected.get("REJECT_POSE_STALE", 0) + 1  # the end of the log
    expected["REJECT_PEOPLE_STALE"] = expected.get("REJECT_PEOPLE_STALE", 0) + 1  # the tracker ends too

    logger = subprocess.Popen([venv_bin("lcm-logger"), "-q", "-f", "--lcm-url", url, "-c", "ROBOT_POSE|PEOPLE|NAV_GOAL|OBSTACLES|PLAN|PLANNER_STATUS",
                               "--flush-interval", "50", rec])
    with open(err_path, "w") as err:
        daemon = subprocess.Popen([gmmrrtd, "--lcm-url", url, "--model-avoid", models["avoid"],
                                   "--model-approach", models["approach"], "--rate-hz", "10", "--budget-ms", "70",
                                   "--robot-radius", str(ROBOT_RADIUS), "--person-radius", str(PERSON_RADIUS),
                                   "--pose-timeout-ms", str(POSE_TIMEOUT_MS)], stderr=err)
    try:
        assert wait_for_line(err_path, "running:"), open(err_path).read()
        time.sleep(0.3)
        play = subprocess.Popen([venv_bin("lcm-logplayer"), "--lcm-url", url, os.path.join(SCENARIOS, "faults.lcmlog")],
                                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        started = time.monotonic()
        for at in stalls_s:
            time.sleep(max(0.0, started + at - time.monotonic()))
            play.send_signal(signal.SIGSTOP)
            time.sleep(0.4)
            play.send_signal(signal.SIGCONT)
        assert play.wait(timeout=60) == 0, play.stderr.read()
        time.sleep(POSE_TIMEOUT_MS / 1000.0 + 1.0)  # past the pose timeout: the daemon must stop the robot
        daemon.send_signal(signal.SIGTERM)
        assert daemon.wait(timeout=10) == 0, open(err_path).read()
    finally:
        if daemon.poll() is None:
            daemon.kill()
            daemon.wait()
        time.sleep(0.3)
        logger.send_signal(signal.SIGINT)
        logger.wait(timeout=10)

    summary, failures = replay_check.check(os.path.join(SCENARIOS, "faults.lcmlog"), rec, rate_hz=10.0,
                                           robot_radius=ROBOT_RADIUS, person_radius=PERSON_RADIUS,
                                           expected_rejected=expected, live=True)
    assert not failures, "\n".join(failures) + "\n" + json.dumps(summary, indent=1) + open(err_path).read()
    assert summary["plans_nonempty"] >= 20, summary

    # The last plans (after the log ended) are stops that say the pose is stale.
    plans = [waypoints_t.decode(d) for _, c, d in replay_check.read_events(rec) if c == "PLAN"]
    assert plans, "no plan recorded"
    tail = plans[-5:]
    assert all(p.num_waypoints == 0 and p.status == GMMRRT_STOP_POSE_STALE for p in tail), \
        [(p.num_waypoints, p.status) for p in tail]
