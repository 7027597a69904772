"""learner.record_demo: tools/record_demo.py turns key presses into DEMO_INFO messages. Published
into a log through LCM's file provider (what lcm-logger would record), the messages decode with the
labels pressed, consecutive episode numbers and the person given; keys that cannot start an episode
publish nothing and say why. The nearest-person rule is checked on its own.
"""
import os
import subprocess
import sys
from pathlib import Path

from gmmrrt_tools.demolog import demo_info_t, scan_structure  # tools/ on PYTHONPATH

REPO = Path(__file__).resolve().parents[3]
sys.path.insert(0, str(REPO / "tools"))
import record_demo  # noqa: E402


def test_keys_become_demo_info_messages(tmp_path):
    log = tmp_path / "labels.lcmlog"
    r = subprocess.run([sys.executable, str(REPO / "tools" / "record_demo.py"), "--lcm-url", f"file://{log}?mode=w",
                        "--person-id", "4", "--first-episode", "7"],
                       input="l\nf\np\nf\nx\nr\nq\nl\n", capture_output=True, text=True, timeout=60,
                       env=dict(os.environ))
    assert r.returncode == 0, r.stderr
    assert "frontal is an approach homotopy" in r.stderr and "unknown key 'x'" in r.stderr
    events = scan_structure(str(log), log.read_bytes())
    assert [ch for _, ch, _ in events] == ["DEMO_INFO"] * 3
    msgs = [demo_info_t.decode(payload) for _, _, payload in events]
    assert [(m.episode, m.task, m.homotopy, m.person_id) for m in msgs] == [(7, 1, 1, 4), (8, 2, 3, 4), (9, 2, 2, 4)]
    assert msgs[0].utime <= msgs[1].utime <= msgs[2].utime and msgs[0].utime > 1.6e15


def test_nearest_person_is_chosen():
    assert record_demo.nearest_person((0.0, 0.0), []) is None
    assert record_demo.nearest_person((1.0, 1.0), [(3, 5.0, 5.0), (8, 1.5, 0.5), (9, -2.0, 1.0)]) == 8
    assert record_demo.nearest_person((0.0, 0.0), [(1, 1.0, 0.0), (2, 0.0, 1.0)]) == 1  # tie: first listed


def test_no_person_known_publishes_nothing(tmp_path):
    rec = record_demo.Recorder(lc=None, task="avoid", person_id=None, first_episode=0)
    assert "no person known" in rec.key("l")
    assert rec.episode == 0
