"""fault.clock_live: the clock cases of fault.clock_* again, live: gmmrrtd on the monotonic clock,
over UDP multicast on loopback (a private port, ttl=0), fed by a publisher in this process that
stamps its messages as a sender would (wall clock in microseconds), then distorts them:

  * a ratchet: 60 re-sends of the current goal within 0.13 s, each stamped 1.9 s later;
  * a first goal stamped near 2^53 us;
  * a people tracker whose clock is 0.6 s / 1.9 s ahead of localisation;
  * every sender's clock stepped an hour ahead mid-run (the daemon's own clock is monotonic: a
    step of this machine's clock cannot be made here, the machine is shared; what the daemon sees
    of one, every stamp moving at once, is what is played).

Each case runs a few seconds, bounded; the pose timeout is raised to 1.5 s so that a publisher
stalled by a loaded machine is not mistaken for the effect (a dragged clock makes poses stale by
far more: 114 s for the ratchet). Run: ctest --test-dir build -R '^fault\\.clock_live'
"""
import select
import signal
import subprocess
import time

import lcm
import pytest

from gmmrrt import nav_goal_t, people_t, planner_status_t, pose2d_t
from gmmrrt_tools.lcm_url import private_url

R = planner_status_t
HOUR_US = 3600 * 10**6


def wait_running(err_path, timeout_s=10.0):
    end = time.monotonic() + timeout_s
    while time.monotonic() < end:
        if "running:" in open(err_path).read():
            return True
        time.sleep(0.05)
    return False


def play(gmmrrtd, tmp_path, seconds, stamp, extra_goals=(), first_goal=None):
    """Runs the daemon; publishes poses (20 Hz), people (10 Hz) and the goal (5 Hz) for `seconds`;
    stamp(channel, t_s, now_us) gives each message's utime. extra_goals: (t_s, [offsets_us]) bursts
    of the same goal, each stamped its offset after the wall clock when the burst starts (not when
    the test starts: the daemon's start-up on a loaded machine would eat into the offsets).
    Returns the statuses received."""
    err_path = str(tmp_path / "gmmrrtd.stderr")
    url = private_url()
    with open(err_path, "w") as err:
        daemon = subprocess.Popen([gmmrrtd, "--lcm-url", url, "--planner", "rrt-star", "--budget-ms", "30",
                                   "--pose-timeout-ms", "1500", "--people-timeout-ms", "1500",
                                   "--log-level", "info"], stderr=err)
    lc = lcm.LCM(url)
    statuses = []
    lc.subscribe("PLANNER_STATUS", lambda ch, data: statuses.append(planner_status_t.decode(data)))
    try:
        assert wait_running(err_path), open(err_path).read()

        def goal(utime):
            g = nav_goal_t()
            g.frame = "map"
            g.goal_id, g.command = 1, nav_goal_t.COMMAND_NEW
            g.utime, g.x, g.y, g.tolerance_m, g.task = utime, 3.0, 0.0, 0.3, nav_goal_t.TASK_NONE
            lc.publish("NAV_GOAL", g.encode())

        if first_goal is not None:
            goal(first_goal)
        t0 = time.monotonic()
        k = 0
        bursts = list(extra_goals)
        while True:
            t = time.monotonic() - t0
            if t >= seconds:
                break
            now = int(time.time() * 1e6)
            p = pose2d_t()
            p.frame = "map"
            p.utime, p.x = stamp("ROBOT_POSE", t, now), 0.0
            lc.publish("ROBOT_POSE", p.encode())
            if k % 2 == 0:
                q = people_t()
                q.frame = "map"
                q.utime = stamp("PEOPLE", t, now)
                q.num_people = 1
                q.people[0].id, q.people[0].x, q.people[0].y = 1, 1.5, 1.2
                lc.publish("PEOPLE", q.encode())
            if k % 4 == 0:
                goal(stamp("NAV_GOAL", t, now))
            if bursts and t >= bursts[0][0]:
                burst_us = int(time.time() * 1e6)
                for offset_us in bursts.pop(0)[1]:
                    goal(burst_us + offset_us)
                    time.sleep(0.13 / 60)
            k += 1
            end = time.monotonic() + 0.05
            while time.monotonic() < end:
                r, _, _ = select.select([lc.fileno()], [], [], max(0.0, end - time.monotonic()))
                if r:
                    lc.handle()
        daemon.send_signal(signal.SIGTERM)
        assert daemon.wait(timeout=10) == 0, open(err_path).read()
    finally:
        if daemon.poll() is None:
            daemon.kill()
            daemon.wait()
    assert len(statuses) >= 10 * seconds * 0.5, "too few statuses: %d" % len(statuses)
    return statuses


def honest(channel, t, now):
    return now


def test_ratchet_live(gmmrrtd, tmp_path):
    """Each re-send 1.9 s later than the one before (the first 1.9 s ahead: within max_future_ms, taken
    as stamped now); the other 59 are refused as from the future and none moves the goal's clock."""
    st = play(gmmrrtd, tmp_path, 4.0, honest, extra_goals=[(1.5, [k * 1_900_000 for k in range(1, 61)])])
    last = st[-1]
    assert last.stops[R.STOP_POSE_STALE] == 0, list(last.stops)
    assert last.rejected[R.REJECT_CLOCK_RESYNC] == 0 and last.rejected[R.REJECT_TIME_FUTURE] >= 55, list(last.rejected)
    assert last.state == R.STATE_PLANNING


def test_far_future_first_goal_live(gmmrrtd, tmp_path):
    st = play(gmmrrtd, tmp_path, 3.0, honest, first_goal=(1 << 53) - 1)
    last = st[-1]
    assert last.stops[R.STOP_POSE_STALE] == 0, list(last.stops)
    assert last.state == R.STATE_PLANNING


@pytest.mark.parametrize("skew_us", [600_000, 1_900_000])
def test_tracker_ahead_live(gmmrrtd, tmp_path, skew_us):
    st = play(gmmrrtd, tmp_path, 3.0, lambda ch, t, now: now + skew_us if ch == "PEOPLE" else now)
    last = st[-1]
    assert sum(last.rejected) == 0, list(last.rejected)
    assert last.stops[R.STOP_POSE_STALE] == 0, list(last.stops)
    assert all(s.stale_inputs == 0 for s in st if s.state != R.STATE_IDLE)
    assert last.state == R.STATE_PLANNING


def test_every_sender_stepped_an_hour_ahead_live(gmmrrtd, tmp_path):
    st = play(gmmrrtd, tmp_path, 5.0, lambda ch, t, now: now + HOUR_US if t >= 1.5 else now)
    last = st[-1]
    assert last.rejected[R.REJECT_CLOCK_RESYNC] == 3, list(last.rejected)  # pose, people, goal: each once
    assert last.rejected[R.REJECT_TIME_FUTURE] > 0
    assert last.state == R.STATE_PLANNING
