"""replay.goal_life: the goal's life (docs/daemon.md, "The goal's life") replayed from
logs/scenarios/goal_life.lcmlog through gmmrrtd (file:// in and out, log clock, iteration budget),
judged from the published PLAN and PLANNER_STATUS alone, cycle by cycle:

  goal 1  accepted and planned; CANCEL at 1.0 s: one empty plan (status 56), then none; a
          re-sent cancel changes nothing; NEW with id 1 at 1.5 s is refused (reused id)
  (1.6 s) an unknown command and (1.7 s) a pose in frame "odom": refused, counted
  goal 2  planned from 2.0 s; replaced at 3.0 s by goal 3 while planning (no end plan for 2)
  goal 3  reached at about 4.2 s on position and heading: one empty plan (status 55)
  goal 4  inside an obstacle from 5.0 s: stops, then FAILED (goal blocked) 3 s later; idle after
"""
import json
import os

from tests.common import daemon_fixture
from tests.common.daemon_fixture import SCENARIOS

from gmmrrt import planner_status_t as R
from gmmrrt_tools import replay_check
from gmmrrt_tools.scenario_logs import T0

STOP_GOAL_REACHED, STOP_GOAL_CANCELLED = 55, 56  # planner/daemon/stop.h, wire-stable
LOG = os.path.join(SCENARIOS, "goal_life.lcmlog")


def cycles_of(gmmrrtd, models, tmp_path):
    out = str(tmp_path / "out.lcmlog")
    daemon_fixture.run_log_clock(gmmrrtd, models, LOG, out, iterations=1000)
    # (time since the scenario's start in s, status, plan or None)
    return [((st.utime - T0) * 1e-6, st, plan) for _, st, plan in replay_check.read_outputs(out)]


def test_each_step_of_the_goals_life(gmmrrtd, models, tmp_path):
    cycles = cycles_of(gmmrrtd, models, tmp_path)
    assert cycles, "no cycles"

    def of(goal_id):
        return [c for c in cycles if c[1].goal_id == goal_id]

    # Goal 1: planned with its remaining length, then cancelled with exactly one empty plan.
    g1 = of(1)
    planning = [c for c in g1 if c[1].goal_state == R.GOAL_PLANNING]
    assert planning and all(c[0] < 1.0 + 0.11 for c in planning), [c[0] for c in planning]
    planned = [c for c in planning if c[2] is not None and c[2].num_waypoints > 0]
    assert planned and all(abs(c[1].remaining_m - c[2].length_m) < 1e-9 for c in planned)
    cancelled = [c for c in g1 if c[1].goal_state == R.GOAL_CANCELLED]
    assert cancelled and 1.0 <= cancelled[0][0] <= 1.11, cancelled[0][0]
    end_plans = [c[2] for c in cancelled if c[2] is not None]
    assert len(end_plans) == 1 and end_plans[0].num_waypoints == 0 and end_plans[0].status == STOP_GOAL_CANCELLED
    assert all(c[1].state == R.STATE_IDLE for c in cancelled)
    assert cancelled[-1][1].stops[R.STOP_GOAL_CANCELLED] == 1

    # Refusals between 1.5 and 1.7 s, each counted once; nothing else refused.
    last = cycles[-1][1]
    assert last.rejected[R.REJECT_GOAL_ID_REUSED] == 1
    assert last.rejected[R.REJECT_UNKNOWN_COMMAND] == 1
    assert last.rejected[R.REJECT_WRONG_FRAME] == 1
    assert last.rejected[R.REJECT_BAD_VALUE] == 0  # the re-sent cancel of a finished goal is not counted

    # Goal 2 plans to (8, 0) until goal 3 replaces it at 3.0 s; it never gets an end plan.
    g2 = of(2)
    assert g2 and all(c[1].goal_state == R.GOAL_PLANNING for c in g2)
    assert 2.0 <= g2[0][0] <= 2.11 and g2[-1][0] <= 3.0 + 1e-9
    assert any(c[2] is not None and c[2].num_waypoints > 0 for c in g2)

    # Goal 3 is reached once, on the pose (1.2 m of 1.5 at 1 m/s from 3 s: 4.2 s), with one empty plan.
    g3 = of(3)
    reached = [c for c in g3 if c[1].goal_state == R.GOAL_REACHED]
    assert reached, [c[1].goal_state for c in g3]
    assert 4.15 <= reached[0][0] <= 4.35, reached[0][0]
    assert reached[0][2] is not None and reached[0][2].num_waypoints == 0
    assert reached[0][2].status == STOP_GOAL_REACHED and reached[0][1].remaining_m == 0.0
    assert all(c[2] is None for c in reached[1:])
    assert all(c[1].goal_state == R.GOAL_ACCEPTED or c[1].goal_state == R.GOAL_PLANNING for c in g3
               if c[0] < reached[0][0])

    # Goal 4: stops (goal in collision) until it fails 3 s (goal_fail_after_ms) after it came; then idle.
    g4 = of(4)
    failed = [c for c in g4 if c[1].goal_state == R.GOAL_FAILED]
    assert failed and 7.95 <= failed[0][0] <= 8.15, failed[0][0] if failed else None
    assert all(c[1].goal_failure == R.FAILURE_GOAL_BLOCKED for c in failed)
    before = [c for c in g4 if c[0] < failed[0][0]]
    assert before and all(c[2] is not None and c[2].num_waypoints == 0 for c in before)
    assert all(c[2] is None for c in failed[1:]) and all(c[1].state == R.STATE_IDLE for c in failed[1:])
    assert last.rejected[R.REJECT_GOAL_IN_COLLISION] == 1


def test_the_scenarios_counters_are_listed(gmmrrtd):
    """scenarios.json carries goal_life's planted refusals (replay.deterministic compares them)."""
    with open(os.path.join(SCENARIOS, "scenarios.json")) as f:
        expected = json.load(f)["goal_life"]["expected_rejected"]
    assert expected == {"REJECT_GOAL_ID_REUSED": 1, "REJECT_GOAL_IN_COLLISION": 1, "REJECT_UNKNOWN_COMMAND": 1,
                        "REJECT_WRONG_FRAME": 1}


def test_each_step_live_over_udpm(gmmrrtd, models):
    """The same life on the live clock (UDP multicast on a private port, ttl=0): the sender's
    messages go in as a task layer sends them, and every transition and refusal shows in
    PLAN and PLANNER_STATUS. No time is asserted; each wait is bounded."""
    import select
    import signal
    import subprocess
    import time

    import lcm
    from gmmrrt import nav_goal_t, planner_status_t, waypoints_t
    from gmmrrt_tools.scenario_logs import cancel, goal, obstacles, people, pose
    from test_replay_udpm import private_url

    url = private_url()
    daemon = subprocess.Popen([gmmrrtd, "--lcm-url", url, "--model-avoid", models["avoid"],
                               "--goal-fail-after-ms", "1000", "--log-level", "error"])
    lc = lcm.LCM(url)
    got = []  # (kind, message) in arrival order
    lc.subscribe("PLAN", lambda c, d: got.append(("plan", waypoints_t.decode(d))))
    lc.subscribe("PLANNER_STATUS", lambda c, d: got.append(("status", planner_status_t.decode(d))))
    robot = [0.0, 0.0]

    def send(ch, m):
        m.utime = int(time.time() * 1e6)
        lc.publish(ch, m.encode())

    def pump(seconds, until=None):
        """Poses at 20 Hz and the world at 2 Hz while handling outputs; stops early once until()."""
        end = time.monotonic() + seconds
        k = 0
        while time.monotonic() < end:
            send("ROBOT_POSE", pose(0, robot[0], robot[1], 0.0))
            if k % 10 == 0:
                send("PEOPLE", people(0, [(1, 4.0, 0.1, 3.1416, 0.0, 0.0)]))
                send("OBSTACLES", obstacles(0, [(6.0, -2.0, 0.5)]))
            k += 1
            t_next = time.monotonic() + 0.05
            while time.monotonic() < t_next:
                r, _, _ = select.select([lc.fileno()], [], [], max(0.0, t_next - time.monotonic()))
                if r:
                    lc.handle()
            if until is not None and until():
                return True
        return False

    def statuses(goal_id, state):
        return [m for k, m in got if k == "status" and m.goal_id == goal_id and m.goal_state == state]

    def last_status():
        return next(m for k, m in reversed(got) if k == "status")

    try:
        pump(0.5)
        send("NAV_GOAL", goal(0, 8.0, 0.0, nav_goal_t.TASK_AVOID, goal_id=11))
        # The cycle's status follows its plan: wait for both (on a loaded machine the plan can be
        # read in one pump round and its status only in the next).
        assert pump(10.0, lambda: any(m.num_waypoints > 0 for k, m in got if k == "plan")
                    and statuses(11, planner_status_t.GOAL_PLANNING)), "goal 11 never planned"
        assert statuses(11, planner_status_t.GOAL_PLANNING)

        mark = len(got)
        send("NAV_GOAL", cancel(0, 11))
        assert pump(5.0, lambda: statuses(11, planner_status_t.GOAL_CANCELLED)), "no cancel"
        pump(0.5)
        after = got[mark:]
        ends = [m for k, m in after if k == "plan" and m.num_waypoints == 0 and m.status == STOP_GOAL_CANCELLED]
        assert len(ends) == 1, [(m.num_waypoints, m.status) for k, m in after if k == "plan"]
        first_cancelled = next(i for i, (k, m) in enumerate(after) if k == "status"
                               and m.goal_state == planner_status_t.GOAL_CANCELLED)
        assert not any(k == "plan" and m.num_waypoints > 0 for k, m in after[first_cancelled:])

        send("NAV_GOAL", goal(0, 8.0, 0.0, nav_goal_t.TASK_AVOID, goal_id=11))  # finished id
        bad = goal(0, 8.0, 0.0, nav_goal_t.TASK_AVOID, goal_id=12)
        bad.command = 7
        send("NAV_GOAL", bad)
        odom = goal(0, 8.0, 0.0, nav_goal_t.TASK_AVOID, goal_id=12)
        odom.frame = "odom"
        send("NAV_GOAL", odom)
        assert pump(3.0, lambda: last_status().rejected[planner_status_t.REJECT_WRONG_FRAME] >= 1)
        st = last_status()
        assert st.rejected[planner_status_t.REJECT_GOAL_ID_REUSED] == 1
        assert st.rejected[planner_status_t.REJECT_UNKNOWN_COMMAND] == 1
        assert st.goal_id == 11 and st.goal_state == planner_status_t.GOAL_CANCELLED  # nothing started

        # A new goal replaced during planning, then one reached by driving there.
        send("NAV_GOAL", goal(0, 8.0, 0.0, nav_goal_t.TASK_AVOID, goal_id=12))
        assert pump(5.0, lambda: statuses(12, planner_status_t.GOAL_PLANNING))
        send("NAV_GOAL", goal(0, 1.5, 0.0, nav_goal_t.TASK_AVOID, goal_id=13, yaw_tol=0.3))
        assert pump(5.0, lambda: statuses(13, planner_status_t.GOAL_PLANNING))
        robot[0] = 1.4
        assert pump(5.0, lambda: statuses(13, planner_status_t.GOAL_REACHED)), "goal 13 not reached"
        assert any(k == "plan" and m.status == STOP_GOAL_REACHED for k, m in got)

        # A goal inside the circle fails after --goal-fail-after-ms with its reason.
        send("NAV_GOAL", goal(0, 6.0, -2.0, nav_goal_t.TASK_AVOID, goal_id=14))
        assert pump(10.0, lambda: statuses(14, planner_status_t.GOAL_FAILED)), "goal 14 did not fail"
        assert statuses(14, planner_status_t.GOAL_FAILED)[0].goal_failure == planner_status_t.FAILURE_GOAL_BLOCKED
        daemon.send_signal(signal.SIGTERM)
        assert daemon.wait(timeout=10) == 0
    finally:
        if daemon.poll() is None:
            daemon.kill()
            daemon.wait()
