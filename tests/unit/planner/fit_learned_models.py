#!/usr/bin/env python3
"""CTest fixture planner.learned_fit: fits the models the planner.learned_* tests plan with
(paper Sect. 3: a 19-component GMM over the
features (d, theta) of the demonstrations, Sect. 5.1) from logs/demos/ with the project's own
learner, `gmmrrt-learn fit`:

    avoid_left.gmm, avoid_right.gmm   one homotopy each (logs/demos/avoid_*.lcmlog)
    avoid_all.gmm                     both homotopies (the paper's two-homotopy model, Fig. 5)
    approach_all.gmm                  every approach homotopy (logs/demos/approach_*.lcmlog)

usage: fit_learned_models.py OUT_DIR   (gmmrrt-learn from $GMMRRT_BIN_DIR, else build/bin)
Seeded (--seed 1), so the same logs give the same models. Exit 1 naming what failed.
"""
import os
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[3]
MODELS = [  # file, task, homotopy, logs
    ("avoid_left.gmm", "avoid", "left", ["avoid_left.lcmlog", "avoid_right.lcmlog"]),
    ("avoid_right.gmm", "avoid", "right", ["avoid_left.lcmlog", "avoid_right.lcmlog"]),
    ("avoid_all.gmm", "avoid", "all", ["avoid_left.lcmlog", "avoid_right.lcmlog"]),
    ("approach_all.gmm", "approach", "all",
     ["approach_frontal.lcmlog", "approach_left.lcmlog", "approach_right.lcmlog"]),
]


def main(argv):
    if len(argv) != 2 or argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0 if len(argv) == 2 else 1
    out = Path(argv[1])
    learn = Path(os.environ.get("GMMRRT_BIN_DIR", REPO / "build" / "bin")) / "gmmrrt-learn"
    if not learn.is_file():
        print(f"fit_learned_models: {learn} not found: build the learner (tools/run build)", file=sys.stderr)
        return 1
    out.mkdir(parents=True, exist_ok=True)
    for name, task, hom, logs in MODELS:
        paths = [REPO / "logs" / "demos" / log for log in logs]
        missing = [str(p) for p in paths if not p.is_file()]
        if missing:
            print(f"fit_learned_models: demonstration log(s) missing: {', '.join(missing)}", file=sys.stderr)
            return 1
        argv_ = [str(learn), "fit", "--input", *map(str, paths), "--task", task, "--homotopy", hom,
                 "--kind", "features", "--seed", "1", "--quiet", "-o", str(out / name)]
        proc = subprocess.run(argv_, capture_output=True, text=True)
        if proc.returncode != 0:
            print(f"fit_learned_models: {' '.join(argv_)} failed (exit {proc.returncode}):\n{proc.stderr}",
                  file=sys.stderr)
            return 1
        print(f"wrote {out / name}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
