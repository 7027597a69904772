"""Small hand-made mixture models for gmmrrtd's scenario and replay tests.

They are fixed so that the replays do not depend on a learner run: a features-kind model
(D = 2: d [m], theta [rad, wrapped]) per task, built, validated, encoded and written
atomically by the C core (gmmrrt_tools.core: gmmrrt_model_from_arrays, gmmrrt_model_encode,
gmmrrt_model_save_file), the one implementation of docs/model-format.md. The avoid model puts its mass beside the person (theta = +-pi/2, d ~ 1.2 m: pass
on either side); the approach model in front of the person (theta ~ 0, d ~ 1.0 m).

    python -m gmmrrt_tools.scenario_models OUT_DIR     # writes avoid.gmm and approach.gmm
"""
import math
import os
import sys

from gmmrrt_tools import core

# model.h: gmmrrt_model_kind_t and gmmrrt_task_t (= nav_goal_t.TASK_* on the wire).
KIND_FEATURES, TASK_AVOID, TASK_APPROACH = 1, 1, 2
THETA_IS_ANGLE = 0b10  # angle_mask: dimension 1 (theta) is a wrapped angle


def features_model(task, components, delta=0.001):
    """A prepared (d, theta) model from components (weight, mean_d, mean_theta, sigma_d, sigma_theta),
    uncorrelated; the weights are normalised to sum to 1."""
    total = sum(c[0] for c in components)
    return core.model_from_arrays(KIND_FEATURES, task, 0, [c[0] / total for c in components],
                                  [(c[1], c[2]) for c in components],
                                  # L = diag(sigma_d, sigma_theta), packed L00, L10, L11
                                  [(c[3], 0.0, c[4]) for c in components], THETA_IS_ANGLE, delta)


def encode_features_model(task, components, delta=0.001):
    """The model file bytes of features_model(task, components, delta)."""
    return core.encode_model(features_model(task, components, delta))


AVOID = [(0.5, 1.2, math.pi / 2, 0.3, 0.35), (0.5, 1.2, -math.pi / 2, 0.3, 0.35)]
APPROACH = [(0.7, 1.0, 0.0, 0.25, 0.3), (0.3, 1.8, 0.0, 0.4, 0.5)]


def write_models(out_dir):
    """Writes avoid.gmm and approach.gmm into out_dir; returns their paths."""
    os.makedirs(out_dir, exist_ok=True)
    paths = {}
    for name, task, comps in (("avoid", TASK_AVOID, AVOID), ("approach", TASK_APPROACH, APPROACH)):
        path = os.path.join(out_dir, name + ".gmm")
        core.save_model(path, features_model(task, comps))
        paths[name] = path
    return paths


def write_approach_set(out_dir):
    """Writes an approach model set into out_dir (gmmrrtd's [models] approach_set, model_set.h):
    one file per direction, named by the core, each with its mass 1.0 m away at its own bearing
    (direction k at theta = -k * 45 degrees), so which member planned shows in the plan.
    Returns the directory."""
    from gmmrrt_tools import core
    os.makedirs(out_dir, exist_ok=True)
    for k in range(8):
        theta = math.remainder(-k * math.pi / 4.0, 2.0 * math.pi)
        path = os.path.join(out_dir, core.approach_direction_name(k) + ".gmm")
        with open(path + ".tmp", "wb") as f:
            f.write(encode_features_model(TASK_APPROACH, [(1.0, 1.0, theta, 0.25, 0.3)]))
        os.replace(path + ".tmp", path)
    return out_dir


if __name__ == "__main__":
    if len(sys.argv) != 2 or sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0 if len(sys.argv) == 2 else 2)
    for p in write_models(sys.argv[1]).values():
        print(p)
