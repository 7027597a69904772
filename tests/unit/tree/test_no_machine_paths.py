"""tree.no_machine_paths: no tracked file names a path of the machine it was written on.

Docs, results, code and tests must say `../shared/data/real`, `build/...` or another relative
path: an absolute path of one machine (a home or work folder, this checkout's own location)
is wrong on every other. Checked: every file git tracks (every file under the checkout, less
build trees and the venv, when there is no git), text files only.
"""
import os
import re
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
# Written split so that this file does not match itself.
FORBIDDEN = re.compile("(?<![\\w.~-])/(?:" + "|".join(["wo" + "rk", "ro" + "ot", "ho" + "me", "Us" + "ers"]) +
                       ")/[\\w.-]+")
SKIP_DIRS = {".git", ".venv", "__pycache__", "node_modules"}


def tracked_files():
    try:
        out = subprocess.run(["git", "-C", str(ROOT), "ls-files", "-z"], capture_output=True, check=True).stdout
        return [ROOT / f for f in out.decode().split("\0") if f]
    except (OSError, subprocess.CalledProcessError):
        files = []
        for d, dirs, names in os.walk(ROOT):
            dirs[:] = [x for x in dirs if x not in SKIP_DIRS and not x.startswith("build")]
            files += [Path(d) / n for n in names]
        return files


def test_no_tracked_file_holds_an_absolute_development_path():
    here = str(ROOT)
    offenders = []
    for f in tracked_files():
        if not f.is_file() or f.is_symlink():
            continue
        data = f.read_bytes()
        if b"\0" in data[:8192]:
            continue  # binary (logs, model files, images)
        text = data.decode("utf-8", errors="replace")
        for no, line in enumerate(text.splitlines(), 1):
            m = FORBIDDEN.search(line) or (here in line and re.search(re.escape(here), line))
            if m:
                offenders.append("%s:%d: %s" % (f.relative_to(ROOT), no, m.group(0)))
    assert not offenders, ("absolute paths of a development machine (use ../shared/data/real, build/, "
                           "or another relative path):\n" + "\n".join(offenders[:50]))
