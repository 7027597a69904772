#!/usr/bin/env python3
"""The body of `tools/run demo`: the whole product end to end, in a few minutes.

1. learn an avoid and an approach model from the demonstrations in logs/demos/ (gmmrrt-learn fit);
2. start the planner daemon gmmrrtd with them;
3. play a scenario of logs/scenarios/ into it with lcm-logplayer and record its PLAN and
   PLANNER_STATUS messages with lcm-logger, over UDP multicast on a private port with ttl=0 (the
   messages never leave the host); when multicast does not work here, the deterministic file://
   replay instead (gmmrrtd reads the scenario log and writes its plans to a log directly);
4. print a metrics table of the plans (gmmrrt_tools.metrics: length, distances to people, turning,
   the largest turn within 0.1 m, plans turning tighter than the radius, escapes, side switches
   between consecutive plans, the approach's arrival) and the daemon's status counters (stops by
   reason, escapes, tight-turn plans);
5. write a PNG with the demonstrations, the mixtures (density in the person's frame) and the
   planned paths in the scenario.

Nothing is made up: a missing executable, log or message is named and the demo exits non-zero.
Outputs go to out/demo/ (override with --out).
"""
from __future__ import annotations

import argparse
import math
import os
import random
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path
from typing import Dict, List, Optional, Tuple

import numpy as np

ROOT = Path(__file__).resolve().parents[1]

from gmmrrt_tools import metrics as M  # noqa: E402
from gmmrrt_tools import runner as R  # noqa: E402
from gmmrrt_tools.core import STATUS_ESCAPE  # noqa: E402


class DemoError(RuntimeError):
    """A piece the demo needs is missing or failed; the message says which."""


def say(msg: str) -> None:
    print(f"[demo] {msg}", flush=True)


def lcm_tool(name: str) -> str:
    for d in (Path(sys.executable).parent, ROOT / ".venv" / "bin"):
        if (d / name).is_file():
            return str(d / name)
    found = shutil.which(name)
    if not found:
        raise DemoError(f"{name} not found (it comes with the lcm Python package in .venv: run `tools/run setup`)")
    return found


DEFAULT_SCENARIOS = ("avoid_obstacles", "approach_obstacles")


def pick_scenarios(args: Optional[List[str]]) -> List[Path]:
    """The scenario logs to play: those given, else avoid_obstacles and approach_obstacles of
    logs/scenarios/ (one per task), else the first clean one there."""
    if args:
        out = [Path(a) for a in args]
        for p in out:
            if not p.is_file():
                raise DemoError(f"scenario log {p} does not exist")
        return out
    d = ROOT / "logs" / "scenarios"
    logs = sorted(d.glob("*.lcmlog"))
    if not logs:
        raise DemoError(f"no scenario logs in {d}: tools/make_scenarios.py writes them")
    chosen = [d / f"{n}.lcmlog" for n in DEFAULT_SCENARIOS if (d / f"{n}.lcmlog").is_file()]
    if chosen:
        return chosen
    clean = [p for p in logs if "fault" not in p.stem]
    return [(clean or logs)[0]]


# ---------------------------------------------------------------- LCM logs

def read_log(path: Path, channels: Tuple[str, ...]) -> List[Tuple[int, str, object]]:
    """(timestamp, channel, decoded message) of the events on `channels`, in log order."""
    import lcm
    from gmmrrt import nav_goal_t, obstacles_t, people_t, planner_status_t, pose2d_t, waypoints_t

    types = {"ROBOT_POSE": pose2d_t, "PEOPLE": people_t, "NAV_GOAL": nav_goal_t, "OBSTACLES": obstacles_t,
             "PLAN": waypoints_t, "PLANNER_STATUS": planner_status_t}
    out = []
    log = lcm.EventLog(str(path), "r")
    try:
        for ev in log:
            if ev.channel in channels and ev.channel in types:
                try:
                    out.append((ev.timestamp, ev.channel, types[ev.channel].decode(ev.data)))
                except ValueError:
                    pass  # the daemon's replay tests plant undecodable events; they are counted there
    finally:
        log.close()
    return out


def multicast_works(url: str) -> bool:
    """Publishes on `url` and checks that this process hears it back within a second."""
    import lcm

    try:
        lc = lcm.LCM(url)
    except Exception:  # noqa: BLE001 - any failure to open means no multicast here
        return False
    got = []
    sub = lc.subscribe("GMMRRT_DEMO_PING", lambda c, d: got.append(d))
    deadline = time.time() + 1.0
    while time.time() < deadline and not got:
        lc.publish("GMMRRT_DEMO_PING", b"ping")
        lc.handle_timeout(100)
    lc.unsubscribe(sub)
    return bool(got)


# ---------------------------------------------------------------- steps

def learn_models(out: Path, bin_dir: Optional[str], seed: int) -> Dict[str, Path]:
    logs = sorted(str(p) for p in (ROOT / "logs" / "demos").glob("*.lcmlog"))
    if not logs:
        raise DemoError(f"no demonstration logs in {ROOT / 'logs' / 'demos'}: logs/README.md says how they are made")
    models = {}
    for task in ("avoid", "approach"):
        path = out / "models" / f"{task}.gmm"
        say(f"learning the {task} model from {len(logs)} demonstration logs -> {path.relative_to(out.parent.parent) if path.is_relative_to(out.parent.parent) else path}")
        R.fit_model(path, task, logs, homotopy="all", kind="features", seed=seed, bin_dir=bin_dir)
        models[task] = path
    return models


def run_daemon(scenario: Path, models: Dict[str, Path], out: Path, bin_dir: Optional[str], transport: str,
               budget_ms: int, iterations: int, min_turn_radius_m: float) -> Path:
    gmmrrtd = R.find_tool("gmmrrtd", bin_dir)
    rec = out / f"plans_{scenario.stem}.lcmlog"
    if rec.exists():
        rec.unlink()
    common = ["--model-avoid", str(models["avoid"]), "--model-approach", str(models["approach"]),
              "--min-turn-radius", str(min_turn_radius_m)]
    daemon_log = open(out / f"gmmrrtd_{scenario.stem}.log", "w")
    if transport == "file":
        say(f"deterministic replay: gmmrrtd reads {scenario.name} via file:// and writes {rec.name}")
        argv = [gmmrrtd, "--lcm-url", f"file://{scenario}?speed=0", "--lcm-out-url", f"file://{rec}?mode=w",
                "--exit-at-eof", "--budget-iterations", str(iterations), "--budget-ms", "0", *common]
        proc = subprocess.run(argv, stdout=daemon_log, stderr=subprocess.STDOUT, timeout=600)
        daemon_log.close()
        if proc.returncode != 0:
            raise DemoError(f"gmmrrtd exited with {proc.returncode}: see {daemon_log.name}")
        return rec
    port = random.Random(os.getpid()).randint(20000, 60000)
    url = f"udpm://239.255.76.67:{port}?ttl=0"
    say(f"live replay over {url}: gmmrrtd, lcm-logger (PLAN, PLANNER_STATUS), lcm-logplayer {scenario.name}")
    daemon = subprocess.Popen([gmmrrtd, "--lcm-url", url, "--budget-ms", str(budget_ms), *common],
                              stdout=daemon_log, stderr=subprocess.STDOUT)
    logger = subprocess.Popen([lcm_tool("lcm-logger"), f"--lcm-url={url}", "--channel=PLAN|PLANNER_STATUS", "-f",
                               str(rec)], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        time.sleep(1.0)
        if daemon.poll() is not None:
            raise DemoError(f"gmmrrtd exited at start-up with {daemon.returncode}: see {daemon_log.name}")
        play = subprocess.run([lcm_tool("lcm-logplayer"), f"--lcm-url={url}", str(scenario)],
                              capture_output=True, text=True, timeout=600)
        if play.returncode != 0:
            raise DemoError(f"lcm-logplayer failed ({play.returncode}): {play.stderr.strip()[-500:]}")
        time.sleep(1.0)  # the last cycles
    finally:
        for p, sig in ((daemon, signal.SIGTERM), (logger, signal.SIGINT)):
            if p.poll() is None:
                p.send_signal(sig)
                try:
                    p.wait(timeout=5)
                except subprocess.TimeoutExpired:
                    p.kill()
                    p.wait()
        daemon_log.close()
    if daemon.returncode not in (0, -signal.SIGTERM):
        raise DemoError(f"gmmrrtd ended with {daemon.returncode}: see {daemon_log.name}")
    if not rec.is_file():
        raise DemoError("lcm-logger wrote no recording")
    return rec


def analyse(scenario: Path, rec: Path, min_turn_radius_m: float) -> Tuple[dict, List[str], str]:
    """Plans and inputs (for the plot), metrics table rows and a status line, from the scenario and
    the recording; min_turn_radius_m: the daemon's [drive] radius, the bound of the turn columns."""
    inputs = read_log(scenario, ("ROBOT_POSE", "PEOPLE", "NAV_GOAL", "OBSTACLES"))
    outputs = read_log(rec, ("PLAN", "PLANNER_STATUS"))
    plans = [m for _, c, m in outputs if c == "PLAN"]
    statuses = [m for _, c, m in outputs if c == "PLANNER_STATUS"]
    if not statuses and not plans:
        raise DemoError(f"the recording {rec} has no PLAN or PLANNER_STATUS message: the daemon published nothing")
    poses = np.array([[m.x, m.y] for _, c, m in inputs if c == "ROBOT_POSE"]) if inputs else np.zeros((0, 2))
    people_msgs = [m for _, c, m in inputs if c == "PEOPLE"]
    people = {}
    for m in people_msgs:
        for p in m.people[: m.num_people]:
            people[p.id] = (p.x, p.y, p.yaw)
    goals = [m for _, c, m in inputs if c == "NAV_GOAL"]
    obst = [m for _, c, m in inputs if c == "OBSTACLES"]
    circles, boxes = [], []
    if obst:
        o = obst[-1]
        circles = [(o.circle_x[i], o.circle_y[i], o.circle_radius[i]) for i in range(o.num_circles)]
        boxes = [(o.box_x[i], o.box_y[i], o.box_width[i], o.box_height[i], o.box_yaw[i]) for i in range(o.num_boxes)]
    task_name = {1: "avoid", 2: "approach"}
    planner_name = {1: "GMM-RRT*", 2: "RRT*", 3: "GMM-RRT"}
    rows: Dict[str, List[dict]] = {}
    ppl = list(people.values())
    last_side: Dict[str, Dict[int, str]] = {}
    for pl in plans:
        n = pl.num_waypoints
        if n < 2:
            continue
        path = np.column_stack((pl.x[:n], pl.y[:n]))
        key = (f"{scenario.stem}: {task_name.get(pl.task, pl.task)} / "
               f"{planner_name.get(pl.planner, pl.planner)}")
        sm = M.social_metrics(path, ppl)
        sm["collides"] = float(M.path_collides(path, circles=circles, boxes=boxes))
        sm["max_turn_deg"] = math.degrees(M.max_turn_per_step(path, 0.1))
        sm["tight"] = float(M.turns_tighter_than(path, pl.yaw[:n], min_turn_radius_m) > 0)
        # An escape's plan carries GMMRRT_ESCAPE (docs/daemon.md, "Escapes and freezes"); a flagged
        # tight plan carries another status and counts in the column before.
        sm["escape"] = float(pl.status == STATUS_ESCAPE)
        # Sides: the person's side each plan passes (at its closest point), for the people it passes
        # within the personal zone; a plan that passes one on the other side than the previous plan
        # of the row did is a side switch (a robot that hesitates between sides).
        sides = {pid: M.passing_side(path, pose) for pid, pose in people.items()
                 if M.min_distance_to_people(path, [pose]) <= M.PERSONAL_ZONE_M}
        prev = last_side.setdefault(key, {})
        if any(pid in prev and prev[pid] != side for pid, side in sides.items()):
            sm["side_switch"] = 1.0
        elif any(pid in prev for pid in sides):
            sm["side_switch"] = 0.0
        prev.update(sides)
        if pl.task == 2 and goals:
            g = [g for g in goals if g.task == 2]
            tgt = people.get(g[-1].target_person_id) if g else None
            if tgt is not None:
                end = M.approach_end(path, tgt)
                sm["final_dist_m"] = end.final_distance_m
                sm["final_heading_err_deg"] = math.degrees(end.heading_error_rad)
        rows.setdefault(key, []).append(sm)
    lines = []
    for key, sms in sorted(rows.items()):
        cells = [key, str(len(sms))]
        for k, _ in TABLE_COLS[1:]:
            v = [s[k] for s in sms if k in s]
            mean, std = M.mean_std(v)
            if not np.isfinite(mean):
                cells.append("–")
            elif k.startswith("frac") or k in PERCENT_COLS:
                cells.append(f"{100 * mean:.1f}")
            else:
                cells.append(f"{mean:.2f} ± {std:.2f}")
        lines.append("| " + " | ".join(cells) + " |")
    if statuses:
        st = statuses[-1]
        # Reason names come from the message's own REJECT_* constants, so a new reason shows up here.
        reasons = {getattr(type(st), n): n[len("REJECT_"):].lower() for n in dir(type(st)) if n.startswith("REJECT_")}
        rej = ", ".join(f"{reasons.get(i, f'reason_{i}')}={v}" for i, v in enumerate(st.rejected) if v) or "none"
        stops = {getattr(type(st), n): n[len("STOP_"):].lower() for n in dir(type(st)) if n.startswith("STOP_")}
        stp = ", ".join(f"{stops.get(i, f'reason_{i}')}={v}" for i, v in enumerate(st.stops) if v) or "none"
        status = (f"{scenario.stem}: gmmrrtd published {st.plans_published} plans, {st.missed_deadlines} missed "
                  f"deadlines, rejected inputs: {rej}; stops: {stp}; escapes {st.escapes}, plans turning tighter "
                  f"than the radius {st.tight_turn_plans}; last cycle {st.iterations} iterations, "
                  f"{st.plan_time_ms:.1f} ms")
    else:
        status = f"{scenario.stem}: no PLANNER_STATUS recorded"
    data = {"name": scenario.stem, "plans": plans, "people": people, "poses": poses, "goals": goals,
            "circles": circles, "boxes": boxes}
    return data, lines, status


TABLE_COLS = [("plans", "plans"), ("length_m", "length (m)"), ("min_dist_person_m", "min dist. person (m)"),
              ("frac_within_0.45m", "% < 0.45 m"), ("frac_within_1.2m", "% < 1.2 m"),
              ("smoothness_rad", "heading change (rad)"), ("collides", "% colliding"),
              ("final_dist_m", "approach: final dist. (m)"), ("final_heading_err_deg", "approach: heading err. (deg)"),
              ("max_turn_deg", "max turn in 0.1 m (deg)"), ("tight", "% tighter than the radius"),
              ("escape", "% escapes"), ("side_switch", "% side switched")]
# Columns shown as a percentage of the plans (mean of a 0/1 value).
PERCENT_COLS = ("collides", "tight", "escape", "side_switch")


def table_header() -> List[str]:
    return ["| scenario: task / planner | " + " | ".join(c[1] for c in TABLE_COLS) + " |",
            "|---" * (len(TABLE_COLS) + 1) + "|"]


def draw(out_png: Path, datas: List[dict], models: Dict[str, Path]) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.patches as mp
    import matplotlib.pyplot as plt

    from gmmrrt_tools import mixture, scenes

    demos = [scenes.to_person_frame(e) for e in scenes.load_demo_logs(str(ROOT / "logs" / "demos"))]
    fig, axes = plt.subplots(1, 2 + len(datas), figsize=(5.4 * (2 + len(datas)), 5.2))
    colors = {"left": "tab:blue", "right": "tab:orange", "frontal": "tab:green"}
    xs = np.linspace(-5, 5, 161)
    ys = np.linspace(-4, 4, 129)
    for ax, task in zip(axes[:2], ("avoid", "approach")):
        m = mixture.Model(str(models[task]))
        dens = m.density_person_frame(xs, ys)
        ax.imshow(np.log10(np.maximum(dens, 1e-6)), origin="lower", extent=(xs[0], xs[-1], ys[0], ys[-1]),
                  cmap="Greys", alpha=0.8, aspect="equal")
        for e in demos:
            if e.task == task:
                ax.plot(e.xy[:, 0], e.xy[:, 1], color=colors.get(e.homotopy, "k"), lw=0.8, alpha=0.8)
        ax.add_patch(mp.Circle((0, 0), 0.25, fill=False, color="k"))
        ax.arrow(0, 0, 0.5, 0, head_width=0.15, color="k")
        ax.set_title(f"{task}: demonstrations, log10 mixture density\n(person's frame, person faces +x)", fontsize=10)
        from matplotlib.lines import Line2D
        hs = sorted({e.homotopy for e in demos if e.task == task})
        ax.legend(handles=[Line2D([0], [0], color=colors.get(h, "k"), label=h) for h in hs], fontsize=8,
                  loc="lower right")
        ax.set_xlim(xs[0], xs[-1])
        ax.set_ylim(ys[0], ys[-1])
        ax.set_xlabel("x' (m)")
        ax.set_ylabel("y' (m), + = person's left")
    for ax, data in zip(axes[2:], datas):
        _draw_world(ax, data)
    fig.tight_layout()
    fig.savefig(out_png, dpi=100)


def _draw_world(ax, data: dict) -> None:
    import matplotlib.patches as mp

    for (x, y, r) in data["circles"]:
        ax.add_patch(mp.Circle((x, y), r, color="0.6"))
    for (cx, cy, w, h, yaw) in data["boxes"]:
        ax.add_patch(mp.Rectangle((cx - w / 2, cy - h / 2), w, h, angle=math.degrees(yaw), rotation_point="center",
                                  color="0.6"))
    for pid, (x, y, yaw) in data["people"].items():
        ax.add_patch(mp.Circle((x, y), 0.25, fill=False, color="k"))
        ax.arrow(x, y, 0.5 * math.cos(yaw), 0.5 * math.sin(yaw), head_width=0.15, color="k")
    if len(data["poses"]):
        ax.plot(data["poses"][:, 0], data["poses"][:, 1], "k.", ms=2, label="robot poses")
    plans = [p for p in data["plans"] if p.num_waypoints >= 2]
    for i, p in enumerate(plans):
        n = p.num_waypoints
        last = i == len(plans) - 1
        ax.plot(p.x[:n], p.y[:n], color="tab:red", lw=2.0 if last else 0.6, alpha=1.0 if last else 0.35,
                label="last plan" if last else ("plans" if i == 0 else None))
    for g in data["goals"]:
        ax.plot(g.x, g.y, "k*", ms=12)
    ax.set_aspect("equal")
    ax.autoscale()
    ax.grid(alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    ax.set_title(f"{data['name']}: {len(plans)} plans from gmmrrtd\n(world frame)", fontsize=10)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scenario", action="append",
                    help="scenario log to play; repeat for several (default: logs/scenarios/avoid_obstacles and "
                         "approach_obstacles)")
    ap.add_argument("--out", default=str(ROOT / "out" / "demo"), help="output folder (default out/demo)")
    ap.add_argument("--transport", choices=("auto", "udpm", "file"), default="auto",
                    help="udpm: lcm-logplayer/lcm-logger over multicast; file: deterministic file:// replay; "
                         "auto: udpm when multicast works here (default)")
    ap.add_argument("--budget-ms", type=int, default=80, help="daemon planning time per cycle (udpm), ms (default 80)")
    ap.add_argument("--iterations", type=int, default=1500, help="daemon samples per cycle (file replay), default 1500")
    ap.add_argument("--seed", type=int, default=1, help="learner seed (default 1)")
    ap.add_argument("--min-turn-radius", type=float, default=0.3,
                    help="gmmrrtd's minimum turning radius, m, and the bound of the turn columns (default 0.3)")
    ap.add_argument("--bin-dir", default=os.environ.get("GMMRRT_BIN_DIR"), help="folder of the gmmrrt executables")
    args = ap.parse_args(argv)
    if not (math.isfinite(args.min_turn_radius) and args.min_turn_radius >= 0.0):
        ap.error(f"--min-turn-radius must be a finite number >= 0, got {args.min_turn_radius}")
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    try:
        for tool in ("gmmrrt-learn", "gmmrrtd"):
            R.find_tool(tool, args.bin_dir)
        scenarios = pick_scenarios(args.scenario)
        models = learn_models(out, args.bin_dir, args.seed)
        transport = args.transport
        if transport in ("auto", "udpm"):
            lcm_tool("lcm-logger"), lcm_tool("lcm-logplayer")
            probe = f"udpm://239.255.76.67:{random.Random(os.getpid() + 1).randint(20000, 60000)}?ttl=0"
            works = multicast_works(probe)
            if transport == "udpm" and not works:
                raise DemoError("UDP multicast does not work on this host (try --transport file)")
            transport = "udpm" if works else "file"
            if transport == "file":
                say("UDP multicast does not work on this host: using the deterministic file:// replay")
        datas, lines, statuses = [], table_header(), []
        for sc in scenarios:
            rec = run_daemon(sc, models, out, args.bin_dir, transport, args.budget_ms, args.iterations,
                             args.min_turn_radius)
            data, rows, status = analyse(sc, rec, args.min_turn_radius)
            datas.append(data)
            lines += rows
            statuses.append(status)
        table = "\n".join(lines + [""] + statuses)
        print()
        print("Plans of gmmrrtd (mean ± std over the published plans of each scenario):")
        print(table)
        (out / "metrics.md").write_text(
            f"# Demo: gmmrrtd on {', '.join(p.name for p in scenarios)}\n\nMade by `tools/run demo` (transport "
            f"{transport}).\n\n{table}\n")
        draw(out / "demo.png", datas, models)
    except (DemoError, R.MissingTool, R.ToolFailed, ValueError, OSError) as exc:
        print(f"[demo] error: {exc}", file=sys.stderr)
        return 1
    print()
    say(f"outputs in {out}/: demo.png (demonstrations, mixtures, plans), metrics.md, models/avoid.gmm, "
        f"models/approach.gmm, plans_<scenario>.lcmlog (recorded plans), gmmrrtd_<scenario>.log")
    return 0


if __name__ == "__main__":
    sys.exit(main())
