"""replay.daemon_scans: gmmrrtd with a map and laser scans (SCAN, docs/world.md), the scan_box
scenario of logs/scenarios/ replayed deterministically (file:// in and out, log clock, iteration
budget):

  * before the box appears the plans run along the corridor through where it will be;
  * once the scans have shown it (one scan period after it appears), every published plan keeps
    more than the robot's radius from the box's rectangle (its true geometry from the scenario,
    not the planner's raster), along every segment sampled every 5 mm, and plans keep coming
    (the daemon goes round it, it does not stop);
  * without the scans the same replay plans through the box (so the check above can fail);
  * no scan of the scenario is refused: every one is bracketed by poses;
  * a local grid (GRID, no map) is planned in: the plans go round a block only the grid holds, and
    once grids stop coming the robot stops (STALE_GRID, counted once).
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
STOP_GRID_STALE = 58  # waypoints_t.status of a stale grid's stop: planner/daemon/stop.h, wire-stable


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


# A local grid (GRID) in place of the map: 13 m x 3 m at 10 cm around the corridor, walls at
# y = +-1, and a block from the lower wall up to y = -0.2 at x 0 .. 0.5 that is in no map.
GRID_BLOCK = (0.0, -1.0, 0.5, -0.2)


def local_grid(t_s):
    from gmmrrt import occupancy_grid_t
    g = occupancy_grid_t()
    g.utime, g.frame, g.resolution_m, g.origin_x, g.origin_y = ms.us(t_s), "map", 0.1, -6.0, -1.5
    g.width, g.height = 130, 30
    g.num_cells = g.width * g.height
    cells = []
    for j in range(g.height):
        for i in range(g.width):
            x, y = g.origin_x + (i + 0.5) * 0.1, g.origin_y + (j + 0.5) * 0.1
            wall = abs(y) > 0.95
            block = GRID_BLOCK[0] <= x <= GRID_BLOCK[2] and GRID_BLOCK[1] <= y <= GRID_BLOCK[3]
            cells.append(100 if wall or block else 0)
    g.data = cells + [0] * (occupancy_grid_t.MAX_CELLS - len(cells))
    return g


def test_a_grid_replaces_the_map_and_a_stale_grid_stops(gmmrrtd, models, tmp_path):
    """Grids at 5 Hz for 3 s, then none: the plans go round the grid's block (above it), which no
    map holds; once the grid is older than grid_timeout_ms (1 s) the robot stops, counted once."""
    sc = ms.Scenario("grid", "a local grid in place of the map", 5.0)
    ms.fill(sc, [(-4.0, 0.0), (-3.0, 0.0)], 0.0, lambda t: [], lambda t: ms.goal(t, 6.0, 0.0, ms.AVOID))
    for k in range(15):
        t = 0.05 + 0.2 * k
        sc.add(t, "GRID", local_grid(t))
    in_log, out = str(tmp_path / "grid.lcmlog"), str(tmp_path / "out.lcmlog")
    sc.write(in_log)
    run_log_clock(gmmrrtd, models, in_log, out, iterations=1000, extra=["--bounds-margin", "2"])
    got = plans(out)
    with_grid = [p for u, p in got if ms.us(0.2) <= u < ms.us(3.5)]
    assert with_grid and all(p.num_waypoints >= 2 for p in with_grid)
    x0, y0, x1, y1 = GRID_BLOCK
    for p in with_grid:
        for x, y in zip(p.x[:p.num_waypoints], p.y[:p.num_waypoints]):
            assert math.hypot(max(x0 - x, 0.0, x - x1), max(y0 - y, 0.0, y - y1)) > ROBOT_RADIUS, (x, y)
    statuses = [planner_status_t.decode(d) for _, c, d in replay_check.read_events(out) if c == "PLANNER_STATUS"]
    last = statuses[-1]
    assert last.stale_inputs & planner_status_t.STALE_GRID
    assert last.rejected[planner_status_t.REJECT_GRID_STALE] == 1
    assert last.stops[planner_status_t.STOP_GRID_STALE] > 0
    stopped = [p for u, p in got if u >= ms.us(4.3)]
    assert stopped and all(p.num_waypoints == 0 and p.status == STOP_GRID_STALE for p in stopped), \
        sorted({(p.num_waypoints, p.status) for p in stopped})
