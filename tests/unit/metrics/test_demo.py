"""tools/demo.py end to end on the deterministic file:// replay (the multicast path is the default of
`tools/run demo`; it needs a host where UDP multicast works, which CI machines may not have)."""
import os
import re
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
    header = next(line for line in md.splitlines() if line.startswith("| scenario"))
    cols = [c.strip() for c in header.strip("|").split("|")]
    for name in ("max turn in 0.1 m (deg)", "% tighter than the radius", "% escapes", "% side switched"):
        assert name in cols, cols
    tight_counted = {sc: int(re.search(r"plans turning tighter than the radius (\d+)", line).group(1))
                     for line in md.splitlines() for sc in ("avoid_obstacles", "approach_obstacles")
                     if line.startswith(f"{sc}: gmmrrtd published")}
    assert set(tight_counted) == {"avoid_obstacles", "approach_obstacles"}, md
    for line in md.splitlines():
        if line.startswith("| avoid_obstacles") or line.startswith("| approach_obstacles"):
            cells = [c.strip() for c in line.strip("|").split("|")]
            assert int(cells[1]) > 0          # plans recorded
            assert cells[7] == "0.0"          # no plan through an obstacle
            # The plans the table finds turning tighter than the radius (from their published yaw)
            # are at most those the daemon counted (it also counts turns in place).
            tight = round(float(cells[cols.index("% tighter than the radius")]) * int(cells[1]) / 100.0)
            assert tight <= tight_counted[cells[0].split(":")[0]], line
            assert cells[cols.index("% escapes")] == "0.0"  # nobody steps into the robot in these scenarios
    assert (out / "demo.png").stat().st_size > 10000
    assert f"outputs in {out}" in proc.stdout


def test_demo_names_a_missing_scenario(tmp_path):
    proc = subprocess.run([sys.executable, str(ROOT / "tools" / "demo.py"), "--scenario", str(tmp_path / "none.lcmlog"),
                           "--out", str(tmp_path / "o")], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 1
    assert "none.lcmlog does not exist" in proc.stderr or "not found" in proc.stderr
