"""planner.model_binding: the Python tools write and read model files through the C core.

gmmrrt_tools.core hands the numbers to gmmrrt_model_from_arrays and encodes/decodes/saves with
model.c and planner/io (the one implementation of docs/model-format.md; the deliberately
independent oracle of the format is tools/gen_model_vectors.py, checked in planner.model_vectors).
Here: a model survives encode -> decode -> fields; the scenario models decode; an invalid model
is refused with the core's reason and nothing is written; a save replaces a file atomically.
"""
import math

import pytest

from gmmrrt_tools import core, scenario_models

COMPONENTS = [(0.3, 1.0, 0.5, 0.2, 0.3), (0.7, 2.0, -2.0, 0.4, 0.25)]


def test_encode_decode_keeps_every_stored_field():
    m = scenario_models.features_model(scenario_models.TASK_APPROACH, COMPONENTS, delta=0.002)
    f = core.model_fields(core.decode_model(core.encode_model(m)))
    assert (f["kind"], f["task"], f["homotopy"], f["dim"], f["k"], f["angle_mask"]) == (1, 2, 0, 2, 2, 0b10)
    assert f["delta"] == 0.002
    assert f["weights"] == [0.3, 0.7]
    assert f["means"] == [[1.0, 0.5], [2.0, -2.0]]
    assert f["chols"] == [[0.2, 0.0, 0.3], [0.4, 0.0, 0.25]]


def test_scenario_models_are_files_the_core_reads(tmp_path):
    paths = scenario_models.write_models(str(tmp_path))
    for name, task in (("avoid", 1), ("approach", 2)):
        data = open(paths[name], "rb").read()
        assert data == scenario_models.encode_features_model(
            task, scenario_models.AVOID if name == "avoid" else scenario_models.APPROACH)
        assert core.model_fields(core.decode_model(data))["task"] == task
    assert sorted(p.name for p in tmp_path.iterdir()) == ["approach.gmm", "avoid.gmm"]  # no temporaries


@pytest.mark.parametrize("weights,means,chols,reason", [
    ([0.5, 0.4], [(1, 0), (2, 0)], [(0.2, 0, 0.2)] * 2, "weight"),
    ([1.0], [(1, math.nan)], [(0.2, 0, 0.2)], r"mean\[1\] is nan"),
    ([1.0], [(1, 0)], [(-0.2, 0, 0.2)], ""),
])
def test_invalid_models_are_refused_with_the_cores_reason(tmp_path, weights, means, chols, reason):
    with pytest.raises(core.ModelError, match=reason):
        core.model_from_arrays(1, 1, 0, weights, means, chols, 0b10, 0.001)


def test_save_replaces_atomically_and_reports_io_errors(tmp_path):
    path = tmp_path / "m.gmm"
    path.write_bytes(b"old")
    m = scenario_models.features_model(1, COMPONENTS)
    core.save_model(str(path), m)
    assert path.read_bytes() == core.encode_model(m)
    with pytest.raises(core.ModelError, match="no_such_dir"):
        core.save_model(str(tmp_path / "no_such_dir" / "m.gmm"), m)
    with pytest.raises(core.ModelError, match="not a valid model"):
        core.decode_model(b"GMMRRTMD this is not a model")
