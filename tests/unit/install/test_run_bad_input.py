"""install.bad_input: `tools/run install` and `tools/run package` refuse bad input with a clear
error before building anything, and leave nothing behind:
- no prefix: the usage line;
- a prefix that cannot be created (under /proc): the error names the prefix and the folder,
  and nothing is created;
- a package build without one of its tools (lintian hidden from PATH): the error names the
  tool and the Debian package that has it; no package is written.
"""
import os
import subprocess
from pathlib import Path

REPO = Path(__file__).resolve().parents[3]
RUN = str(REPO / "tools" / "run")


def run(*args, env=None):
    return subprocess.run([RUN, *args], capture_output=True, text=True, timeout=120, env=env)


def test_install_without_a_prefix_prints_the_usage():
    r = run("install")
    assert r.returncode == 1
    assert "usage: tools/run install PREFIX" in r.stderr


def test_install_into_a_prefix_that_cannot_be_created_fails_and_creates_nothing():
    prefix = "/proc/gmmrrt-install-test/prefix"
    r = run("install", prefix)
    assert r.returncode == 1
    assert "cannot install into %s" % prefix in r.stderr and "/proc" in r.stderr, r.stderr
    assert not os.path.exists("/proc/gmmrrt-install-test")


def test_package_without_lintian_names_the_missing_tool(tmp_path):
    bindir = tmp_path / "bin"
    bindir.mkdir()
    for d in ("/usr/local/bin", "/usr/bin", "/usr/sbin", "/bin", "/sbin"):
        if not os.path.isdir(d):
            continue
        for name in os.listdir(d):
            if name != "lintian" and not (bindir / name).exists():
                os.symlink(os.path.join(d, name), bindir / name)
    env = dict(os.environ, PATH=str(bindir))
    build = Path(os.environ.get("GMMRRT_BUILD_DIR", REPO / "build"))
    before = sorted((build / "package").glob("*.deb")) if (build / "package").is_dir() else []
    r = run("package", env=env)
    assert r.returncode == 1
    assert "needs lintian (Debian package lintian)" in r.stderr, r.stderr
    after = sorted((build / "package").glob("*.deb")) if (build / "package").is_dir() else []
    assert after == before
