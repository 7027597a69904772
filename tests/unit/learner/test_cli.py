"""learner.cli: gmmrrt-learn end to end and its bad-input contract.

Every error case must exit non-zero with a message naming the problem (and the file / line
where there is one) and must leave no output model behind. Runs build/bin/gmmrrt-learn via
GMMRRT_BIN_DIR; real-data cases skip with the reason when GMMRRT_REAL_DATA is absent.
"""
import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

BIN = Path(os.environ.get("GMMRRT_BIN_DIR", "build/bin")) / "gmmrrt-learn"
REAL = Path(os.environ.get("GMMRRT_REAL_DATA", "../shared/data/real"))


def run(*args):
    return subprocess.run([str(BIN), *map(str, args)], capture_output=True, text=True, timeout=300)


@pytest.fixture
def blobs_csv(tmp_path):
    rng = np.random.default_rng(1)
    x = np.vstack([rng.normal([0, 0], 0.5, (300, 2)), rng.normal([5, 1], 0.4, (200, 2))])
    p = tmp_path / "blobs.csv"
    np.savetxt(p, x, delimiter=",", header="a,b", comments="", fmt="%.12g")
    return p


def episodes_csv(tmp_path, rows):
    p = tmp_path / "episodes.csv"
    lines = ["episode_id,task,homotopy,t,robot_x,robot_y,person_x,person_y,person_yaw"]
    lines += [",".join(map(str, r)) for r in rows]
    p.write_text("\n".join(lines) + "\n")
    return p


def synthetic_episodes(n_episodes=12, n=30):
    rows = []
    for e in range(n_episodes):
        side = 1 if e % 2 == 0 else -1
        for i in range(n):
            a = np.pi * i / (n - 1)
            rows.append((f"ep{e:02d}", "avoid", "left" if side > 0 else "right", 0.1 * i,
                         round(3 * np.cos(a) + 0.01 * e, 6), round(side * 1.5 * np.sin(a), 6), 0, 0, 0))
    return rows


def test_help_and_usage():
    r = run("--help")
    assert r.returncode == 0 and "fit" in r.stdout and "import" in r.stdout
    for cmd in ("fit", "score", "inspect", "import"):
        r = run(cmd, "--help")
        assert r.returncode == 0 and f"gmmrrt-learn {cmd}" in r.stdout
    r = run("frobnicate")
    assert r.returncode != 0 and "unknown command" in r.stderr


def test_fit_inspect_score_round_trip(tmp_path, blobs_csv):
    model = tmp_path / "m.gmm"
    r = run("fit", "--features-csv", blobs_csv, "--k", 2, "--seed", 3, "-o", model)
    assert r.returncode == 0, r.stderr
    assert "iteration" in r.stderr and "mean log-likelihood" in r.stderr
    r = run("inspect", model)
    assert r.returncode == 0, r.stderr
    assert "kind     generic" in r.stdout and "K        2" in r.stdout and "D        2" in r.stdout
    r = run("score", model, "--features-csv", blobs_csv)
    assert r.returncode == 0, r.stderr
    ll = float(r.stdout.split()[1])
    assert np.isfinite(ll) and -5 < ll < 0
    # --quiet silences progress; the same seed writes the same model bytes (the provenance trailer
    # after them differs: it records the command line and the time).
    model2 = tmp_path / "m2.gmm"
    r = run("fit", "--features-csv", blobs_csv, "--k", 2, "--seed", 3, "-o", model2, "--quiet")
    assert r.returncode == 0 and r.stderr == ""
    model_len = 32 + 8 * 2 * (1 + 2 + 3) + 4  # D = 2, K = 2 (docs/model-format.md)
    assert model.read_bytes()[:model_len] == model2.read_bytes()[:model_len]
    assert model.read_bytes()[model_len:model_len + 8] == b"GMMRRTPV"


def test_fit_episodes_features_and_xy(tmp_path):
    eps = episodes_csv(tmp_path, synthetic_episodes())
    for kind, d in (("features", 2), ("xy", 3)):
        model = tmp_path / f"{kind}.gmm"
        r = run("fit", "--input", eps, "--task", "avoid", "--homotopy", "left", "--kind", kind,
                "--k", 3, "-o", model, "-q")
        assert r.returncode == 0, r.stderr
        r = run("inspect", model)
        assert f"kind     {kind}" in r.stdout and f"D        {d}" in r.stdout and "homotopy left" in r.stdout
        if kind == "xy":
            means = [float(line.split()[1]) for line in r.stdout.splitlines() if line.strip().startswith("mean ")]
            assert means == sorted(means)  # components in order of progress s
        r = run("score", model, "--input", eps)
        assert r.returncode == 0 and "points 180" in r.stdout, r.stdout + r.stderr


def test_k_auto_prints_a_bic_table(tmp_path, blobs_csv):
    model = tmp_path / "auto.gmm"
    r = run("fit", "--features-csv", blobs_csv, "--k", "auto", "--k-range", "1..4", "-o", model, "-q")
    assert r.returncode == 0, r.stderr
    lines = [line for line in r.stdout.splitlines() if line.strip() and line.split()[0].isdigit()]
    assert [int(line.split()[0]) for line in lines] == [1, 2, 3, 4]
    assert "chosen K = 2" in r.stdout


BAD_FIT_CASES = {
    "no data file": (lambda t: ["--features-csv", t / "missing.csv"], "missing.csv"),
    "empty csv": (lambda t: ["--features-csv", write(t / "e.csv", "a,b\n")], "no data rows"),
    "nan": (lambda t: ["--features-csv", write(t / "n.csv", "1,2\n3,4\nnan,5\n")], "n.csv:3"),
    "inf": (lambda t: ["--features-csv", write(t / "i.csv", "1,2\n3,inf\n")], "i.csv:2"),
    "too few points": (lambda t: ["--features-csv", write(t / "f.csv", "1,2\n3,4\n5,7\n"), "--k", 2],
                       "need at least"),
    "too few points names the file": (lambda t: ["--features-csv", write(t / "few.csv", "1,2\n3,4\n5,7\n"),
                                                 "--k", 2], "few.csv"),
    "too few points in episodes": (lambda t: ["--input", episodes_csv(t, synthetic_episodes(1, 5)), "--task", "avoid",
                                              "--k", 3], "episodes.csv"),
    "seed in exponent form": (lambda t: ["--features-csv", write(t / "s.csv", "1\n2\n"), "--seed", "1e3"],
                              "--seed '1e3'"),
    "seed with a fraction": (lambda t: ["--features-csv", write(t / "s.csv", "1\n2\n"), "--seed", "2.5e1"],
                             "--seed '2.5e1'"),
    "unknown homotopy label in the file": (
        lambda t: ["--input", write(t / "lab.csv", "episode_id,task,homotopy,t,robot_x,robot_y,person_x,person_y,"
                                    "person_yaw\ne1,avoid,sideways,0,1,1,0,0,0\n"), "--task", "avoid"], "lab.csv: line 2: unknown homotopy"),
    "unknown task": (lambda t: ["--input", write(t / "ep.csv", "x\n"), "--task", "dance"], "unknown task 'dance'"),
    "unknown homotopy": (lambda t: ["--input", write(t / "ep.csv", "x\n"), "--task", "avoid", "--homotopy", "up"],
                         "unknown homotopy 'up'"),
    "unreadable episodes": (lambda t: ["--input", t / "nope.csv", "--task", "avoid"], "nope.csv"),
    "bad k": (lambda t: ["--features-csv", write(t / "k.csv", "1\n2\n"), "--k", "0"], "--k '0'"),
    "no episodes of task": (lambda t: ["--input", episodes_csv(t, synthetic_episodes(2, 5)), "--task", "approach"],
                            "no episode of task approach"),
}


def write(path, text):
    path.write_text(text)
    return path


@pytest.mark.parametrize("case", sorted(BAD_FIT_CASES))
def test_fit_bad_input_fails_cleanly(tmp_path, case):
    args, needle = BAD_FIT_CASES[case]
    model = tmp_path / "out.gmm"
    r = run("fit", *args(tmp_path), "-o", model)
    assert r.returncode != 0
    assert needle in r.stderr, r.stderr
    assert not model.exists()
    assert not [p for p in tmp_path.iterdir() if p.name.startswith("out.gmm")]  # no temporary left


def test_failed_fit_keeps_the_old_model(tmp_path, blobs_csv):
    model = tmp_path / "m.gmm"
    assert run("fit", "--features-csv", blobs_csv, "--k", 2, "-o", model, "-q").returncode == 0
    before = model.read_bytes()
    bad = write(tmp_path / "bad.csv", "1,2\nnan,3\n")
    assert run("fit", "--features-csv", bad, "--k", 2, "-o", model, "-q").returncode != 0
    assert model.read_bytes() == before


def test_inspect_rejects_invalid_models(tmp_path, blobs_csv):
    model = tmp_path / "m.gmm"
    assert run("fit", "--features-csv", blobs_csv, "--k", 2, "-o", model, "-q").returncode == 0
    data = bytearray(model.read_bytes())
    cases = {"truncated": bytes(data[:-9]), "flipped": bytes(data[:40]) + bytes([data[40] ^ 1]) + bytes(data[41:]),
             "not a model": b"hello world, definitely not a model file"}
    for name, content in cases.items():
        p = write(tmp_path / f"{name}.gmm", "")
        p.write_bytes(content)
        r = run("inspect", p)
        assert r.returncode != 0 and "invalid model" in r.stderr, (name, r.stderr)
    r = run("inspect", tmp_path / "absent.gmm")
    assert r.returncode != 0 and "absent.gmm" in r.stderr
    r = run("score", tmp_path / "absent.gmm", "--features-csv", blobs_csv)
    assert r.returncode != 0


def test_score_dimension_mismatch(tmp_path, blobs_csv):
    model = tmp_path / "m.gmm"
    assert run("fit", "--features-csv", blobs_csv, "--k", 2, "-o", model, "-q").returncode == 0
    three = write(tmp_path / "three.csv", "1,2,3\n4,5,6\n")
    r = run("score", model, "--features-csv", three)
    assert r.returncode != 0 and "D = 3" in r.stderr


def test_import_plain_json_and_errors(tmp_path):
    good = tmp_path / "g.json"
    good.write_text(json.dumps({"priors": [0.4, 0.6], "means": [[1.0, 3.0], [2.0, -0.5]],
                                "covs": [[[0.2, 0.01], [0.01, 0.1]], [[0.3, 0.0], [0.0, 0.2]]]}))
    model = tmp_path / "g.gmm"
    r = run("import", "--json", good, "-o", model)
    assert r.returncode == 0, r.stderr
    r = run("inspect", model)
    assert "kind     features" in r.stdout and "task     approach" in r.stdout and "angles   2" in r.stdout
    bad = tmp_path / "b.json"
    bad.write_text(json.dumps({"priors": [1.0], "means": [[1.0, 0.0]], "covs": [[[1.0, 2.0], [2.0, 1.0]]]}))
    out = tmp_path / "b.gmm"
    r = run("import", "--json", bad, "-o", out)
    assert r.returncode != 0 and "component 0: covariance is not positive definite" in r.stderr
    assert not out.exists()


def test_import_upo_approach_models():
    path = REAL / "upo_approach_gmms.json"
    if not path.exists():
        pytest.skip(f"real data not found at {REAL} (set GMMRRT_REAL_DATA)")
    import tempfile
    with tempfile.TemporaryDirectory() as d:
        out = Path(d) / "front.gmm"
        r = run("import", "--json", path, "--task-name", "1-front", "-o", out)
        assert r.returncode == 0, r.stderr
        spec = json.loads(path.read_text())["sets"]["tasks"]["1-front"]
        r = run("inspect", out)
        assert f"K        {spec['n_components']}" in r.stdout
        # Every task of both sets imports; two-homotopy tasks (priors summing to 2) say so.
        sets = json.loads(path.read_text())["sets"]
        for set_name, tasks in sets.items():
            for task_name, task in tasks.items():
                r = run("import", "--json", path, "--set", set_name, "--task-name", task_name, "-o", out)
                assert r.returncode == 0, (set_name, task_name, r.stderr)
                assert ("one mixture per homotopy" in r.stderr) == bool(task["two_homotopies"])
                assert f"K        {task['n_components']}" in run("inspect", out).stdout
        r = run("import", "--json", path, "--task-name", "9-nowhere", "-o", out)
        assert r.returncode != 0 and "1-front" in r.stderr  # lists the known tasks


def test_fit_from_demonstration_logs(tmp_path):
    logs = [Path("logs/demos/avoid_left.lcmlog"), Path("logs/demos/avoid_right.lcmlog")]
    if not all(p.exists() for p in logs):
        pytest.fail("logs/demos/avoid_*.lcmlog missing: tools/synth_demonstrations.py --seed 1 --out-dir logs/demos makes them")
    model = tmp_path / "demo.gmm"
    r = run("fit", "--input", *logs, "--task", "avoid", "--homotopy", "left", "--k", 4, "-o", model, "-q")
    assert r.returncode == 0, r.stderr
    assert "homotopy left" in run("inspect", model).stdout
    own = float(run("score", model, "--input", logs[0], "-q").stdout.split()[1])
    other = float(run("score", model, "--input", logs[1], "--homotopy", "right", "-q").stdout.split()[1])
    assert own > other  # a left-passing model explains left passes better than right ones


def test_csv_with_a_utf8_byte_order_mark_is_accepted(tmp_path, blobs_csv):
    bom = b"\xef\xbb\xbf"
    feats = tmp_path / "bom.csv"
    feats.write_bytes(bom + blobs_csv.read_bytes())
    r = run("fit", "--features-csv", feats, "--k", 2, "-o", tmp_path / "f.gmm", "-q")
    assert r.returncode == 0, r.stderr
    eps = episodes_csv(tmp_path, synthetic_episodes())
    eps.write_bytes(bom + eps.read_bytes())
    r = run("fit", "--input", eps, "--task", "avoid", "--k", 2, "-o", tmp_path / "e.gmm", "-q")
    assert r.returncode == 0, r.stderr


def test_output_that_is_not_a_regular_file_is_refused(tmp_path, blobs_csv):
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    link = tmp_path / "link.gmm"
    link.symlink_to(fifo)
    folder = tmp_path / "folder.gmm"
    folder.mkdir()
    for target in (fifo, link, folder, Path("/dev/null")):
        r = run("fit", "--features-csv", blobs_csv, "--k", 2, "-o", target, "-q")
        assert r.returncode == 1, (target, r.stderr)
        assert str(target) in r.stderr and "not a regular file" in r.stderr, r.stderr
    assert fifo.is_fifo() and link.is_symlink() and folder.is_dir()
    assert Path("/dev/null").is_char_device()
    assert not [p for p in tmp_path.iterdir() if ".tmp." in p.name]
    # A link to a regular file is replaced atomically by the new model.
    old = tmp_path / "old.gmm"
    old.write_bytes(b"old")
    good_link = tmp_path / "good_link.gmm"
    good_link.symlink_to(old)
    r = run("fit", "--features-csv", blobs_csv, "--k", 2, "-o", good_link, "-q")
    assert r.returncode == 0, r.stderr
    assert run("inspect", good_link).returncode == 0


def test_inspect_json_holds_the_model(tmp_path, blobs_csv):
    model = tmp_path / "m.gmm"
    assert run("fit", "--features-csv", blobs_csv, "--k", 2, "-o", model, "-q").returncode == 0
    r = run("inspect", "--json", model)
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert d["kind"] == "generic" and d["dim"] == 2 and d["k"] == 2 and d["angle_dims"] == []
    assert abs(sum(c["weight"] for c in d["components"]) - 1) < 1e-12
    text = run("inspect", model).stdout
    for c in d["components"]:
        cov = np.array(c["covariance"])
        chol = np.array(c["chol"])
        np.testing.assert_allclose(chol @ chol.T, cov, rtol=1e-12, atol=0)
        assert f"weight {c['weight']:.6f}" in text
    # A corrupt file: the loader's reason, exit 1, no JSON on stdout.
    data = bytearray(model.read_bytes())
    data[40] ^= 1
    bad = tmp_path / "bad.gmm"
    bad.write_bytes(bytes(data))
    r = run("inspect", "--json", bad)
    assert r.returncode == 1 and r.stdout == "" and "invalid model" in r.stderr


def test_unlabelled_episodes_fit_with_homotopy_all(tmp_path):
    rows = [(e, t, "", *rest) for (e, t, _h, *rest) in synthetic_episodes()]
    eps = episodes_csv(tmp_path, rows)
    model = tmp_path / "all.gmm"
    r = run("fit", "--input", eps, "--task", "avoid", "--homotopy", "all", "--k", 2, "-o", model, "-q")
    assert r.returncode == 0, r.stderr
    r = run("fit", "--input", eps, "--task", "avoid", "--homotopy", "left", "--k", 2, "-o", tmp_path / "l.gmm", "-q")
    assert r.returncode == 1 and "no episode" in r.stderr and not (tmp_path / "l.gmm").exists()
