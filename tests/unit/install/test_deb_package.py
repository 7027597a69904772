"""install.deb: the Debian package CPack makes from this build (what `tools/run package` makes).

- cpack -G DEB builds it (into a temporary folder) without error;
- dpkg-deb: the fields (name, version, architecture, dependencies found by dpkg-shlibdeps,
  conffiles, shlibs, the ldconfig trigger) and the files (daemon, tools, library shared and
  static, headers, pkg-config and CMake files, unit, INI, docs, copyright, changelog);
- lintian reports no error (warnings are printed, not failed: see docs/install.md);
- unpacked into a throwaway root (dpkg -x), the executables run, the unit starts
  /usr/bin/gmmrrtd with /etc/gmmrrt/gmmrrtd.ini, and what its Documentation= names is there.
A missing tool (cpack, dpkg-deb, dpkg-shlibdeps, lintian) is a failure: tools/run setup installs them.
"""
import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
BUILD = Path(os.environ.get("GMMRRT_BUILD_DIR", REPO / "build")).resolve()


def tool(name, package):
    path = shutil.which(name)
    if path is None:
        pytest.fail("%s not found: install the Debian package %s (tools/run setup does)" % (name, package))
    return path


def run(cmd, **kw):
    res = subprocess.run(cmd, capture_output=True, text=True, timeout=600, **kw)
    assert res.returncode == 0, "%s exited %d\n%s\n%s" % (" ".join(map(str, cmd)), res.returncode,
                                                          res.stdout[-4000:], res.stderr[-4000:])
    return res.stdout


@pytest.fixture(scope="module")
def deb(tmp_path_factory):
    config = BUILD / "CPackConfig.cmake"
    if not config.is_file():
        pytest.fail("%s missing: configure the build first (tools/run build)" % config)
    tool("dpkg-shlibdeps", "dpkg-dev")
    out = tmp_path_factory.mktemp("deb")
    run([tool("cpack", "cmake"), "-G", "DEB", "--config", str(config), "-B", str(out)], cwd=str(BUILD))
    debs = sorted(out.glob("gmmrrt_*.deb"))
    assert len(debs) == 1, list(out.iterdir())
    return debs[0]


def field(info, name):
    m = re.search(r"^ %s: (.*)$" % name, info, re.M)
    assert m, "no %s field in:\n%s" % (name, info)
    return m.group(1)


def test_control_fields_and_dependencies(deb):
    info = run([tool("dpkg-deb", "dpkg"), "--info", str(deb)])
    assert field(info, "Package") == "gmmrrt"
    assert field(info, "Architecture") == run(["dpkg", "--print-architecture"]).strip()
    depends = field(info, "Depends")
    for lib in ("libc6", "libfcl", "libglib2.0-0", "libinih1", "libstdc++6", "python3"):
        assert lib in depends, depends
    assert "lcm" not in depends, "LCM is linked statically; Debian's liblcm is too old: %s" % depends
    assert "python3-matplotlib" in field(info, "Recommends")  # gmmrrt-learn plot draws with it
    control = Path(str(deb) + ".control")
    run(["dpkg-deb", "--control", str(deb), str(control)])
    assert (control / "conffiles").read_text().split() == ["/etc/gmmrrt/gmmrrtd.ini"]
    assert (control / "shlibs").read_text().startswith("libgmmrrt 0.1 gmmrrt")
    assert "ldconfig" in (control / "triggers").read_text()


def test_lintian_finds_no_error(deb):
    res = subprocess.run([tool("lintian", "lintian"), "--no-tag-display-limit", str(deb)],
                         capture_output=True, text=True, timeout=600)
    print(res.stdout)
    errors = [line for line in res.stdout.splitlines() if line.startswith("E:")]
    assert not errors, "lintian errors:\n%s" % "\n".join(errors)
    assert res.returncode in (0, 2), res.stderr  # 2: warnings only (lintian's own exit code)


def test_unpacked_into_a_throwaway_root_it_runs_and_is_complete(deb, tmp_path):
    root = tmp_path / "root"
    run(["dpkg", "-x", str(deb), str(root)])
    for f in ("usr/bin/gmmrrtd", "usr/bin/gmmrrt-plan", "usr/bin/gmmrrt-learn", "usr/lib/libgmmrrt.a",
              "usr/lib/libgmmrrt_io.a", "usr/lib/libgmmrrt_lcmtypes_c.a", "usr/lib/gmmrrt/liblcm.a",
              "usr/lib/pkgconfig/gmmrrt.pc", "usr/lib/cmake/gmmrrt/gmmrrtConfig.cmake",
              "usr/lib/cmake/gmmrrt/gmmrrtConfigVersion.cmake", "usr/include/gmmrrt/planner.h",
              "usr/include/gmmrrt/model_file.h", "usr/include/gmmrrt/third_party/lcm/lcm.h",
              "etc/gmmrrt/gmmrrtd.ini", "lib/systemd/system/gmmrrtd.service",
              "usr/share/doc/gmmrrt/copyright", "usr/share/doc/gmmrrt/changelog.gz",
              "usr/share/doc/gmmrrt/install.md", "usr/share/gmmrrt/plot_render.py"):
        assert (root / f).exists(), "the package lacks /%s" % f
    sonames = sorted(p.name for p in (root / "usr" / "lib").glob("libgmmrrt.so*"))
    assert sonames == ["libgmmrrt.so", "libgmmrrt.so.0.1", "libgmmrrt.so.0.1.0"], sonames
    env = {"PATH": "/usr/bin:/bin", "LC_ALL": "C"}
    for exe in ("gmmrrtd", "gmmrrt-plan", "gmmrrt-learn"):
        run([str(root / "usr" / "bin" / exe), "--help"], env=env, cwd=str(tmp_path))
    unit = (root / "lib" / "systemd" / "system" / "gmmrrtd.service").read_text()
    assert re.search(r"^ExecStart=/usr/bin/gmmrrtd --config /etc/gmmrrt/gmmrrtd.ini$", unit, re.M), unit
    doc = re.search(r"^Documentation=file:///(\S+)$", unit, re.M).group(1)
    assert (root / doc).is_file(), doc
    ini = (root / "etc" / "gmmrrt" / "gmmrrtd.ini").read_text()
    assert "avoid = /etc/gmmrrt/models/avoid.gmm" in ini and "approach = /etc/gmmrrt/models/approach.gmm" in ini
