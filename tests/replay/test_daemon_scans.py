"""replay.daemon_scans: gmmrrtd with a map and laser scans (SCAN, docs/world.md), the scan_box
scenario of logs/scenarios/ replayed deterministically (file:// in and out, log clock, iteration
budget):

  * before the box appears the plans run along the corridor through where it will be;
  * once the scans have shown it (one scan period after it appears), every published plan keeps
    more than the robot's radius from the box's rectangle (its true geometry from the scenario,
    not the planner's raster), along every segment sampled every 5 mm, and plans keep coming
    (the daemon goes round it, it does not stop);
  * without the scans the same replay plans through the box (so the check above can fail);
  * no scan of the scenario is refused: every one is bracketed by poses.
"""
import math
import os

import pytest
from daemon_fixture import ROBOT_RADIUS, ROOT, run_log_clock

from gmmrrt import planner_status_t, waypoints_t
from gmmrrt_tools import replay_check
from gmmrrt_tools import scenario_logs as ms

LOG = os.path.join(ROOT, "logs", "scenarios", "scan_box.lcmlog")
MAP_ARGS = ["--map", os.path.join(ROOT, ms.SCAN_MAP), "--bounds-margin", "2"]


def box_distance(x, y):
    x0, y0, x1, y1 = ms.SCAN_BOX
    return math.hypot(max(x0 - x, 0.0, x - x1), max(y0 - y, 0.0, y - y1))


def min_box_clearance(plan):
    best = math.inf
    pts = list(zip(plan.x[:plan.num_waypoints], plan.y[:plan.num_waypoints]))
    for (xa, ya), (xb, yb) in zip(pts, pts[1:]):
        n = max(1, int(math.ceil(math.hypot(xb - xa, yb - ya) / 0.005)))
        for k in range(n + 1):
            best = min(best, box_distance(xa + (xb - xa) * k / n, ya + (yb - ya) * k / n))
    return best


def plans(out_log):
    """(the pose stamp it was planned from, plan) of every PLAN."""
    out = [waypoints_t.decode(d) for _, c, d in replay_check.read_events(out_log) if c == "PLAN"]
    return [(p.utime, p) for p in out]


@pytest.fixture(scope="module")
def replayed(gmmrrtd, models, tmp_path_factory):
    out = str(tmp_path_factory.mktemp("scans") / "out.lcmlog")
    run_log_clock(gmmrrtd, models, LOG, out, iterations=1000, extra=MAP_ARGS)
    return out


def test_plans_go_round_the_box_the_scans_show(replayed):
    seen_from = ms.us(ms.SCAN_BOX_APPEARS_S + 0.25)  # the first scan after it appeared has arrived
    before = [p for u, p in plans(replayed) if u < ms.us(ms.SCAN_BOX_APPEARS_S) and p.num_waypoints >= 2]
    after = [p for u, p in plans(replayed) if u >= seen_from]
    assert before and after
    # Before: straight along the corridor, through the box's place.
    assert min(min_box_clearance(p) for p in before) < ROBOT_RADIUS
    # After: every plan published, none empty, each keeps the robot's radius from the box.
    assert all(p.num_waypoints >= 2 for p in after), [p.status for p in after if p.num_waypoints < 2]
    worst = min(min_box_clearance(p) for p in after)
    assert worst > ROBOT_RADIUS, "a plan passes %.3f m from the box (robot radius %.2f)" % (worst, ROBOT_RADIUS)


def test_every_scan_was_placed(replayed):
    last = [planner_status_t.decode(d) for _, c, d in replay_check.read_events(replayed) if c == "PLANNER_STATUS"][-1]
    assert list(last.rejected) == [0] * planner_status_t.NUM_REJECT_REASONS, list(last.rejected)
    assert last.stale_inputs == 0


def test_without_scans_the_plans_cross_the_box(gmmrrtd, models, tmp_path):
    out = str(tmp_path / "out.lcmlog")
    run_log_clock(gmmrrtd, models, LOG, out, iterations=1000, extra=[*MAP_ARGS, "--channel-scan", "NO_SCANS"])
    after = [p for u, p in plans(out) if u >= ms.us(ms.SCAN_BOX_APPEARS_S + 0.25) and p.num_waypoints >= 2]
    assert after and min(min_box_clearance(p) for p in after) < ROBOT_RADIUS
