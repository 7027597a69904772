"""replay.daemon_cli: gmmrrtd's command line, INI file and signals.
--help/--version; bad flags and bad INI lines are errors naming the flag or file:line; flags
override the file; a missing model at start-up is fatal; SIGHUP with a corrupted model file
keeps the old model (planning goes on) and counts REJECT_MODEL_RELOAD; SIGINT exits 0.
"""
import os
import select
import signal
import subprocess
import time

import lcm
from tests.common.daemon_fixture import ROOT, SCENARIOS, venv_bin
from test_replay_udpm import private_url, wait_for_line

from gmmrrt import planner_status_t, waypoints_t


def run(gmmrrtd, *args, timeout=60):
    return subprocess.run([gmmrrtd, *args], capture_output=True, text=True, timeout=timeout)


def test_help_and_version(gmmrrtd):
    res = run(gmmrrtd, "--help")
    assert res.returncode == 0
    for flag in ("--config", "--lcm-url", "--lcm-out-url", "--model-avoid", "--model-approach", "--rate-hz",
                 "--budget-ms", "--robot-radius", "--channel-pose", "--exit-at-eof", "ttl=0"):
        assert flag in res.stdout, flag
    res = run(gmmrrtd, "--version")
    assert res.returncode == 0 and res.stdout.startswith("gmmrrtd ")


def test_bad_flags_are_named(gmmrrtd):
    cases = [(["--no-such-flag"], "--no-such-flag"), (["--rate-hz", "abc"], "--rate-hz"),
             (["--rate-hz", "0"], "--rate-hz"), (["--robot-radius", "nan"], "--robot-radius"),
             (["--planner", "a-star"], "--planner"), (["--rate-hz"], "--rate-hz"), (["stray"], "stray"),
             (["--rate-hz", "20", "--budget-ms", "60"], "budget_ms"), (["--informed", "2"], "--informed"),
             (["--rewire-k", "-1"], "--rewire-k"),
             # Channel names are literals: LCM would read "ROBOT.POSE" as a pattern (ROBOTXPOSE too).
             (["--channel-pose", "ROBOT.POSE"], "[channels] pose"),
             (["--channel-people", "PEOPLE|NAV_GOAL"], "[channels] people"),
             (["--channel-goal", "NAV_GOAL.*"], "regular expressions"),
             # The planning frame follows the messages' frame rule (msg_decode.c): no space, 1..64 bytes.
             (["--frame", "my map"], "[world] frame"), (["--frame", ""], "[world] frame"),
             (["--frame", "m" * 65], "--frame"), (["--goal-fail-after-ms", "-1"], "--goal-fail-after-ms")]
    for args, named in cases:
        res = run(gmmrrtd, *args)
        assert res.returncode == 2, (args, res.returncode, res.stderr)
        assert named in res.stderr, (args, res.stderr)


def test_bad_ini_lines_name_file_and_line(gmmrrtd, tmp_path):
    for body, line in (("[timing]\nrate_hz = 10\n\nbudget_ms = fast\n", 4),
                       ("[lcm]\nurl = udpm://239.255.76.67:7667?ttl=0\n[timing]\nrate = 10\n", 4),
                       ("[planner]\nrobot_radius_m = -1\n", 2),
                       ("[planner]\nseed = 3\ninformed_sampling = yes\n", 3),
                       ("[timing\n", 1)):
        ini = tmp_path / "bad.ini"
        ini.write_text(body)
        res = run(gmmrrtd, "--config", str(ini))
        assert res.returncode == 2, res.stderr
        assert "%s:%d:" % (ini, line) in res.stderr, res.stderr
    res = run(gmmrrtd, "--config", str(tmp_path / "missing.ini"))
    assert res.returncode == 2 and "missing.ini" in res.stderr


def test_flags_override_the_file_and_missing_model_is_fatal(gmmrrtd, models, tmp_path):
    ini = tmp_path / "d.ini"
    ini.write_text("[timing]\nbudget_ms = 500\nbudget_iterations = 200\n[models]\navoid = %s\napproach = %s\n"
                   % (models["avoid"], models["approach"]))
    out = tmp_path / "out.lcmlog"
    common = ["--config", str(ini), "--lcm-url", "file://%s?speed=0" % os.path.join(SCENARIOS, "avoid_one_person.lcmlog"),
              "--lcm-out-url", "file://%s?mode=w" % out, "--exit-at-eof"]
    res = run(gmmrrtd, *common)
    assert res.returncode == 2 and "budget_ms" in res.stderr  # 500 ms does not fit a 100 ms period
    res = run(gmmrrtd, *common, "--budget-ms", "0")
    assert res.returncode == 0, res.stderr
    assert out.stat().st_size > 0
    res = run(gmmrrtd, *common, "--budget-ms", "0", "--model-avoid", str(tmp_path / "nope.gmm"))
    assert res.returncode == 1 and "nope.gmm" in res.stderr


def test_the_shipped_example_ini_is_accepted(gmmrrtd, models, tmp_path):
    """tools/systemd/gmmrrtd.ini is what users copy to /etc: every key in it must parse. Its model
    paths point into /etc, so the flags override them (flags win over the file)."""
    out = tmp_path / "out.lcmlog"
    res = run(gmmrrtd, "--config", os.path.join(ROOT, "tools", "systemd", "gmmrrtd.ini"),
              "--model-avoid", str(models["avoid"]), "--model-approach", str(models["approach"]),
              "--lcm-url", "file://%s?speed=0" % os.path.join(SCENARIOS, "avoid_one_person.lcmlog"),
              "--lcm-out-url", "file://%s?mode=w" % out, "--exit-at-eof")
    assert res.returncode == 0, res.stderr
    assert "error" not in res.stderr and out.stat().st_size > 0


class StatusListener:
    def __init__(self, url):
        self.lc = lcm.LCM(url)
        self.status, self.plans = None, []
        self.lc.subscribe("PLANNER_STATUS", self._on_status)
        self.lc.subscribe("PLAN", lambda c, d: self.plans.append(waypoints_t.decode(d)))

    def _on_status(self, channel, data):
        self.status = planner_status_t.decode(data)

    def pump(self, seconds):
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            r, _, _ = select.select([self.lc.fileno()], [], [], 0.05)
            if r:
                self.lc.handle()


def test_sighup_with_a_bad_model_keeps_the_old_one(gmmrrtd, models, tmp_path):
    url = private_url()
    avoid = tmp_path / "avoid.gmm"
    avoid.write_bytes(open(models["avoid"], "rb").read())
    ini = tmp_path / "d.ini"
    ini.write_text("[lcm]\nurl = %s\n[models]\navoid = %s\n[timing]\nbudget_ms = 50\n" % (url, avoid))
    err_path = tmp_path / "stderr"
    listener = StatusListener(url)
    with open(err_path, "w") as err:
        daemon = subprocess.Popen([gmmrrtd, "--config", str(ini)], stderr=err)
    try:
        assert wait_for_line(str(err_path), "running:"), err_path.read_text()
        listener.pump(0.5)
        assert listener.status is not None, "no PLANNER_STATUS from the daemon"
        assert listener.status.rejected[planner_status_t.REJECT_MODEL_RELOAD] == 0

        avoid.write_bytes(b"GMMRRTMD this is not a model")
        daemon.send_signal(signal.SIGHUP)
        listener.pump(0.8)
        assert daemon.poll() is None, "gmmrrtd died on SIGHUP with a bad model"
        assert listener.status.rejected[planner_status_t.REJECT_MODEL_RELOAD] == 1, err_path.read_text()

        # The old avoid model still plans: a scenario gives non-empty plans, not STOP_NO_MODEL.
        player = subprocess.Popen([venv_bin("lcm-logplayer"), "--lcm-url", url,
                                   os.path.join(SCENARIOS, "avoid_one_person.lcmlog")])
        listener.plans.clear()
        listener.pump(3.0)
        player.wait(timeout=30)
        assert any(p.num_waypoints > 0 for p in listener.plans), [(p.num_waypoints, p.status) for p in listener.plans]

        daemon.send_signal(signal.SIGINT)
        assert daemon.wait(timeout=10) == 0
    finally:
        if daemon.poll() is None:
            daemon.kill()
            daemon.wait()
    assert "old model kept" in err_path.read_text()


def test_file_input_without_output_url_is_refused(gmmrrtd, models):
    res = run(gmmrrtd, "--lcm-url", "file://%s?speed=0" % os.path.join(SCENARIOS, "avoid_one_person.lcmlog"),
              "--model-avoid", models["avoid"])
    assert res.returncode == 2 and "--lcm-out-url" in res.stderr, res.stderr


def test_warm_start_is_used_when_nothing_changes_and_not_across_stops(gmmrrtd, models, tmp_path):
    """Still robot, still person, same goal: nearly every cycle after the first is seeded with the
    last path. The faults scenario stops often (stale pose, bad goals), and a stop forgets the path."""
    import re
    counts = {}
    for sc in ("avoid_one_person", "faults"):
        res = run(gmmrrtd, "--lcm-url", "file://%s?speed=0" % os.path.join(SCENARIOS, sc + ".lcmlog"),
                  "--lcm-out-url", "file://%s?mode=w" % (tmp_path / (sc + ".lcmlog")), "--exit-at-eof",
                  "--model-avoid", models["avoid"], "--model-approach", models["approach"],
                  "--budget-ms", "0", "--budget-iterations", "300")
        assert res.returncode == 0, res.stderr
        m = re.search(r"exiting: (\d+) cycles, (\d+) plans, (\d+) warm starts", res.stderr)
        assert m, res.stderr
        counts[sc] = tuple(int(g) for g in m.groups())
    cycles, _, warm = counts["avoid_one_person"]
    assert warm >= cycles - 2, counts
    cycles, _, warm = counts["faults"]
    assert 0 < warm < cycles - 20, counts


def built_with_systemd():
    cache = os.path.join(os.environ.get("GMMRRT_BUILD_DIR", ""), "CMakeCache.txt")
    return os.path.exists(cache) and "LIBSYSTEMD_FOUND:INTERNAL=1" in open(cache).read()


def test_systemd_notify_ready_watchdog_reloading_stopping(gmmrrtd, models, tmp_path):
    """Type=notify without systemd: a datagram socket in NOTIFY_SOCKET receives what the unit needs
    (or, in a build without libsystemd, nothing at all)."""
    import socket
    path = str(tmp_path / "notify.sock")
    sock = socket.socket(socket.AF_UNIX, socket.SOCK_DGRAM)
    sock.bind(path)
    sock.settimeout(0.2)
    env = dict(os.environ, NOTIFY_SOCKET=path, WATCHDOG_USEC="2000000")
    url = private_url()
    daemon = subprocess.Popen([gmmrrtd, "--lcm-url", url, "--model-avoid", models["avoid"],
                               "--log-level", "warn"], env=env)
    got = []

    def collect(seconds):
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            try:
                got.append(sock.recv(4096).decode())
            except socket.timeout:
                pass

    try:
        collect(1.0)
        # A goal and a pose: each cycle now sets a problem up (the world may be rebuilt), and
        # the watchdog interval is stretched around that step too.
        from gmmrrt import nav_goal_t, pose2d_t
        lc = lcm.LCM(url)
        for _ in range(5):
            now = int(time.time() * 1e6)
            p = pose2d_t()
            p.frame = "map"
            p.utime = now
            lc.publish("ROBOT_POSE", p.encode())
            g = nav_goal_t()
            g.frame = "map"
            g.goal_id, g.command = 1, nav_goal_t.COMMAND_NEW
            g.utime, g.x, g.tolerance_m, g.task = now, 3.0, 0.3, nav_goal_t.TASK_NONE
            lc.publish("NAV_GOAL", g.encode())
            collect(0.1)
        setup_stretches = "\n".join(got).count("WATCHDOG_USEC=30000000")
        daemon.send_signal(signal.SIGHUP)
        collect(0.5)
        daemon.send_signal(signal.SIGTERM)
        assert daemon.wait(timeout=10) == 0
        collect(0.3)
    finally:
        if daemon.poll() is None:
            daemon.kill()
            daemon.wait()
        sock.close()
    text = "\n".join(got)
    if not built_with_systemd():
        assert got == [], "built without libsystemd yet sent notifications: %s" % got[:3]
        return
    assert "READY=1" in got[0], got[:3]
    assert text.count("WATCHDOG=1") >= 5, got  # every cycle at 10 Hz
    assert "RELOADING=1" in text and "STOPPING=1" in got[-1], got[-3:]
    # A set-up or a reload may take long: the watchdog interval is stretched to long_step_ms for
    # it and restored to the unit's after it (WATCHDOG_USEC, systemd >= 236).
    assert setup_stretches >= 2, got
    assert "WATCHDOG_USEC=30000000" in text, got
    assert text.index("WATCHDOG_USEC=2000000") > text.index("WATCHDOG_USEC=30000000"), got
