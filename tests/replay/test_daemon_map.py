"""replay.daemon_map: gmmrrtd with a static map ([world] map / --map, docs/world.md).

  * a replay in the floor plan of logs/maps/ from the first room to the second below the
    corridor: the wall between them is in the way, so every plan goes round it through two
    doorways, and every published plan keeps more than the robot's radius from every blocked
    pixel of floor.pgm (read here, by the map_server rules, not through the planner's raster),
    along every segment sampled every 5 mm;
  * without the map the same replay plans straight through the wall (the test can fail);
  * a map larger than the configured raster is refused at start-up with the numbers; a missing
    map is fatal at start-up;
  * SIGHUP after the map file was replaced by garbage keeps the old map (plans still go round
    the wall), counted in REJECT_MODEL_RELOAD and logged with "old map kept".
"""
import os
import signal
import subprocess

import numpy as np

from daemon_fixture import ROBOT_RADIUS, ROOT, run_log_clock, venv_bin
from test_daemon_cli import StatusListener
from test_replay_udpm import private_url, wait_for_line

from gmmrrt import nav_goal_t, planner_status_t
from gmmrrt_tools.replay_check import read_outputs
from gmmrrt_tools.scenario_logs import Scenario, goal, pose

MAP = os.path.join(ROOT, "logs", "maps", "floor.yaml")
PGM = os.path.join(ROOT, "logs", "maps", "floor.pgm")
RES, ORIGIN_X, ORIGIN_Y = 0.05, -11.0, -7.0  # floor.yaml
START, GOAL = (-9.0, -2.5), (0.0, -3.0)      # first and second room below the corridor; wall x = -3
WALL_X = -3.0
MARGIN = ["--bounds-margin", "5"]            # the bounds must reach the corridor (y -1 .. 1)


def blocked_cells():
    """Centres (x, y) of floor.pgm's blocked pixels: map_server trinary, p = (255 - v) / 255,
    occupied above 0.65, free below 0.196, unknown between (blocked, as the daemon's default)."""
    with open(PGM, "rb") as f:
        data = f.read()
    parts = data.split(b"\n", 3)
    assert parts[0] == b"P5"
    header = [line for line in parts[1:3] if not line.startswith(b"#")]
    rest = parts[3]
    if len(header) < 2:  # a comment took a line: the maxval is still to come
        header.append(rest.split(b"\n", 1)[0])
        rest = rest.split(b"\n", 1)[1]
    w, h = (int(v) for v in header[0].split())
    assert int(header[1]) == 255
    img = np.frombuffer(rest[:w * h], dtype=np.uint8).reshape(h, w)
    p = (255.0 - img) / 255.0
    rows, cols = np.nonzero(p >= 0.196)
    x = ORIGIN_X + (cols + 0.5) * RES
    y = ORIGIN_Y + (h - 1 - rows + 0.5) * RES  # the image's top row is the map's last
    return np.stack([x, y], axis=1)


def clearance(points, cells):
    """Distance from each point to the nearest blocked cell (a closed square of side RES)."""
    out = np.empty(len(points))
    for k in range(0, len(points), 256):
        q = points[k:k + 256]
        dx = np.maximum(np.abs(q[:, None, 0] - cells[None, :, 0]) - RES / 2, 0.0)
        dy = np.maximum(np.abs(q[:, None, 1] - cells[None, :, 1]) - RES / 2, 0.0)
        out[k:k + 256] = np.sqrt(dx * dx + dy * dy).min(axis=1)
    return out


def samples(plan, step=0.005):
    pts = []
    for i in range(plan.num_waypoints - 1):
        a = np.array([plan.x[i], plan.y[i]])
        b = np.array([plan.x[i + 1], plan.y[i + 1]])
        n = max(1, int(np.ceil(np.linalg.norm(b - a) / step)))
        t = np.linspace(0.0, 1.0, n + 1)[:, None]
        pts.append(a + t * (b - a))
    return np.concatenate(pts)


def write_scenario(path, seconds=4.0):
    sc = Scenario("map_wall", "a wall of the floor plan between start and goal", seconds)
    for k in range(int(seconds * 10)):
        sc.add(k * 0.1, "ROBOT_POSE", pose(k * 0.1, START[0], START[1], 0.0))
        if k % 10 == 0:
            sc.add(k * 0.1, "NAV_GOAL", goal(k * 0.1, GOAL[0], GOAL[1], nav_goal_t.TASK_NONE))
    sc.write(str(path))


def crosses_wall(plan):
    """True when a segment crosses x = WALL_X below the corridor (through the wall, y < -1.2)."""
    for i in range(plan.num_waypoints - 1):
        x0, y0, x1, y1 = plan.x[i], plan.y[i], plan.x[i + 1], plan.y[i + 1]
        if (x0 - WALL_X) * (x1 - WALL_X) < 0:
            y = y0 + (y1 - y0) * (WALL_X - x0) / (x1 - x0)
            if y < -1.2:
                return True
    return False


def plans_of(out):
    return [plan for _, _, plan in read_outputs(str(out)) if plan is not None and plan.num_waypoints > 1]


def test_plans_go_round_the_map_wall_and_keep_the_robot_radius(gmmrrtd, models, tmp_path):
    log = tmp_path / "map_wall.lcmlog"
    write_scenario(log)
    out = tmp_path / "out.lcmlog"
    err = run_log_clock(gmmrrtd, models, str(log), str(out), iterations=3000, extra=[*MARGIN, "--map", MAP])
    plans = plans_of(out)
    assert len(plans) >= 20, err
    cells = blocked_cells()
    seen = set()
    for plan in plans:
        key = tuple(np.round(plan.x[:plan.num_waypoints], 6)) + tuple(np.round(plan.y[:plan.num_waypoints], 6))
        if key in seen:
            continue
        seen.add(key)
        assert not crosses_wall(plan), list(zip(plan.x[:plan.num_waypoints], plan.y[:plan.num_waypoints]))
        assert max(plan.y[:plan.num_waypoints]) > -1.0, "a plan round the wall passes through the corridor"
        c = clearance(samples(plan), cells)
        assert c.min() > ROBOT_RADIUS, (c.min(), int(c.argmin()))


def test_without_the_map_plans_cross_the_wall(gmmrrtd, models, tmp_path):
    """The check above can fail: with no map the shortest plan runs straight through the wall."""
    log = tmp_path / "map_wall.lcmlog"
    write_scenario(log, seconds=1.0)
    out = tmp_path / "out.lcmlog"
    run_log_clock(gmmrrtd, models, str(log), str(out), iterations=3000, extra=MARGIN)
    plans = plans_of(out)
    assert plans and all(crosses_wall(p) for p in plans)
    assert clearance(samples(plans[-1]), blocked_cells()).min() < ROBOT_RADIUS


def test_a_map_larger_than_the_raster_or_missing_is_refused_at_start_up(gmmrrtd, models, tmp_path):
    res = subprocess.run([gmmrrtd, "--model-avoid", models["avoid"], "--map", MAP, "--map-max-cells", "100000"],
                         capture_output=True, text=True, timeout=30)
    assert res.returncode == 1, res.stderr
    assert "440 x 280 = 123200 cells" in res.stderr and "map_max_cells = 100000" in res.stderr, res.stderr
    res = subprocess.run([gmmrrtd, "--model-avoid", models["avoid"], "--map", MAP, "--map-max-side", "300"],
                         capture_output=True, text=True, timeout=30)
    assert res.returncode == 1 and "map_max_side = 300" in res.stderr and "440" in res.stderr, res.stderr
    missing = str(tmp_path / "nothing.yaml")
    res = subprocess.run([gmmrrtd, "--model-avoid", models["avoid"], "--map", missing],
                         capture_output=True, text=True, timeout=30)
    assert res.returncode == 1 and missing in res.stderr, res.stderr


def test_sighup_with_a_garbage_map_keeps_the_old_one(gmmrrtd, models, tmp_path):
    url = private_url()
    mapdir = tmp_path / "map"
    mapdir.mkdir()
    yaml_path = mapdir / "floor.yaml"
    yaml_path.write_text(open(MAP).read())
    (mapdir / "floor.pgm").write_bytes(open(PGM, "rb").read())
    ini = tmp_path / "d.ini"
    ini.write_text("[lcm]\nurl = %s\n[models]\navoid = %s\n[timing]\nbudget_ms = 0\nbudget_iterations = 3000\n"
                   "[world]\nmap = %s\nbounds_margin_m = 5\n" % (url, models["avoid"], yaml_path))
    log = tmp_path / "map_wall.lcmlog"
    write_scenario(log)
    err_path = tmp_path / "stderr"
    listener = StatusListener(url)
    with open(err_path, "w") as err:
        daemon = subprocess.Popen([gmmrrtd, "--config", str(ini)], stderr=err)
    try:
        assert wait_for_line(str(err_path), "running:"), err_path.read_text()
        listener.pump(0.5)
        assert listener.status is not None, "no PLANNER_STATUS from the daemon"
        assert listener.status.rejected[planner_status_t.REJECT_MODEL_RELOAD] == 0

        yaml_path.write_bytes(b"\x00\xff garbage: [ not: a map\n")
        daemon.send_signal(signal.SIGHUP)
        listener.pump(0.8)
        assert daemon.poll() is None, "gmmrrtd died on SIGHUP with a garbage map"
        assert listener.status.rejected[planner_status_t.REJECT_MODEL_RELOAD] == 1, err_path.read_text()

        player = subprocess.Popen([venv_bin("lcm-logplayer"), "--lcm-url", url, str(log)])
        listener.plans.clear()
        listener.pump(5.0)
        player.wait(timeout=30)
        plans = [p for p in listener.plans if p.num_waypoints > 1]
        assert plans, [(p.num_waypoints, p.status) for p in listener.plans]
        assert not any(crosses_wall(p) for p in plans), "the old map was dropped"

        daemon.send_signal(signal.SIGINT)
        assert daemon.wait(timeout=10) == 0
    finally:
        if daemon.poll() is None:
            daemon.kill()
            daemon.wait()
    text = err_path.read_text()
    assert "old map kept" in text and str(yaml_path) in text, text
