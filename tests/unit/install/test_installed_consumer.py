"""install.consumer: an install is usable from anywhere, by programs outside the project.

`cmake --install` of this build into a fresh prefix, which is then moved elsewhere (so nothing
can rely on where it was installed), is used with a clean environment (PATH=/usr/bin:/bin only:
no venv, no PYTHONPATH, no LD_LIBRARY_PATH) from a temporary working directory:
- no installed file names the source tree or the build tree, and every installed executable and
  shared library resolves its libraries outside both (ldd);
- a C program built with `pkg-config --cflags --libs gmmrrt` (shared libgmmrrt) and the same
  program linked statically with `pkg-config --static` each load a model and plan one path;
- a CMake project using find_package(gmmrrt CONFIG REQUIRED) with gmmrrt::io, gmmrrt::gmmrrt and
  gmmrrt::lcmtypes does the same and round-trips a message;
- the installed gmmrrtd runs a short file:// replay to its end and exits 0, once with flags and
  once with the installed INI (models put where that INI and the installed unit say);
- the installed gmmrrt-learn goes from a raw recording to a picture of a model: `segment` cuts an
  unlabelled log into a labelled episode CSV, `fit --homotopy all` learns from it, and `plot`
  draws it with the system's python3 and Debian's matplotlib (no venv on PATH).
The test's own Python (the venv) only drives these steps and writes the model files.
"""
import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
BUILD = Path(os.environ.get("GMMRRT_BUILD_DIR", REPO / "build")).resolve()
CONSUMER = REPO / "tests" / "unit" / "install" / "consumer"
SCENARIO = REPO / "logs" / "scenarios" / "avoid_one_person.lcmlog"


def run(cmd, env, cwd, timeout=300):
    res = subprocess.run(cmd, env=env, cwd=cwd, capture_output=True, text=True, timeout=timeout)
    assert res.returncode == 0, "%s exited %d\nstdout:\n%s\nstderr:\n%s" % (
        " ".join(map(str, cmd)), res.returncode, res.stdout[-3000:], res.stderr[-3000:])
    return res.stdout


@pytest.fixture(scope="module")
def prefix(tmp_path_factory):
    """A fresh install, moved away from where it was installed; returns (prefix, clean env, work dir)."""
    if not (BUILD / "CMakeCache.txt").is_file():
        pytest.fail("no configured build at %s (tools/run build)" % BUILD)
    top = tmp_path_factory.mktemp("installed")
    first = top / "first" / "prefix"
    res = subprocess.run(["cmake", "--install", str(BUILD), "--prefix", str(first)],
                         capture_output=True, text=True, timeout=300)
    assert res.returncode == 0, res.stderr
    moved = top / "moved" / "gmmrrt"
    moved.parent.mkdir()
    shutil.move(str(first), str(moved))
    shutil.rmtree(top / "first")
    work = top / "work"
    work.mkdir()
    env = {"PATH": "/usr/bin:/bin", "HOME": str(work), "LC_ALL": "C",
           "PKG_CONFIG_PATH": str(moved / "lib" / "pkgconfig")}
    return moved, env, work


@pytest.fixture(scope="module")
def models(prefix):
    from gmmrrt_tools.scenario_models import write_models
    return write_models(str(prefix[2] / "models"))


def test_nothing_installed_points_into_the_build_or_source_tree(prefix):
    p, env, work = prefix
    needles = [str(REPO).encode(), str(BUILD).encode()]
    offenders = [str(f.relative_to(p)) for f in p.rglob("*") if f.is_file() and not f.is_symlink()
                 and any(n in f.read_bytes() for n in needles)]
    assert not offenders, "installed files that name the checkout or the build: %s" % offenders
    binaries = [p / "bin" / e for e in ("gmmrrtd", "gmmrrt-plan", "gmmrrt-learn")] + list((p / "lib").glob("libgmmrrt.so*"))
    for b in binaries:
        out = run(["ldd", str(b)], env, work)
        assert "not found" not in out, "%s: %s" % (b, out)
        assert str(REPO) not in out and str(BUILD) not in out, "%s resolves into the checkout:\n%s" % (b, out)
    for exe in ("gmmrrtd", "gmmrrt-plan", "gmmrrt-learn"):
        run([str(p / "bin" / exe), "--help"], env, work)


def test_c_program_with_pkg_config_loads_a_model_and_plans(prefix, models):
    p, env, work = prefix
    cflags = run(["pkg-config", "--cflags", "gmmrrt"], env, work).split()
    libs = run(["pkg-config", "--libs", "gmmrrt"], env, work).split()
    assert not any(f.startswith("-std=") for f in cflags), "C++ flags leak into C compiles: %s" % cflags
    libdir = run(["pkg-config", "--variable=libdir", "gmmrrt"], env, work).strip()
    assert os.path.realpath(libdir) == str((p / "lib").resolve()), "pkg-config prefix is not the install's: %s" % libdir
    exe = work / "plan_pc"
    run(["cc", "-std=c11", "-Wall", "-Werror", "-o", str(exe), str(CONSUMER / "plan_one.c"), *cflags, *libs,
         "-Wl,-rpath," + libdir], env, work)
    assert "path " in run([str(exe), models["avoid"]], env, work)
    assert "libgmmrrt.so" in run(["ldd", str(exe)], env, work)

    # Static: the archives, plus everything Libs.private names (FCL, the C++ runtime).
    static = run(["pkg-config", "--static", "--libs", "gmmrrt"], env, work)
    static = re.sub(r"-lgmmrrt_io -lgmmrrt\b", "-Wl,-Bstatic -lgmmrrt_io -lgmmrrt -Wl,-Bdynamic", static).split()
    exe = work / "plan_pc_static"
    run(["cc", "-std=c11", "-Wall", "-Werror", "-o", str(exe), str(CONSUMER / "plan_one.c"), *cflags, *static],
        env, work)
    assert "path " in run([str(exe), models["avoid"]], env, work)
    assert "libgmmrrt" not in run(["ldd", str(exe)], env, work)


def test_cmake_project_with_find_package_loads_a_model_and_plans(prefix, models):
    p, env, work = prefix
    src = work / "consumer-src"
    shutil.copytree(CONSUMER, src)
    build = work / "consumer-build"
    run(["cmake", "-S", str(src), "-B", str(build), "-DCMAKE_PREFIX_PATH=" + str(p)], env, work)
    run(["cmake", "--build", str(build)], env, work)
    out = run([str(build / "plan_one"), models["avoid"]], env, work)
    assert "path " in out and "lcmtypes: waypoints message round-trips" in out, out
    config = (p / "lib" / "cmake" / "gmmrrt")
    assert (config / "gmmrrtConfigVersion.cmake").is_file()


def test_installed_daemon_replays_a_log_and_exits_0(prefix, models):
    p, env, work = prefix
    log = work / "in.lcmlog"
    shutil.copy(SCENARIO, log)
    out = work / "out.lcmlog"
    run([str(p / "bin" / "gmmrrtd"), "--lcm-url", "file://%s?speed=0" % log, "--lcm-out-url",
         "file://%s?mode=w" % out, "--exit-at-eof", "--model-avoid", models["avoid"], "--model-approach",
         models["approach"], "--budget-ms", "0", "--budget-iterations", "100", "--log-level", "warn"], env, work)
    assert out.stat().st_size > 0, "the replay published nothing"


def test_installed_unit_and_ini_point_at_the_prefix(prefix, models):
    p, env, work = prefix
    unit = (p / "lib" / "systemd" / "system" / "gmmrrtd.service").read_text()
    exec_start = re.search(r"^ExecStart=(\S+) --config (\S+)$", unit, re.M)
    assert exec_start, unit
    # Paths are the install-time prefix (before the move): the same tail under the moved prefix.
    daemon, ini = (Path(x) for x in exec_start.groups())
    assert daemon.name == "gmmrrtd" and (p / daemon.relative_to(daemon.parents[1])).is_file()
    installed_prefix = daemon.parents[1]
    ini_here = p / ini.relative_to(installed_prefix)
    assert ini_here.is_file(), ini
    doc = re.search(r"^Documentation=file://(\S+)$", unit, re.M).group(1)
    assert (p / Path(doc).relative_to(installed_prefix)).is_file(), doc
    text = ini_here.read_text()
    for task in ("avoid", "approach"):
        m = re.search(r"^%s = (\S+)$" % task, text, re.M)
        assert m and m.group(1) == str(installed_prefix / "etc" / "gmmrrt" / "models" / (task + ".gmm")), text
    # The installed INI, with its model paths moved along with the prefix, runs a replay.
    (p / "etc" / "gmmrrt" / "models").mkdir(exist_ok=True)
    for task in ("avoid", "approach"):
        shutil.copy(models[task], p / "etc" / "gmmrrt" / "models" / (task + ".gmm"))
    ini_moved = work / "gmmrrtd.ini"
    ini_moved.write_text(text.replace(str(installed_prefix), str(p)))
    log = work / "in2.lcmlog"
    shutil.copy(SCENARIO, log)
    run([str(p / "bin" / "gmmrrtd"), "--config", str(ini_moved), "--lcm-url", "file://%s?speed=0" % log,
         "--lcm-out-url", "file://%s?mode=w" % (work / "out2.lcmlog"), "--exit-at-eof", "--budget-ms", "0",
         "--budget-iterations", "100", "--log-level", "warn"], env, work)


def test_installed_learner_segments_fits_and_plots_a_raw_recording(prefix):
    import lcm
    import numpy as np
    from gmmrrt import people_t, pose2d_t  # the test's own (build) message package writes the input

    p, env, work = prefix
    log_path = work / "drive.lcmlog"
    log = lcm.EventLog(str(log_path), "w", overwrite=True)
    t0 = 1_700_000_000_000_000
    rng = np.random.default_rng(3)
    for k in range(200):  # 20 s at 10 Hz: the robot passes a standing person on their left
        u = t0 + k * 100_000
        pe = people_t()
        pe.utime, pe.frame, pe.num_people = u, "map", 1
        q = pe.people[0]
        q.utime, q.id, q.x, q.y, q.yaw = u, 1, float(rng.normal(0, 0.01)), float(rng.normal(0, 0.01)), 0.0
        log.write_event(u, "PEOPLE", pe.encode())
        po = pose2d_t()
        po.utime, po.frame, po.x, po.y = u, "map", -6.0 + 0.06 * k, 1.2
        log.write_event(u, "ROBOT_POSE", po.encode())
    log.close()
    learn = str(p / "bin" / "gmmrrt-learn")
    run([learn, "segment", str(log_path), "-o", "eps.csv"], env, work)
    head = (work / "eps.csv").read_text().splitlines()
    assert head[0].startswith("episode_id,task,homotopy") and head[1].startswith("drive_seg0000,avoid,left,"), head[:2]
    run([learn, "fit", "--input", "eps.csv", "--task", "avoid", "--homotopy", "all", "--k", "2", "-o", "m.gmm",
         "-q"], env, work)
    run([learn, "plot", "m.gmm", "-o", "m.png"], env, work)
    assert (work / "m.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
