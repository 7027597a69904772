"""fault.model_reload and fault.flood_live: gmmrrtd live (UDP multicast on a private port,
ttl=0, live clock) fed by this test at 10 Hz while faults are injected:

  * model_reload: the avoid model file is replaced by garbage, by a truncated copy, by an empty
    file, by a model for the other task and by one with a broken checksum, each followed by
    SIGHUP: every reload is refused and counted (rejected[REJECT_MODEL_RELOAD] + 1), the daemon
    stays up, keeps planning with the old model and keeps its rate; the good file back + SIGHUP
    is taken without a count; SIGINT ends it cleanly.
  * flood_live: 1 kHz poses and 100 obstacle messages per second for 4 s: still a status
    every period (median interval within 15 % of it) and plans throughout.

In the sanitizer pass the daemon is the ASan + LeakSanitizer build: its exit after SIGINT
runs the leak check, and daemon_fixture.assert_clean fails the test on any report.
"""
import math
import os
import select
import signal
import statistics
import subprocess
import time

import lcm
import pytest
from tests.common.daemon_fixture import PERSON_RADIUS, ROBOT_RADIUS, assert_clean, daemon_env

from gmmrrt import nav_goal_t, obstacles_t, people_t, person_t, planner_status_t, pose2d_t, waypoints_t
from gmmrrt_tools.lcm_url import private_url

R = planner_status_t


class Live:
    """Publishes the inputs of a simple avoid scene with the wall clock and records the outputs."""

    def __init__(self, url):
        self.lc = lcm.LCM(url)
        self.statuses, self.plans = [], []
        self.lc.subscribe("PLANNER_STATUS", lambda c, d: self.statuses.append((time.monotonic(), R.decode(d))))
        self.lc.subscribe("PLAN", lambda c, d: self.plans.append((time.monotonic(), waypoints_t.decode(d))))
        self.next_inputs = 0.0

    @staticmethod
    def now_us():
        return int(time.time() * 1e6)

    def pose(self, x=0.0):
        m = pose2d_t()
        m.frame = "map"
        m.utime, m.x, m.y, m.yaw = self.now_us(), x, 0.0, 0.0
        self.lc.publish("ROBOT_POSE", m.encode())

    def obstacles(self, r=0.5):
        m = obstacles_t()
        m.frame = "map"
        m.utime, m.num_circles, m.num_boxes = self.now_us(), 1, 0
        cx, cy, cr = [0.0] * 64, [0.0] * 64, [0.0] * 64
        cx[0], cy[0], cr[0] = 4.0, -1.7, r
        m.circle_x, m.circle_y, m.circle_radius = cx, cy, cr
        m.box_x = m.box_y = m.box_width = m.box_height = m.box_yaw = [0.0] * 64
        self.lc.publish("OBSTACLES", m.encode())

    def regular_inputs(self):
        """Pose, people and goal (every 100 ms)."""
        self.pose()
        pm = people_t()
        pm.frame = "map"
        pm.utime = self.now_us()
        pm.num_people = 1
        p = person_t()
        p.utime, p.id, p.x, p.y, p.yaw = pm.utime, 1, 4.0, 0.1, math.pi
        pm.people[0] = p
        self.lc.publish("PEOPLE", pm.encode())
        g = nav_goal_t()
        g.frame = "map"
        g.goal_id, g.command = 1, nav_goal_t.COMMAND_NEW
        g.utime, g.x, g.y, g.tolerance_m, g.task, g.target_person_id = self.now_us(), 8.0, 0.0, 0.3, 1, -1
        self.lc.publish("NAV_GOAL", g.encode())

    def pump(self, seconds, flood=False):
        """Feeds inputs and handles outputs for `seconds`; with flood, 1 kHz poses and 100 Hz obstacles."""
        end = time.monotonic() + seconds
        next_pose = next_obst = time.monotonic()
        k = 0
        while True:
            now = time.monotonic()
            if now >= end:
                return
            if now >= self.next_inputs:
                self.regular_inputs()
                self.next_inputs = now + 0.1
            if flood:
                while next_pose <= now:
                    self.pose()
                    next_pose += 0.001
                if next_obst <= now:
                    k += 1
                    self.obstacles(0.5 + 0.02 * (k % 2))
                    next_obst += 0.01
            r, _, _ = select.select([self.lc.fileno()], [], [], 0.0005 if flood else 0.01)
            if r:
                self.lc.handle()

    def last_status(self):
        return self.statuses[-1][1] if self.statuses else None


def start(gmmrrtd, url, avoid_path, approach_path, err_path, budget_ms=30):
    ini = os.path.join(os.path.dirname(err_path), "d.ini")
    with open(ini, "w") as f:
        f.write("[lcm]\nurl = %s\n[models]\navoid = %s\napproach = %s\n[timing]\nbudget_ms = %d\n"
                "[planner]\nrobot_radius_m = %g\nperson_radius_m = %g\n" % (url, avoid_path, approach_path, budget_ms,
                                                                         ROBOT_RADIUS, PERSON_RADIUS))
    with open(err_path, "w") as err:
        proc = subprocess.Popen([gmmrrtd, "--config", ini, "--log-level", "info"], stderr=err, env=daemon_env())
    end = time.monotonic() + 20
    while time.monotonic() < end:
        if "running:" in open(err_path).read():
            return proc
        if proc.poll() is not None:
            break
        time.sleep(0.05)
    text = open(err_path).read()
    proc.kill()
    proc.wait()
    pytest.fail("gmmrrtd did not start:\n" + text)


def stop(proc, err_path):
    proc.send_signal(signal.SIGINT)
    try:
        rc = proc.wait(timeout=30)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait()
        pytest.fail("gmmrrtd did not exit on SIGINT")
    assert_clean(rc, open(err_path).read())


def median_interval_s(statuses):
    stamps = [t for t, _ in statuses]
    gaps = [b - a for a, b in zip(stamps, stamps[1:])]
    assert len(gaps) >= 10, "only %d status messages" % len(statuses)
    return statuses and statistics.median(gaps)


def test_model_replaced_by_garbage_then_sighup(gmmrrtd, models, tmp_path):
    good = open(models["avoid"], "rb").read()
    other_task = open(models["approach"], "rb").read()
    avoid = tmp_path / "avoid.gmm"
    avoid.write_bytes(good)
    err_path = str(tmp_path / "stderr")
    url = private_url()
    live = Live(url)
    proc = start(gmmrrtd, url, str(avoid), models["approach"], err_path)
    try:
        live.pump(1.5)
        st = live.last_status()
        assert st is not None, "no PLANNER_STATUS: " + open(err_path).read()
        assert st.state == R.STATE_PLANNING and st.rejected[R.REJECT_MODEL_RELOAD] == 0, (st.state, st.last_error)
        broken_crc = bytearray(good)
        broken_crc[-1] ^= 0x55
        bad_files = [("garbage", bytes((i * 131 + 7) % 256 for i in range(4096))), ("truncated", good[:len(good) // 2]),
                     ("empty", b""), ("other task", other_task), ("broken checksum", bytes(broken_crc))]
        for n, (what, data) in enumerate(bad_files, start=1):
            avoid.write_bytes(data)
            proc.send_signal(signal.SIGHUP)
            live.pump(1.0)
            assert proc.poll() is None, "gmmrrtd died after SIGHUP with a %s model:\n%s" % (what, open(err_path).read())
            st = live.last_status()
            assert st.rejected[R.REJECT_MODEL_RELOAD] == n, (what, list(st.rejected))
            # The old model keeps planning: the last plans are not stops.
            recent = [p for t, p in live.plans if t > time.monotonic() - 0.5]
            assert recent and all(p.num_waypoints > 0 for p in recent), (what, [(p.num_waypoints, p.status)
                                                                             for p in recent])
        avoid.write_bytes(good)
        proc.send_signal(signal.SIGHUP)
        live.pump(1.0)
        assert live.last_status().rejected[R.REJECT_MODEL_RELOAD] == len(bad_files)
        assert live.last_status().state == R.STATE_PLANNING
        med = median_interval_s(live.statuses)
        assert abs(med - 0.1) <= 0.015, "median status interval %.1f ms, promised 100 ms" % (med * 1e3)
    finally:
        if proc.poll() is None:
            stop(proc, err_path)
    assert "old model kept" in open(err_path).read()


def test_flood_of_poses_and_obstacles_live(gmmrrtd, models, tmp_path):
    err_path = str(tmp_path / "stderr")
    url = private_url()
    live = Live(url)
    proc = start(gmmrrtd, url, models["avoid"], models["approach"], err_path)
    try:
        live.pump(1.0)
        n0 = len(live.statuses)
        live.pump(4.0, flood=True)
        flood_statuses = live.statuses[n0:]
        assert proc.poll() is None, open(err_path).read()
        med = median_interval_s(flood_statuses)
        assert abs(med - 0.1) <= 0.015, "median status interval %.1f ms under the flood, promised 100 ms" % (med * 1e3)
        assert len(flood_statuses) >= 30, len(flood_statuses)
        st = live.last_status()
        assert sum(st.rejected) == 0, list(st.rejected)
        planned = [s for _, s in flood_statuses if s.state == R.STATE_PLANNING]
        assert len(planned) >= 0.8 * len(flood_statuses), [(s.state, s.last_error) for _, s in flood_statuses]
    finally:
        if proc.poll() is None:
            stop(proc, err_path)
