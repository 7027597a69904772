"""planner.settings: gmmrrt-plan, gmmrrtd and the Python tools read the planner settings from one
table, the core's (config_keys.h, through gmmrrt_tools.core.config_keys).

Every setting of the table is listed by both programs' --help under the same flag, is accepted
by both command lines and gmmrrtd's [planner] section under the same names, and a value out of
its range is refused by all three with the same reason, the core's. The docs list every name.
"""
import os
import subprocess
from pathlib import Path

import pytest

from gmmrrt_tools import core, runner

ROOT = Path(__file__).resolve().parents[3]
BIN = Path(os.environ.get("GMMRRT_BIN_DIR", ROOT / "build" / "bin"))
PROBLEM = ["--start", "0,0", "--goal", "1,1"]

# A text each kind of setting refuses: out of range for a number, an unknown name for a choice,
# 2 for a switch (0 or 1; every switch of the table, so a new one needs no entry here).
BAD = {"seed": "-1", "planner": "a-star", "task_cost": "max"}


def run(name, *args, **kw):
    exe = BIN / name
    if not exe.exists():
        pytest.fail(f"{exe} is missing: build the project first (tools/run build)")
    return subprocess.run([str(exe), *args], capture_output=True, text=True, timeout=60, **kw)


def bad_value(key):
    if key.name in BAD:
        return BAD[key.name]
    if key.range == "0 or 1":
        return "2"
    return "-1" if ">" in key.range or "[0" in key.range or "(0" in key.range else "0"


def test_the_binding_reads_the_core_table():
    keys = core.config_keys()
    assert {"gmm_bias", "delta", "task_cost", "robot_radius_m", "planner", "seed", "w_task"} <= set(keys)
    assert keys["gmm_bias"].flag == "--gmm-bias" and keys["gmm_bias"].default == "0.95"
    assert keys["gmm_bias"].range == "in [0, 1]"
    assert keys["task_cost"].choices == ("paper", "inward", "background")
    assert keys["delta"].default == "0"  # 0: the model's delta
    assert core.planner_flags({"delta": 0.001, "informed_sampling": 0}) == ["--delta", "0.001", "--informed", "0"]
    with pytest.raises(KeyError, match="no planner setting 'bias'"):
        core.planner_flags({"bias": 0.5})


def test_runner_builds_flags_from_the_table():
    scene = runner.Scene((0.0, 0.0), (1.0, 1.0), [], (-1.0, -1.0, 2.0, 2.0))
    argv = runner.plan_argv(scene, "rrt-star", 1, bias=0.5, robot_radius_m=0.2, settings={"delta": 0.001})
    joined = " ".join(argv)
    assert "--gmm-bias 0.5" in joined and "--robot-radius 0.2" in joined and "--delta 0.001" in joined


def test_both_programs_list_every_setting_with_its_default():
    plan_help = run("gmmrrt-plan", "--help").stdout
    daemon_help = run("gmmrrtd", "--help").stdout
    for key in core.config_keys().values():
        assert f"{key.flag} V" in plan_help, key.name
        line = next((l for l in daemon_help.splitlines() if f"[planner] {key.name}" in l), None)
        assert line is not None and f"{key.flag} V" in line and f"default {key.default}" in line, key.name


@pytest.mark.parametrize("name", sorted(core.config_keys()))
def test_a_bad_value_is_refused_alike_by_cli_daemon_flag_and_daemon_ini(name, tmp_path):
    key = core.config_keys()[name]
    value = bad_value(key)
    reasons = []
    for how in ("plan", "daemon-flag", "daemon-ini"):
        if how == "plan":
            r = run("gmmrrt-plan", *PROBLEM, key.flag, value)
        elif how == "daemon-flag":
            r = run("gmmrrtd", key.flag, value)
        else:
            ini = tmp_path / "bad.ini"
            ini.write_text(f"[planner]\n{name} = {value}\n")
            r = run("gmmrrtd", "--config", str(ini))
        assert r.returncode in (1, 2) and r.stdout == "", (how, r.stdout, r.stderr)
        msg = r.stderr.strip()
        assert f"config.{name}" in msg, (how, msg)
        reasons.append(msg[msg.index(f"config.{name}"):])
    assert reasons[0] == reasons[1] == reasons[2], reasons


def test_delta_is_a_daemon_setting_too(tmp_path):
    """The paper's cost (delta = 0.001) can be set on the robot: gmmrrtd takes [planner] delta and
    --delta, refusing a bad one before it starts."""
    ini = tmp_path / "delta.ini"
    ini.write_text("[planner]\ndelta = 0.001\ntask_cost = background\n[timing]\nrate_hz = 0\n")
    # Both read (a background cost is a daemon setting too: the model files bring the background);
    # the next rule is reached: the rate.
    r = run("gmmrrtd", "--config", str(ini))
    assert r.returncode == 2 and "rate_hz" in r.stderr and "task_cost" not in r.stderr, r.stderr
    r = run("gmmrrtd", "--delta", "0.001", "--task-cost", "background", "--rate-hz", "0")
    assert r.returncode == 2 and "--rate-hz" in r.stderr and "task_cost" not in r.stderr, r.stderr


def test_switches_take_an_optional_value_on_both_command_lines():
    """--face-target alone is 1, --face-target=0 switches it off (gmmrrtd's [drive] face_target,
    gmmrrt-plan's arrival): both accept 0 and 1 and refuse anything else, naming the flag."""
    r = run("gmmrrtd", "--face-target=maybe")
    assert r.returncode == 2 and "--face-target" in r.stderr, r.stderr
    # Accepted: the next error is another flag's.
    r = run("gmmrrtd", "--face-target=0", "--use-goal-yaw", "--rate-hz", "0")
    assert r.returncode == 2 and "--rate-hz" in r.stderr and "face-target" not in r.stderr, r.stderr
    r = run("gmmrrt-plan", *PROBLEM, "--face-target=maybe")
    assert r.returncode == 1 and "--face-target" in r.stderr, r.stderr


def test_old_cli_spellings_are_refused_with_the_new_name():
    for old, new in (("--bias", "--gmm-bias"), ("--cost", "--task-cost")):
        r = run("gmmrrt-plan", *PROBLEM, old, "0.5")
        assert r.returncode == 1 and f"{old} was renamed {new}" in r.stderr, r.stderr


def test_the_settings_page_names_every_setting():
    page = (ROOT / "docs" / "settings.md").read_text()
    for key in core.config_keys().values():
        assert f"`{key.name}`" in page and f"`{key.flag}`" in page, key.name
