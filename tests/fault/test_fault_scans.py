"""fault.scan_* and fault.grid_malformed: fault-injection replays of gmmrrtd's SCAN and GRID inputs
(docs/world.md), in the floor plan of logs/maps/ with the scan_box traffic (the robot drives the
corridor, ray-cast scans at 5 Hz, a box only the scans show). Each replay (file:// in and out, log
clock, iteration budget) checks with tools/gmmrrt_tools/replay_check.py that the daemon stays up
and exits cleanly (sanitizers in build-asan), keeps its rate, publishes only valid plans, and that
planner_status_t.rejected[] equals exactly the faults planted; then that each fault was logged
and the daemon kept planning on its last good world:

  * a scan flood (12 scans within 11 ms): scan_max_per_cycle are integrated, the rest counted as
    REJECT_COUNT_OVER_BOUND and logged;
  * scans whose every range is NaN for a second: valid, nothing counted as rejected, logged as
    scans without a return; the box they no longer show stays marked (plans still keep the robot
    radius from it: NaN clears nothing);
  * a scan stamped before every robot pose kept: REJECT_TIME_BACKWARDS, logged;
  * malformed grids (a cell out of range, another frame, cut short, a side over the raster): each
    counted by reason, the map stays the world planned in.
"""
import math
import os
import struct

from tests.common.daemon_fixture import ROBOT_RADIUS, ROOT, run_log_clock

from gmmrrt import occupancy_grid_t, planner_status_t, waypoints_t
from gmmrrt_tools import replay_check
from gmmrrt_tools import scenario_logs as ms
from gmmrrt_tools.scan_sim import Caster

R = planner_status_t
MAP_ARGS = ["--map", os.path.join(ROOT, ms.SCAN_MAP), "--bounds-margin", "2"]
CASTER = Caster(os.path.join(ROOT, ms.SCAN_MAP))
SPEED = 0.8


def base(name, duration_s=4.0, box_at=lambda t: [ms.SCAN_BOX], scans_from=0.2, nan_between=None):
    """scan_box traffic; the box there from the start unless box_at says otherwise. Scans in
    [nan_between) have every range NaN."""
    sc = ms.Scenario(name, "fault replay " + name, duration_s)
    ms.fill(sc, ms.SCAN_ROBOT_PATH, SPEED, lambda t: [], lambda t: ms.goal(t, ms.SCAN_GOAL[0], ms.SCAN_GOAL[1], ms.AVOID))
    t = scans_from
    while t <= duration_s + 1e-9:
        taken = t - 0.05
        x, y, yaw = ms.pose_between_samples(ms.SCAN_ROBOT_PATH, SPEED, taken)
        ranges = CASTER.ranges(x, y, yaw, box_at(taken))
        if nan_between and nan_between[0] <= t < nan_between[1]:
            ranges[:] = math.nan
        sc.add(t, "SCAN", CASTER.message(ms.us(taken), ranges))
        t = round(t + 0.2, 6)
    return sc


def replay(gmmrrtd, models, tmp_path, sc, min_plans_frac=0.8):
    in_log, out_log = str(tmp_path / (sc.name + ".lcmlog")), str(tmp_path / "out.lcmlog")
    sc.write(in_log)
    stderr = run_log_clock(gmmrrtd, models, in_log, out_log, iterations=600, extra=MAP_ARGS)
    summary, failures = replay_check.check(in_log, out_log, rate_hz=10.0, robot_radius=ROBOT_RADIUS,
                                           person_radius=0.25,
                                           expected_rejected={replay_check.REASONS[k]: v
                                                              for k, v in sc.expected.items()})
    assert not failures, "\n".join(failures)
    assert summary["plans_nonempty"] >= min_plans_frac * summary["cycles"], summary
    plans = [waypoints_t.decode(d) for _, c, d in replay_check.read_events(out_log) if c == "PLAN"]
    return stderr, plans


def box_clearance(p):
    x0, y0, x1, y1 = ms.SCAN_BOX
    best = math.inf
    pts = list(zip(p.x[:p.num_waypoints], p.y[:p.num_waypoints]))
    for (xa, ya), (xb, yb) in zip(pts, pts[1:]):
        n = max(1, int(math.ceil(math.hypot(xb - xa, yb - ya) / 0.005)))
        for k in range(n + 1):
            x, y = xa + (xb - xa) * k / n, ya + (yb - ya) * k / n
            best = min(best, math.hypot(max(x0 - x, 0.0, x - x1), max(y0 - y, 0.0, y - y1)))
    return best


def planned_after(plans, t_s):
    return [p for p in plans if p.utime >= ms.us(t_s)]


def test_scan_flood(gmmrrtd, models, tmp_path):
    sc = base("scan_flood")
    for k in range(12):  # between the cycles at 1.0 s and 1.1 s, after the regular scan of 1.0 s
        taken = 1.04 + 0.001 * k
        x, y, yaw = ms.pose_between_samples(ms.SCAN_ROBOT_PATH, SPEED, taken)
        sc.add_at(ms.us(1.05) + 1000 * k, "SCAN", CASTER.message(ms.us(taken), CASTER.ranges(x, y, yaw, [ms.SCAN_BOX])))
    sc.expect(R.REJECT_COUNT_OVER_BOUND, 12 + 1 - 4)  # scan_max_per_cycle = 4 a cycle
    stderr, plans = replay(gmmrrtd, models, tmp_path, sc)
    assert "a flood" in stderr, stderr
    after = [p for p in planned_after(plans, 1.1) if p.num_waypoints >= 2]
    assert after and min(box_clearance(p) for p in after) > ROBOT_RADIUS


def test_scans_with_every_range_nan(gmmrrtd, models, tmp_path):
    sc = base("scan_nan", nan_between=(2.0, 3.0))
    stderr, plans = replay(gmmrrtd, models, tmp_path, sc)  # nothing rejected: expected_rejected is empty
    assert "has no return" in stderr, stderr
    blind = [p for p in plans if ms.us(2.0) <= p.utime < ms.us(3.0)]
    assert blind and all(p.num_waypoints >= 2 for p in blind)
    assert min(box_clearance(p) for p in blind) > ROBOT_RADIUS  # the marks stay: NaN clears nothing


def test_scan_stamped_before_every_pose(gmmrrtd, models, tmp_path):
    sc = base("scan_before_poses")
    x, y, yaw = ms.pose_between_samples(ms.SCAN_ROBOT_PATH, SPEED, 0.0)
    sc.add(0.1, "SCAN", CASTER.message(ms.us(-0.5), CASTER.ranges(x, y, yaw, [ms.SCAN_BOX])))
    sc.expect(R.REJECT_TIME_BACKWARDS, 1)
    stderr, plans = replay(gmmrrtd, models, tmp_path, sc)
    assert "stamped before every robot pose" in stderr, stderr
    after = [p for p in planned_after(plans, 0.5) if p.num_waypoints >= 2]
    assert after and min(box_clearance(p) for p in after) > ROBOT_RADIUS


def grid(t_s, cells=None, **kw):
    g = occupancy_grid_t()
    g.utime, g.frame, g.resolution_m, g.origin_x, g.origin_y = ms.us(t_s), "map", 0.1, -6.0, -1.0
    g.width, g.height = 120, 20
    g.num_cells = g.width * g.height
    c = list(cells) if cells is not None else [0] * g.num_cells
    g.data = c + [0] * (occupancy_grid_t.MAX_CELLS - len(c))
    for k, v in kw.items():
        setattr(g, k, v)
    return g.encode()


def test_grid_malformed(gmmrrtd, models, tmp_path):
    sc = base("grid_malformed")
    cells = [0] * 2400
    cells[77] = 101
    sc.add(1.02, "GRID", grid(1.02, cells))                            # a cell out of range
    sc.add(1.22, "GRID", grid(1.22, frame="odom"))                     # not the planning frame
    sc.expect(R.REJECT_WRONG_FRAME, 1)
    sc.add(1.42, "GRID", grid(1.42, num_cells=5))                      # count and sides disagree
    sc.expect(R.REJECT_BAD_VALUE, 2)
    sc.add(1.62, "GRID", grid(1.62)[:4000])                            # cut short
    data = bytearray(grid(1.82))
    data[16:20] = struct.pack(">i", 1 << 30)                           # a frame length past the end
    sc.add(1.82, "GRID", bytes(data))
    sc.expect(R.REJECT_DECODE, 2)
    sc.add(2.02, "GRID", grid(2.02, width=65536, height=1, num_cells=65536, cells=[0] * 65536))  # a side too long
    sc.expect(R.REJECT_COUNT_OVER_BOUND, 1)
    stderr, plans = replay(gmmrrtd, models, tmp_path, sc)
    assert "occupancy_grid_t" in stderr and "grid rejected" in stderr, stderr
    # No grid was taken: the map (and the scans) stay the world, so the plans keep clear of the box.
    after = [p for p in planned_after(plans, 1.0) if p.num_waypoints >= 2]
    assert after and min(box_clearance(p) for p in after) > ROBOT_RADIUS
