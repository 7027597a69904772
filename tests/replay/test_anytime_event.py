"""replay.anytime: anytime publications and event-triggered cycles (docs/daemon.md, "Triggers
and anytime plans").

- Log clock (file:// in and out, iteration budget): with anytime_max_plans = 4 the plans of one
  cycle (those before its PLANNER_STATUS) are at most 4, start from the same pose (utime), carry
  consecutive sequence numbers and never rise in cost; some cycle publishes more than one; two
  runs give identical output (a replay stays deterministic).
- Live clock over udpm (ttl=0): with trigger = event at a 2 Hz tick, every pose sent 150 ms
  apart gets a plan made from it; with trigger = tick the same poses mostly do not (the oracle
  can fail). Counts only, no time is asserted.
"""
import json
import os
import subprocess
import time

import lcm
import daemon_fixture
from daemon_fixture import PERSON_RADIUS, ROBOT_RADIUS, SCENARIOS, assert_clean, daemon_env

from gmmrrt import nav_goal_t, people_t, person_t, pose2d_t, waypoints_t
from gmmrrt_tools.lcm_url import private_url

ANYTIME = ["--anytime-max-plans", "4", "--anytime-improvement", "0.02"]
COLD = ["--warm-robot-offset", "0"]  # every cycle from scratch: its first path is rarely its best


def read_cycles(path):
    """[(plans of the cycle)] in the order published; a cycle ends with its PLANNER_STATUS."""
    cycles, current = [], []
    for e in lcm.EventLog(path, "r"):
        if e.channel == "PLAN":
            current.append(waypoints_t.decode(e.data))
        elif e.channel == "PLANNER_STATUS":
            cycles.append(current)
            current = []
    return cycles


def test_anytime_plans_of_a_cycle_share_the_pose_and_never_rise_in_cost(gmmrrtd, models, tmp_path):
    with open(os.path.join(SCENARIOS, "scenarios.json")) as f:
        log = os.path.join(SCENARIOS, json.load(f)["avoid_crowd"]["log"])
    outs = []
    for run in range(2):
        out = str(tmp_path / ("out%d.lcmlog" % run))
        daemon_fixture.run_log_clock(gmmrrtd, models, log, out, iterations=1500, extra=ANYTIME + COLD)
        outs.append(out)
    cycles = read_cycles(outs[0])
    multi = 0
    for plans in cycles:
        assert len(plans) <= 4
        moving = [p for p in plans if p.num_waypoints > 0]
        if len(moving) > 1:
            multi += 1
        assert len({p.utime for p in plans}) <= 1, "one cycle's plans start from different poses"
        for a, b in zip(plans, plans[1:]):
            assert b.seq == a.seq + 1
            assert b.total_cost <= a.total_cost, "cost rose within a cycle: %g -> %g" % (a.total_cost, b.total_cost)
    assert multi >= len(cycles) // 4, "only %d of %d cycles published better plans" % (multi, len(cycles))
    first = [(e.channel, e.data) for e in lcm.EventLog(outs[0], "r")]
    second = [(e.channel, e.data) for e in lcm.EventLog(outs[1], "r")]
    status_free = lambda evs: [(c, d) for c, d in evs if c == "PLAN"]  # noqa: E731  (status has wall times)
    assert status_free(first) == status_free(second), "two replays differ"


def poses_planned(gmmrrtd, models, tmp_path, trigger, n_poses=20, spacing_s=0.15):
    """Sends a goal and a standing person, then n_poses poses spacing_s apart (a 2 Hz tick);
    returns how many of them a plan names as its start."""
    url = private_url()
    err_path = str(tmp_path / ("gmmrrtd_%s.err" % trigger))
    with open(err_path, "w") as err:
        proc = subprocess.Popen([gmmrrtd, "--lcm-url", url, "--rate-hz", "2", "--budget-ms", "30", "--seed", "7",
                                 "--trigger", trigger, "--min-period-ms", "5", *ANYTIME,
                                 "--robot-radius", str(ROBOT_RADIUS), "--person-radius", str(PERSON_RADIUS),
                                 "--pose-timeout-ms", "2000", "--model-avoid", models["avoid"], "--log-level", "info"],
                                stdout=subprocess.DEVNULL, stderr=err, env=daemon_env())
        try:
            end = time.monotonic() + 15.0
            while time.monotonic() < end and "running:" not in open(err_path).read():
                assert proc.poll() is None, open(err_path).read()
                time.sleep(0.05)
            lc = lcm.LCM(url)
            starts = set()
            lc.subscribe("PLAN", lambda c, d: starts.add(waypoints_t.decode(d).utime))
            sent = []
            for k in range(n_poses + 2):
                utime = int(time.time() * 1e6)
                if k % 5 == 0:
                    g = nav_goal_t()
                    g.frame = "map"
                    g.goal_id, g.command = 1, nav_goal_t.COMMAND_NEW
                    g.utime, g.x, g.y, g.tolerance_m, g.task, g.target_person_id = utime, 6.0, 0.0, 0.3, 1, -1
                    lc.publish("NAV_GOAL", g.encode())
                    ppl = people_t()
                    ppl.frame = "map"
                    q = person_t()
                    q.utime, q.id, q.x, q.y = utime, 1, 3.0, 0.2
                    ppl.utime, ppl.num_people = utime, 1
                    ppl.people = [q] + [person_t() for _ in range(len(ppl.people) - 1)]
                    lc.publish("PEOPLE", ppl.encode())
                p = pose2d_t()
                p.frame = "map"
                p.utime, p.x = utime, 0.01 * k
                lc.publish("ROBOT_POSE", p.encode())
                if k >= 2:  # the first two only set the scene
                    sent.append(utime)
                end = time.monotonic() + spacing_s
                while time.monotonic() < end:
                    lc.handle_timeout(max(1, int((end - time.monotonic()) * 1000)))
            end = time.monotonic() + 0.6
            while time.monotonic() < end:
                lc.handle_timeout(50)
        finally:
            proc.terminate()
            rc = proc.wait(timeout=20)
    assert_clean(rc, open(err_path).read())
    return sum(1 for u in sent if u in starts)


def test_event_trigger_plans_from_every_pose(gmmrrtd, models, tmp_path):
    event = poses_planned(gmmrrtd, models, tmp_path, "event")
    tick = poses_planned(gmmrrtd, models, tmp_path, "tick")
    assert event >= 18, "event trigger: only %d of 20 poses were planned from" % event
    assert tick <= 12, "tick trigger at 2 Hz planned from %d of 20 poses 150 ms apart" % tick
