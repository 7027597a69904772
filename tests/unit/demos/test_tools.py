"""tools/demonstration_stats.py and tools/plot_demonstrations.py on logs/demos and the real data: they run, write what
they say, and fail plainly without the real data. Skipped (with the reason) when the real data is
absent."""
import os
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
REAL = Path(os.environ.get("GMMRRT_REAL_DATA", ""))
need_real = pytest.mark.skipif(not (REAL / "upo_avoid_episodes.csv").is_file(),
                               reason=f"real data not found in {REAL!s}: set GMMRRT_REAL_DATA")


def run(tool, *args, env=None):
    return subprocess.run([sys.executable, str(REPO / "tools" / tool), *map(str, args)], capture_output=True,
                          text=True, cwd=REPO, env=env)


@need_real
def test_demonstration_stats_prints_both_tables():
    r = run("demonstration_stats.py", "--markdown", "--real-data", REAL)
    assert r.returncode == 0, r.stderr
    assert "vs UPO avoid (all, frontal encounters, 122 episodes)" in r.stdout
    rows = [l for l in r.stdout.splitlines() if l.startswith("| min distance to the person [m] | synthetic | 18 |")]
    assert len(rows) == 1
    ks = float(rows[0].rstrip(" |").split("|")[-1])
    assert 0.0 <= ks <= 1.0


@need_real
def test_plot_demonstrations_writes_a_png(tmp_path):
    out = tmp_path / "d.png"
    r = run("plot_demonstrations.py", "--real-data", REAL, "--out", out, "--real-sample", 5)
    assert r.returncode == 0, r.stderr
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_tools_without_real_data_fail_plainly(tmp_path):
    env = dict(os.environ)
    env.pop("GMMRRT_REAL_DATA", None)
    for tool in ("demonstration_stats.py", "plot_demonstrations.py"):
        r = run(tool, "--real-data", tmp_path / "nowhere", env=env)
        assert r.returncode == 1 and "real data folder not found" in r.stderr
