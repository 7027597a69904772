"""replay.daemon_files: files that are not what they claim, and numbers parsed with their type.

  * --config naming a directory, /dev/zero or a FIFO is refused at once (exit 2, the reason
    named), before anything else runs (a directory used to run silently on defaults with no
    models; /dev/zero spun at 100 % CPU; a FIFO blocked);
  * a model path that is a FIFO is refused at start-up, and on SIGHUP it neither blocks the
    daemon (statuses keep coming) nor goes unnoticed (REJECT_MODEL_RELOAD, a line every time,
    also for two failures within log_interval_ms);
  * a model of the wrong feature space (an x-y model with task "avoid" for GMM-RRT*) is refused
    at start-up and on SIGHUP (the good model stays and still plans);
  * [planner] task_cost = background: an avoid model file without a background model is refused
    at start-up, naming the file and the command that fits one; the same model with a background
    (the file's background section) plans a replay; a SIGHUP to the background cost with that
    file refuses the file and the new planner settings, and the old settings go on planning;
  * whole-number settings take digits only: --seed 1e3 and --seed 2.5e1 are errors, not 1 and 2;
  * gmmrrt-plan: --model naming a FIFO fails at once; --w-task 1e308 is refused (it overflowed
    every cost to inf and reported "no path yet").
"""
import os
import signal
import subprocess

from daemon_fixture import SCENARIOS, venv_bin
from test_daemon_cli import StatusListener
from test_replay_udpm import private_url, wait_for_line

from gmmrrt import planner_status_t

from gmmrrt_tools import core
from gmmrrt_tools.replay_check import read_outputs
from gmmrrt_tools.scenario_models import KIND_FEATURES, TASK_AVOID, THETA_IS_ANGLE

R = planner_status_t


def run(exe, *args, timeout=10):
    return subprocess.run([exe, *args], capture_output=True, text=True, timeout=timeout)


def xy_model_bytes(task=1):
    """A valid x-y kind model (D = 3: s, x', y'; docs/model-format.md) with one component, encoded
    by the core (the one writer of the format)."""
    xy_kind = 2  # model.h: GMMRRT_MODEL_KIND_XY
    return core.encode_model(core.model_from_arrays(xy_kind, task, 0, [1.0], [(0.5, 1.0, 0.0)],
                                                    [(0.3, 0.0, 0.3, 0.0, 0.0, 0.3)], 0, 0.001))


def test_config_that_is_not_a_regular_file_is_refused_at_once(gmmrrtd, tmp_path):
    fifo = str(tmp_path / "cfg.fifo")
    os.mkfifo(fifo)
    for path, why in ((str(tmp_path), "is a directory"), ("/dev/zero", "not a regular file"),
                      (fifo, "not a regular file")):
        res = run(gmmrrtd, "--config", path, timeout=10)  # a hang or a spin is a timeout: failure
        assert res.returncode == 2, (path, res.returncode, res.stderr)
        assert path in res.stderr and why in res.stderr, res.stderr


def test_whole_numbers_take_digits_only(gmmrrtd, tmp_path):
    for args in (("--seed", "1e3"), ("--seed", "2.5e1"), ("--seed", "-1"), ("--max-nodes", "1e3"),
                 ("--budget-iterations", "10.0")):
        res = run(gmmrrtd, *args)
        assert res.returncode == 2 and args[0] in res.stderr and "whole number" in res.stderr, (args, res.stderr)
    ini = tmp_path / "seed.ini"
    ini.write_text("[planner]\nseed = 1e3\n")
    res = run(gmmrrtd, "--config", str(ini))
    assert res.returncode == 2 and "%s:2:" % ini in res.stderr, res.stderr


def test_planner_settings_are_checked_by_the_core(gmmrrtd, tmp_path):
    """The [planner] keys' ranges are the core's settings table (config_keys.c), named by key."""
    for args, rule in ((("--robot-radius", "-1"), "config.robot_radius_m"),
                       (("--grid-max-cells", "100000000"), "config.grid_max_cells"),
                       (("--goal-bias", "1"), "config.goal_bias"),
                       (("--max-nodes", "99999999999"), "config.max_nodes must be in 2..4194304")):
        res = run(gmmrrtd, *args)
        assert res.returncode == 2 and args[0] in res.stderr and rule in res.stderr, (args, res.stderr)
    ini = tmp_path / "weights.ini"
    ini.write_text("[planner]\nw_length = 0\nw_task = 0\n")
    res = run(gmmrrtd, "--config", str(ini))
    assert res.returncode == 2 and "must not both be 0" in res.stderr, res.stderr


def test_model_fifo_and_wrong_kind_are_refused_at_start_up(gmmrrtd, tmp_path):
    fifo = str(tmp_path / "m.fifo")
    os.mkfifo(fifo)
    res = run(gmmrrtd, "--lcm-url", private_url(), "--model-avoid", fifo)
    assert res.returncode == 1 and "not a regular file" in res.stderr, res.stderr
    xy = tmp_path / "xy_avoid.gmm"
    xy.write_bytes(xy_model_bytes())
    res = run(gmmrrtd, "--lcm-url", private_url(), "--model-avoid", str(xy))
    assert res.returncode == 1 and "does not fit the gmm-rrt-star planner" in res.stderr, res.stderr
    # The same file is right for the GMM-RRT baseline, which plans in that feature space.
    res = run(gmmrrtd, "--lcm-url", "file://%s?speed=0" % os.path.join(SCENARIOS, "avoid_one_person.lcmlog"),
              "--lcm-out-url", "file://%s?mode=w" % (tmp_path / "out.lcmlog"), "--exit-at-eof",
              "--planner", "gmm-rrt", "--model-avoid", str(xy), "--budget-ms", "0", "--budget-iterations", "50")
    assert res.returncode == 0, res.stderr


def test_sighup_with_a_fifo_or_a_wrong_kind_keeps_the_model_and_says_so_every_time(gmmrrtd, models, tmp_path):
    url = private_url()
    avoid = tmp_path / "avoid.gmm"
    avoid.write_bytes(open(models["avoid"], "rb").read())
    err_path = tmp_path / "stderr"
    listener = StatusListener(url)
    with open(err_path, "w") as err:
        daemon = subprocess.Popen([gmmrrtd, "--lcm-url", url, "--model-avoid", str(avoid), "--budget-ms", "50"],
                                  stderr=err)
    try:
        assert wait_for_line(str(err_path), "running:"), err_path.read_text()
        listener.pump(0.5)
        assert listener.status is not None
        # 1: the model path becomes a FIFO (nobody writes it): the reload must not block.
        os.unlink(avoid)
        os.mkfifo(avoid)
        daemon.send_signal(signal.SIGHUP)
        listener.pump(0.6)
        before = listener.status.utime
        listener.pump(0.5)
        assert daemon.poll() is None and listener.status.utime > before, "no status after SIGHUP: blocked"
        assert listener.status.rejected[R.REJECT_MODEL_RELOAD] == 1, err_path.read_text()
        # 2: within the log interval, an x-y model with task avoid: refused, counted, logged too.
        os.unlink(avoid)
        avoid.write_bytes(xy_model_bytes())
        daemon.send_signal(signal.SIGHUP)
        listener.pump(0.6)
        assert listener.status.rejected[R.REJECT_MODEL_RELOAD] == 2, err_path.read_text()
        # The old (features) model still plans.
        player = subprocess.Popen([venv_bin("lcm-logplayer"), "--lcm-url", url,
                                   os.path.join(SCENARIOS, "avoid_one_person.lcmlog")])
        listener.plans.clear()
        listener.pump(3.0)
        player.wait(timeout=30)
        assert any(p.num_waypoints > 0 for p in listener.plans), [(p.num_waypoints, p.status) for p in listener.plans]
        daemon.send_signal(signal.SIGTERM)
        assert daemon.wait(timeout=10) == 0
    finally:
        if daemon.poll() is None:
            daemon.kill()
            daemon.wait()
    text = err_path.read_text()
    assert "reload rejected (total 1)" in text and "not a regular file" in text, text
    assert "reload rejected (total 2)" in text and "does not fit" in text, text


def test_gmmrrt_plan_model_fifo_and_huge_task_weight(gmmrrtd, tmp_path):
    plan = os.path.join(os.path.dirname(gmmrrtd), "gmmrrt-plan")
    fifo = str(tmp_path / "p.fifo")
    os.mkfifo(fifo)
    res = run(plan, "--start", "0,0", "--goal", "3,0", "--model", fifo, timeout=10)
    assert res.returncode != 0 and "not a regular file" in res.stderr, res.stderr
    res = run(plan, "--start", "0,0", "--goal", "3,0", "--w-task", "1e308")
    assert res.returncode != 0 and "w_task" in res.stderr, res.stderr
    res = run(plan, "--start", "0,0", "--goal", "3,0", "--w-task", "1e6")
    assert res.returncode == 0, res.stderr


def test_goal_flood_writes_a_few_lines_not_one_per_goal(gmmrrtd, models, tmp_path):
    """2000 different goals in one second of log: each is taken (the last one is planned for),
    but the "new goal" line is rate-limited like every other (one per log_interval_ms, then a count
    of the suppressed ones); it used to be written once per goal (55 920 lines in 3 s)."""
    from gmmrrt_tools import scenario_logs as ms
    sc = ms.Scenario("goal_flood", "", 3.0)
    for k in range(31):
        t = k * 0.1
        sc.add(t, "ROBOT_POSE", ms.pose(t, 0.0, 0.0, 0.0))
    for k in range(2000):
        t = 1.0 + k * 0.0005
        sc.add(t, "NAV_GOAL", ms.goal(t, 3.0 + k * 1e-3, 0.0, ms.AVOID))
    in_log, out_log = str(tmp_path / "flood.lcmlog"), str(tmp_path / "out.lcmlog")
    sc.write(in_log)
    res = run(gmmrrtd, "--lcm-url", "file://%s?speed=0" % in_log, "--lcm-out-url", "file://%s?mode=w" % out_log,
              "--exit-at-eof", "--model-avoid", models["avoid"], "--budget-ms", "0", "--budget-iterations", "100",
              timeout=120)
    assert res.returncode == 0, res.stderr
    lines = [l for l in res.stderr.splitlines() if "new goal" in l]
    assert 1 <= len(lines) <= 3, lines[:5]


def test_background_cost_needs_the_model_files_background(gmmrrtd, models, tmp_path):
    res = run(gmmrrtd, "--lcm-url", private_url(), "--task-cost", "background", "--model-avoid", models["avoid"])
    assert res.returncode == 1, res.stderr
    assert models["avoid"] in res.stderr and "gmmrrt-learn fit --background straight" in res.stderr, res.stderr
    # The same task model with a background (walkers on the straight line: theta near 0 and pi).
    model = core.decode_model(open(models["avoid"], "rb").read())
    background = core.model_from_arrays(KIND_FEATURES, TASK_AVOID, 0, [0.5, 0.5], [(1.5, 0.0), (1.5, 3.0)],
                                        [(0.6, 0.0, 0.5), (0.6, 0.0, 0.5)], THETA_IS_ANGLE, 0.001)
    with_bg = tmp_path / "avoid_bg.gmm"
    with_bg.write_bytes(core.encode_model(model, background=background))
    out = tmp_path / "out.lcmlog"
    res = run(gmmrrtd, "--lcm-url", "file://%s?speed=0" % os.path.join(SCENARIOS, "avoid_one_person.lcmlog"),
              "--lcm-out-url", "file://%s?mode=w" % out, "--exit-at-eof", "--task-cost", "background",
              "--model-avoid", str(with_bg), "--budget-ms", "0", "--budget-iterations", "200", "--log-level", "info",
              timeout=120)
    assert res.returncode == 0, res.stderr
    assert "background K = 2" in res.stderr, res.stderr
    plans = [plan for _, _, plan in read_outputs(str(out)) if plan is not None and plan.num_waypoints > 1]
    assert plans, res.stderr


def test_sighup_to_the_background_cost_without_backgrounds_keeps_the_old_settings(gmmrrtd, models, tmp_path):
    """A reload that switches to task_cost = background while the model file has no background:
    the file is refused (old model kept), and so are the new planner settings, which that model
    cannot plan with: the daemon goes on planning with the paper's cost instead of stopping every
    avoid goal with a set-up error."""
    url = private_url()
    ini = tmp_path / "d.ini"
    base = "[lcm]\nurl = %s\n[models]\navoid = %s\n[timing]\nbudget_ms = 50\n" % (url, models["avoid"])
    ini.write_text(base)
    err_path = tmp_path / "stderr"
    listener = StatusListener(url)
    with open(err_path, "w") as err:
        daemon = subprocess.Popen([gmmrrtd, "--config", str(ini)], stderr=err)
    try:
        assert wait_for_line(str(err_path), "running:"), err_path.read_text()
        listener.pump(0.5)
        assert listener.status is not None
        ini.write_text(base + "[planner]\ntask_cost = background\n")
        daemon.send_signal(signal.SIGHUP)
        listener.pump(0.8)
        # The model file (no background) and the planner settings: two rejections.
        assert listener.status.rejected[R.REJECT_MODEL_RELOAD] == 2, err_path.read_text()
        player = subprocess.Popen([venv_bin("lcm-logplayer"), "--lcm-url", url,
                                   os.path.join(SCENARIOS, "avoid_one_person.lcmlog")])
        listener.plans.clear()
        listener.pump(3.0)
        player.wait(timeout=30)
        assert any(p.num_waypoints > 0 for p in listener.plans), [(p.num_waypoints, p.status) for p in listener.plans]
        assert listener.status.rejected[R.REJECT_SETUP] == 0, err_path.read_text()
        daemon.send_signal(signal.SIGTERM)
        assert daemon.wait(timeout=10) == 0
    finally:
        if daemon.poll() is None:
            daemon.kill()
            daemon.wait()
    text = err_path.read_text()
    assert "has no background model" in text and "keeping the old planner settings" in text, text
