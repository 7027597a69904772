"""learner.provenance: `gmmrrt-learn fit` stores what a model was learned from, and every reader sees it.

fit writes a provenance trailer (docs/model-format.md) holding a JSON record: SHA-256 of the data
files, the command line, seed, K, BIC, mean log-likelihood, learner version, UTC time. Checked here
against hashlib and the fit's own report; `inspect` (text and --json), the core's Python binding
(gmmrrt_tools.core) and the independent oracle (gmmrrt_tools.model_vectors) all read the same text;
--no-provenance writes the bare model that loaders from before the trailer read; a damaged or cut
trailer is refused naming it, and a file without one still loads.
"""
import hashlib
import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

from gmmrrt_tools import core
from gmmrrt_tools import model_vectors as oracle  # the independent oracle

BIN = Path(os.environ.get("GMMRRT_BIN_DIR", "build/bin")) / "gmmrrt-learn"
MODEL_LEN = 32 + 8 * 3 * (1 + 2 + 3) + 4  # D = 2, K = 3


def run(*args, env=None):
    return subprocess.run([str(BIN), *map(str, args)], capture_output=True, text=True, timeout=300,
                          env=dict(os.environ, **(env or {})))


@pytest.fixture
def data(tmp_path):
    rng = np.random.default_rng(5)
    x = np.vstack([rng.normal([0, 0], 0.5, (300, 2)), rng.normal([4, 1], 0.4, (200, 2)),
                   rng.normal([0, 4], 0.3, (200, 2))])
    p = tmp_path / "three.csv"
    np.savetxt(p, x, delimiter=",", header="a,b", comments="", fmt="%.12g")
    return p


def fit(tmp_path, data, *extra, env=None):
    model = tmp_path / "m.gmm"
    r = run("fit", "--features-csv", data, "--k", 3, "--seed", 11, "-o", model, *extra, env=env)
    assert r.returncode == 0, r.stderr
    return model, r


def test_fit_records_data_hash_command_seed_k_bic_loglik(tmp_path, data):
    model, r = fit(tmp_path, data, env={"SOURCE_DATE_EPOCH": "1700000000"})
    rec = json.loads(core.model_provenance(model.read_bytes()))
    digest = hashlib.sha256(data.read_bytes()).hexdigest()
    assert rec["data_sha256"] == digest and rec["data_bytes"] == data.stat().st_size
    assert rec["data_files"] == [{"path": str(data), "bytes": data.stat().st_size, "sha256": digest}]
    assert rec["command_line"] == ["gmmrrt-learn", "fit", "--features-csv", str(data), "--k", "3", "--seed", "11",
                                   "-o", str(model)]
    assert (rec["seed"], rec["k"], rec["k_auto"], rec["points"], rec["dim"]) == (11, 3, False, 700, 2)
    assert rec["created_utc"] == "2023-11-14T22:13:20Z"  # SOURCE_DATE_EPOCH, for reproducible files
    assert rec["learner"].startswith("gmmrrt-learn ")
    # The fit's own report (stderr, 10 significant digits) and `score` agree with the record.
    report = dict(w.split("=", 1) for w in r.stderr.split() if w.startswith(("BIC=", "mean_log_likelihood=")))
    assert rec["bic"] == pytest.approx(float(report["BIC"]), rel=1e-9)
    assert rec["mean_log_likelihood"] == pytest.approx(float(report["mean_log_likelihood"]), rel=1e-9)
    score = run("score", model, "--features-csv", data)
    assert score.returncode == 0, score.stderr
    assert rec["mean_log_likelihood"] == pytest.approx(float(score.stdout.split()[1]), rel=1e-9, abs=1e-9)
    n, d, k = 700, 2, 3
    params = k * (1 + d + d * (d + 1) // 2) - 1
    assert rec["bic"] == pytest.approx(-2 * n * rec["mean_log_likelihood"] + params * np.log(n), rel=1e-12)
    # Same seed and time: the same file, trailer included.
    again, _ = fit(tmp_path, data, env={"SOURCE_DATE_EPOCH": "1700000000"})
    assert again.read_bytes() == model.read_bytes()


def test_inspect_text_and_json_show_the_provenance(tmp_path, data):
    model, _ = fit(tmp_path, data)
    r = run("inspect", "--json", model)
    assert r.returncode == 0, r.stderr
    doc = json.loads(r.stdout)
    assert doc["provenance"] == json.loads(core.model_provenance(model.read_bytes()))
    assert doc["provenance"]["seed"] == 11 and doc["k"] == 3
    text = run("inspect", model).stdout
    assert "provenance" in text and doc["provenance"]["data_sha256"] in text and "command_line" in text


def test_oracle_and_binding_agree_and_the_model_bytes_are_unchanged(tmp_path, data):
    model, _ = fit(tmp_path, data)
    raw = model.read_bytes()
    independent = oracle.decode(raw)
    assert independent["provenance"] == core.model_provenance(raw)
    # The model part is an ordinary model file: the core and the oracle read the same numbers.
    bare = raw[:MODEL_LEN]
    assert oracle.decode(bare)["provenance"] is None and core.model_provenance(bare) is None
    f = core.model_fields(core.decode_model(raw))
    np.testing.assert_array_equal(f["weights"], independent["weights"])
    assert core.model_fields(core.decode_model(bare)) == f
    # Python writes the same trailer as the oracle's encoder, through the core.
    text = independent["provenance"]
    m = core.decode_model(raw)
    assert core.encode_model(m, provenance=text) == bare + oracle.encode_provenance(text)
    core.save_model(str(tmp_path / "py.gmm"), m, provenance="{\"by\": \"python\"}")
    assert core.model_provenance((tmp_path / "py.gmm").read_bytes()) == "{\"by\": \"python\"}"


def test_no_provenance_writes_the_bare_model_old_loaders_read(tmp_path, data):
    model, _ = fit(tmp_path, data)
    bare_path = tmp_path / "bare.gmm"
    r = run("fit", "--features-csv", data, "--k", 3, "--seed", 11, "-o", bare_path, "--no-provenance", "-q")
    assert r.returncode == 0, r.stderr
    bare = bare_path.read_bytes()
    assert len(bare) == MODEL_LEN and bare == model.read_bytes()[:MODEL_LEN]
    doc = json.loads(run("inspect", "--json", bare_path).stdout)
    assert doc["provenance"] is None
    assert "provenance none" in run("inspect", bare_path).stdout
    # The rule a loader from before the trailer applies (length == encoded size of D, K): the bare
    # file passes it, the file with provenance does not (it is refused as "trailing bytes").
    assert len(model.read_bytes()) > MODEL_LEN


@pytest.mark.parametrize("damage,reason", [
    (lambda b: b[:MODEL_LEN + 30] + bytes([b[MODEL_LEN + 30] ^ 0x20]) + b[MODEL_LEN + 31:], "provenance is corrupt"),
    (lambda b: b[:-1], "truncated"),
    (lambda b: b[:MODEL_LEN + 5], "provenance trailer"),
    (lambda b: b + b"x", "trailing"),
])
def test_damaged_or_cut_trailer_is_refused_naming_it(tmp_path, data, damage, reason):
    model, _ = fit(tmp_path, data)
    bad = tmp_path / "bad.gmm"
    bad.write_bytes(damage(model.read_bytes()))
    r = run("inspect", "--json", bad)
    assert r.returncode == 1 and r.stdout == "" and reason in r.stderr and str(bad) in r.stderr, r.stderr
    with pytest.raises(core.ModelError, match=reason):
        core.decode_model(bad.read_bytes())
    with pytest.raises(core.ModelError, match=reason):
        core.model_provenance(bad.read_bytes())
    with pytest.raises(ValueError):
        oracle.decode(bad.read_bytes())
    assert run("score", bad, "--features-csv", data).returncode != 0


def test_a_long_command_line_still_fits_the_trailer(tmp_path, data):
    # Past GMMRRT_MAX_PROVENANCE_BYTES (4096) the per-file list goes first, then the command line's
    # tail; the combined hash still names the data and the record says what it left out.
    model = tmp_path / "long.gmm"
    args = ["fit", "--features-csv", data, "--k", 3, "-o", model, "-q"] + ["--tol", "1e-6"] * 400
    r = run(*args)
    assert r.returncode == 0, r.stderr
    text = core.model_provenance(model.read_bytes())
    assert len(text.encode()) <= 4096
    rec = json.loads(text)
    assert rec["command_line_truncated"] is True and rec["data_files_omitted"] == 1
    assert rec["command_line"][:4] == ["gmmrrt-learn", "fit", "--features-csv", str(data)]
    assert rec["data_sha256"] == hashlib.sha256(data.read_bytes()).hexdigest()


def test_python_load_exposes_the_provenance_through_the_core(tmp_path, data):
    from gmmrrt_tools.learn import GaussianMixture

    model, _ = fit(tmp_path, data)
    gm = GaussianMixture.load(model)
    assert gm.provenance_text_ == core.model_provenance(model.read_bytes())
    assert gm.provenance_["data_sha256"] == hashlib.sha256(data.read_bytes()).hexdigest()
    assert (gm.provenance_["seed"], gm.provenance_["k"], gm.provenance_["points"]) == (11, 3, 700)
    assert gm.provenance_["command_line"][:2] == ["gmmrrt-learn", "fit"]
    # A file without a trailer (what GaussianMixture.save writes) loads with provenance None.
    bare = tmp_path / "bare.gmm"
    gm.save(bare)
    assert len(bare.read_bytes()) == MODEL_LEN
    back = GaussianMixture.load(bare)
    assert back.provenance_ is None and back.provenance_text_ is None
    # A trailer that another writer filled with something other than a JSON object is named.
    m = core.decode_model(model.read_bytes())
    for text in ("not json", "[1, 2]"):
        odd = tmp_path / "odd.gmm"
        core.save_model(str(odd), m, provenance=text)
        with pytest.raises(ValueError, match="odd.gmm: the provenance trailer is not"):
            GaussianMixture.load(odd)
