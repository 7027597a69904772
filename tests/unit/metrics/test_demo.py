"""tools/demo.py end to end on the deterministic file:// replay (the multicast path is the default of
`tools/run demo`; it needs a host where UDP multicast works, which CI machines may not have)."""
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]
BIN = Path(os.environ.get("GMMRRT_BIN_DIR", ROOT / "build" / "bin"))


def test_demo_file_replay_writes_metrics_and_plot(tmp_path):
    for tool in ("gmmrrt-learn", "gmmrrtd"):
        if not (BIN / tool).is_file():
            pytest.fail(f"{tool} is not built in {BIN} (a missing build output is a failure)")
    if not list((ROOT / "logs" / "demos").glob("*.lcmlog")) or not (ROOT / "logs" / "scenarios").is_dir():
        pytest.fail("logs/demos or logs/scenarios missing from the checkout")
    out = tmp_path / "demo"
    proc = subprocess.run([sys.executable, str(ROOT / "tools" / "demo.py"), "--transport", "file", "--out", str(out),
                           "--iterations", "600"], capture_output=True, text=True, timeout=900)
    assert proc.returncode == 0, proc.stderr[-3000:] + proc.stdout[-3000:]
    md = (out / "metrics.md").read_text()
    assert "| avoid_obstacles: avoid / GMM-RRT* |" in md
    assert "| approach_obstacles: approach / GMM-RRT* |" in md
    for line in md.splitlines():
        if line.startswith("| avoid_obstacles") or line.startswith("| approach_obstacles"):
            cells = [c.strip() for c in line.strip("|").split("|")]
            assert int(cells[1]) > 0          # plans recorded
            assert cells[7] == "0.0"          # no plan through an obstacle
    assert (out / "demo.png").stat().st_size > 10000
    assert f"outputs in {out}" in proc.stdout


def test_demo_names_a_missing_scenario(tmp_path):
    proc = subprocess.run([sys.executable, str(ROOT / "tools" / "demo.py"), "--scenario", str(tmp_path / "none.lcmlog"),
                           "--out", str(tmp_path / "o")], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 1
    assert "none.lcmlog does not exist" in proc.stderr or "not found" in proc.stderr
