"""What a gmmrrtd cycle spends before planning (set_problem: the collision world, and the warm
start), measured on a cluttered drive: 10 circles and 5 boxes (bench_planner's clutter), four
walking people, the robot driving 12 m at 0.6 m/s towards an avoid goal, OBSTACLES re-sent every
second. The log is made here with gmmrrt_tools.scenario_logs' helpers, replayed deterministically
(log clock, iteration budget) with --log-level debug, and the daemon's "cycle set-up" lines are
summarised. Give several gmmrrtd binaries to compare them (they run interleaved, --repeat times).
Not a test: it prints, asserts nothing (docs/daemon.md, "Cycle set-up").

    eval "$(tools/run env)"; python -m gmmrrt_tools.bench.daemon_setup_cost build/bin/gmmrrtd
"""
import argparse
import math
import os
import re
import statistics
import subprocess
import sys
import tempfile

from gmmrrt_tools import scenario_logs as ms
from gmmrrt_tools.scenario_models import write_models


def make_log(path):
    sc = ms.Scenario("clutter_drive", "clutter drive", 15.0)
    circles = [(1.0 + 1.3 * i, 3.0 * math.sin(i), 0.3 + 0.05 * i) for i in range(10)]
    boxes = [(2.0 + 2.5 * i, -3.5 + 0.5 * i, 1.0, 0.4, 0.3 * i) for i in range(5)]
    walkers = [ms.walker(1, 4.0, 1.5, 0.1, -0.05), ms.walker(2, 8.0, -1.0, -0.1, 0.1),
               ms.walker(3, 10.0, 2.0, 0.0, -0.1), ms.walker(4, 3.0, -2.0, 0.2, 0.0)]
    ms.fill(sc, robot_path=[(0.0, 0.0), (6.0, 1.0), (12.0, 0.0)], robot_speed=0.6,
            persons_at=lambda t: [w(t) for w in walkers], goal_at=lambda t: ms.goal(t, 13.0, 0.0, ms.AVOID),
            obst=lambda t: ms.obstacles(t, circles, boxes))
    sc.write(path)


def run(gmmrrtd, log, out, models, iterations):
    cmd = [gmmrrtd, "--lcm-url", "file://%s?speed=0" % log, "--lcm-out-url", "file://%s?mode=w" % out,
           "--exit-at-eof", "--model-avoid", models["avoid"], "--model-approach", models["approach"],
           "--budget-ms", "0", "--budget-iterations", str(iterations), "--seed", "7", "--robot-radius", "0.3",
           "--person-radius", "0.25", "--log-level", "debug"]
    res = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    if res.returncode != 0:
        sys.exit("%s failed (%d):\n%s" % (gmmrrtd, res.returncode, res.stderr[-2000:]))
    return sorted(float(v) for v in re.findall(r"cycle set-up ([0-9.]+) ms", res.stderr))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("gmmrrtd", nargs="+", help="gmmrrtd binaries to measure")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--iterations", type=int, default=2000, help="planning iterations per cycle")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        log, out = os.path.join(tmp, "clutter.lcmlog"), os.path.join(tmp, "out.lcmlog")
        make_log(log)
        models = write_models(tmp)
        print("%-40s %-4s %-7s %-9s %-9s %-9s %-9s" % ("gmmrrtd", "run", "cycles", "p50 ms", "p90 ms", "max ms",
                                                     "mean ms"))
        for r in range(args.repeat):
            for b in args.gmmrrtd:
                v = run(b, log, out, models, args.iterations)
                if not v:
                    sys.exit("%s logged no 'cycle set-up' lines" % b)
                print("%-40s %-4d %-7d %-9.3f %-9.3f %-9.3f %-9.3f" % (
                    b[-40:], r + 1, len(v), v[len(v) // 2], v[int(0.9 * (len(v) - 1))], v[-1], statistics.mean(v)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
