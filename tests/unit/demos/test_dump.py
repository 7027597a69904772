"""demos.dump_py: `gmmrrt-learn dump --json`, the door through which Python gets episodes from the
learner's reader (learner/cli/cmd_dump.cpp over demo_io.cpp). The JSON has the documented shape,
numbers read back to the same doubles, a heading the reader cannot estimate is null, --index gives
each episode its split, and errors and bad usage exit non-zero with the reader's message."""
import json
import os
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
LEARN = Path(os.environ.get("GMMRRT_BIN_DIR", REPO / "build" / "bin")) / "gmmrrt-learn"
HEADER = "episode_id,task,homotopy,t,robot_x,robot_y,person_x,person_y,person_yaw\n"


def dump(*args):
    if not LEARN.is_file():
        pytest.fail(f"{LEARN} is missing: build first (tools/run build)")
    return subprocess.run([str(LEARN), "dump", *map(str, args)], capture_output=True, text=True, timeout=120)


def test_csv_episodes_with_split_and_exact_numbers(tmp_path):
    csv = tmp_path / "e.csv"
    # e1 moves (a heading), e2 stands still (no heading: null).
    csv.write_text(HEADER + "e1,avoid,left,0.0,0.1,0.2,1.0,1.0,0.3\n"
                            "e1,avoid,left,0.5,0.30000000000000004,0.2,1.0,1.0,0.3\n"
                            "e2,approach,frontal,0.0,2.0,2.0,0.0,0.0,0.0\n")
    index = tmp_path / "i.csv"
    index.write_text("episode_id,split\ne1,train\n")
    r = dump("--json", "--index", index, csv)
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    assert out["warnings"] == []
    e1, e2 = out["episodes"]
    assert (e1["id"], e1["task"], e1["homotopy"], e1["split"], e1["source"]) == ("e1", 1, 1, "train", str(csv))
    assert (e2["id"], e2["task"], e2["homotopy"], e2["split"]) == ("e2", 2, 3, "")
    assert e1["robot_x"] == [0.1, 0.30000000000000004] and e1["t"] == [0.0, 0.5]
    assert e1["person_yaw"] == [0.3, 0.3]
    assert all(v is not None for v in e1["robot_yaw"]) and e2["robot_yaw"] == [None]


def test_demonstration_logs_in_order_with_their_labels():
    logs = [REPO / "logs" / "demos" / "avoid_left.lcmlog", REPO / "logs" / "demos" / "approach_frontal.lcmlog"]
    r = dump("--json", *logs)
    assert r.returncode == 0, r.stderr
    eps = json.loads(r.stdout)["episodes"]
    assert [e["id"] for e in eps[:1]] == ["avoid_left_0000"] and eps[-1]["id"].startswith("approach_frontal_")
    assert {(e["task"], e["homotopy"]) for e in eps} == {(1, 1), (2, 3)}
    assert all(len(e[k]) == len(e["t"]) > 0 for e in eps for k in ("robot_x", "person_yaw"))


def test_errors_and_usage():
    r = dump("--json", REPO / "no_such_file.csv")
    assert r.returncode == 1 and "no_such_file.csv: cannot open" in r.stderr and r.stdout == ""
    r = dump(REPO / "logs" / "demos" / "avoid_left.lcmlog")
    assert r.returncode == 2 and "--json" in r.stderr
    r = dump("--json")
    assert r.returncode == 2 and "FILE" in r.stderr
