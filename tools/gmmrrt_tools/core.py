"""ctypes binding to the gmmrrt C libraries: one definition of each rule, in C.

- build/lib/libgmmrrt.so (planner/src + planner/io): the features (d, theta), angle wrapping,
  the mixture, the model file format (gmmrrt_model_encode/decode, atomic gmmrrt_model_save_file),
  the table of planner settings (config_keys.h: names, flags, ranges, defaults, help);
- build/lib/libgmmrrt_msg.so (lcmtypes/msg_decode.c): the validating message decoders that gmmrrtd
  uses, so a Python check judges a message exactly as the daemon does.

The libraries are looked up in $GMMRRT_BUILD_DIR/lib, then <repo>/build/lib. Build them with
`tools/run build`.
"""
from __future__ import annotations

import ctypes
import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Dict, List, Optional, Tuple

_REPO = Path(__file__).resolve().parents[2]


class CoreNotBuilt(RuntimeError):
    """libgmmrrt.so was not found: run `tools/run build` first."""


class Pose(ctypes.Structure):
    """gmmrrt_pose_t: x, y [m], yaw [rad]."""

    _fields_ = [("x", ctypes.c_double), ("y", ctypes.c_double), ("yaw", ctypes.c_double)]


def _candidates(name: str):
    env = os.environ.get("GMMRRT_BUILD_DIR")
    if env:
        yield Path(env) / "lib" / name
    yield _REPO / "build" / "lib" / name


def _load(name: str) -> ctypes.CDLL:
    for path in _candidates(name):
        if path.is_file():
            return ctypes.CDLL(str(path))
    raise CoreNotBuilt(
        name + " not found in " + ", ".join(str(p) for p in _candidates(name))
        + ": run `tools/run build` (or set GMMRRT_BUILD_DIR)")


_lib = None
_msg_lib = None


def lib() -> ctypes.CDLL:
    """The loaded core library (loaded once)."""
    global _lib
    if _lib is None:
        _lib = _load("libgmmrrt.so")
        d = ctypes.c_double
        pd = ctypes.POINTER(ctypes.c_double)
        pp = ctypes.POINTER(Pose)
        _lib.gmmrrt_wrap_angle.argtypes = [d]
        _lib.gmmrrt_wrap_angle.restype = d
        _lib.gmmrrt_features_from_xy.argtypes = [pp, d, d, pd, pd]
        _lib.gmmrrt_features_from_xy.restype = None
        _lib.gmmrrt_features_to_xy.argtypes = [pp, d, d, pd, pd]
        _lib.gmmrrt_features_to_xy.restype = None
        _lib.gmmrrt_path_swept_angle.argtypes = [pp, pd, ctypes.c_size_t]
        _lib.gmmrrt_path_swept_angle.restype = d
        _lib.gmmrrt_path_passing_side.argtypes = [pp, pd, ctypes.c_size_t]
        _lib.gmmrrt_path_passing_side.restype = ctypes.c_int
        _lib.gmmrrt_world_to_person.argtypes = [pp, d, d, pd, pd]
        _lib.gmmrrt_world_to_person.restype = None
        _lib.gmmrrt_person_to_world.argtypes = [pp, d, d, pd, pd]
        _lib.gmmrrt_person_to_world.restype = None
        _lib.gmmrrt_status_str.argtypes = [ctypes.c_int]
        _lib.gmmrrt_status_str.restype = ctypes.c_char_p
        _lib.gmmrrt_model_sizeof.argtypes = []
        _lib.gmmrrt_model_sizeof.restype = ctypes.c_size_t
        _lib.gmmrrt_model_from_arrays.argtypes = [ctypes.c_int32] * 5 + [ctypes.c_uint32, d, pd, pd, pd,
                                                                         ctypes.c_void_p, ctypes.c_char_p,
                                                                         ctypes.c_size_t]
        _lib.gmmrrt_model_from_arrays.restype = ctypes.c_int
        _lib.gmmrrt_model_to_arrays.argtypes = [ctypes.c_void_p, ctypes.POINTER(ctypes.c_int32), pd, pd, pd, pd]
        _lib.gmmrrt_model_to_arrays.restype = None
        _lib.gmmrrt_model_max_encoded_size.argtypes = []
        _lib.gmmrrt_model_max_encoded_size.restype = ctypes.c_size_t
        _lib.gmmrrt_model_encode.argtypes = [ctypes.c_void_p, ctypes.c_char_p, ctypes.c_size_t,
                                             ctypes.POINTER(ctypes.c_size_t), ctypes.c_char_p, ctypes.c_size_t]
        _lib.gmmrrt_model_encode.restype = ctypes.c_int
        _lib.gmmrrt_model_decode.argtypes = [ctypes.c_char_p, ctypes.c_size_t, ctypes.c_void_p, ctypes.c_char_p,
                                             ctypes.c_size_t]
        _lib.gmmrrt_model_decode.restype = ctypes.c_int
        _lib.gmmrrt_model_save_file.argtypes = [ctypes.c_char_p, ctypes.c_void_p, ctypes.c_char_p, ctypes.c_size_t]
        _lib.gmmrrt_model_save_file.restype = ctypes.c_int
        sz, psz = ctypes.c_size_t, ctypes.POINTER(ctypes.c_size_t)
        _lib.gmmrrt_model_max_file_size.argtypes = []
        _lib.gmmrrt_model_max_file_size.restype = sz
        _lib.gmmrrt_model_encode_provenance.argtypes = [ctypes.c_void_p, ctypes.c_char_p, sz, ctypes.c_char_p, sz,
                                                        psz, ctypes.c_char_p, sz]
        _lib.gmmrrt_model_encode_provenance.restype = ctypes.c_int
        _lib.gmmrrt_model_provenance.argtypes = [ctypes.c_char_p, sz, ctypes.c_char_p, sz, psz,
                                                 ctypes.POINTER(ctypes.c_int), ctypes.c_char_p, sz]
        _lib.gmmrrt_model_provenance.restype = ctypes.c_int
        _lib.gmmrrt_model_save_file_provenance.argtypes = [ctypes.c_char_p, ctypes.c_void_p, ctypes.c_char_p, sz,
                                                           ctypes.c_char_p, sz]
        _lib.gmmrrt_model_save_file_provenance.restype = ctypes.c_int
        _lib.gmmrrt_model_encode_file.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_char_p, sz,
                                                  ctypes.c_char_p, sz, psz, ctypes.c_char_p, sz]
        _lib.gmmrrt_model_encode_file.restype = ctypes.c_int
        _lib.gmmrrt_model_background.argtypes = [ctypes.c_char_p, sz, ctypes.c_void_p, ctypes.POINTER(ctypes.c_int),
                                                 ctypes.c_char_p, sz]
        _lib.gmmrrt_model_background.restype = ctypes.c_int
        _lib.gmmrrt_approach_direction_name.argtypes = [ctypes.c_int32]
        _lib.gmmrrt_approach_direction_name.restype = ctypes.c_char_p
        pk = ctypes.POINTER(_ConfigKey)
        _lib.gmmrrt_config_key_count.argtypes = []
        _lib.gmmrrt_config_key_count.restype = ctypes.c_int32
        _lib.gmmrrt_config_key_at.argtypes = [ctypes.c_int32]
        _lib.gmmrrt_config_key_at.restype = pk
        _lib.gmmrrt_problem_bounds.argtypes = [d, d, d, d, d, ctypes.POINTER(ctypes.c_double * 4)]
        _lib.gmmrrt_problem_bounds.restype = ctypes.c_int
        for fn in (_lib.gmmrrt_config_key_default, _lib.gmmrrt_config_key_range):
            fn.argtypes = [pk, ctypes.c_char_p, sz]
            fn.restype = ctypes.c_char_p
    return _lib


def msg_lib() -> ctypes.CDLL:
    """The loaded message decoders (libgmmrrt_msg.so, loaded once)."""
    global _msg_lib
    if _msg_lib is None:
        _msg_lib = _load("libgmmrrt_msg.so")
        for t in MESSAGE_TYPES:
            fn = getattr(_msg_lib, "gmmrrt_msg_decode_" + t)
            fn.argtypes = [ctypes.c_char_p, ctypes.c_size_t, ctypes.c_void_p, ctypes.c_char_p, ctypes.c_size_t]
            fn.restype = ctypes.c_int
        for t in FRAMED_TYPES:
            fn = getattr(_msg_lib, "gmmrrt_msg_release_" + t)
            fn.argtypes = [ctypes.c_void_p]
            fn.restype = None
        _msg_lib.gmmrrt_msg_check_frame.argtypes = [ctypes.c_char_p, ctypes.c_char_p, ctypes.c_char_p,
                                                    ctypes.c_char_p, ctypes.c_size_t]
        _msg_lib.gmmrrt_msg_check_frame.restype = ctypes.c_int
    return _msg_lib


# ------------------------------------------------------------------ planner settings (config_keys.h)

class _ConfigKey(ctypes.Structure):
    """gmmrrt_config_key_t (config_keys.h); read only through the table's accessors."""

    _fields_ = [("name", ctypes.c_char_p), ("flag", ctypes.c_char_p), ("type", ctypes.c_int32),
                ("offset", ctypes.c_size_t), ("min", ctypes.c_double), ("max", ctypes.c_double),
                ("min_open", ctypes.c_int32), ("max_open", ctypes.c_int32), ("choices", ctypes.c_char_p * 4),
                ("help", ctypes.c_char_p)]


@dataclass(frozen=True)
class ConfigKey:
    """One planner setting as the core's table has it: `name` ([planner] key of gmmrrtd, and the
    name used here), `flag` (the long option of gmmrrt-plan and gmmrrtd, with its dashes), the
    default and the range as text, the choices of a named setting, the help line."""
    name: str
    flag: str
    default: str
    range: str
    choices: Tuple[str, ...]
    help: str


_config_keys: Optional[Dict[str, ConfigKey]] = None


def config_keys() -> Dict[str, ConfigKey]:
    """The planner settings by name, in the core's --help order (gmmrrt_config_key_at)."""
    global _config_keys
    if _config_keys is None:
        L = lib()
        out: Dict[str, ConfigKey] = {}
        buf = ctypes.create_string_buffer(256)
        for i in range(L.gmmrrt_config_key_count()):
            k = L.gmmrrt_config_key_at(i)
            c = k.contents
            default = L.gmmrrt_config_key_default(k, buf, len(buf)).decode()
            rng = L.gmmrrt_config_key_range(k, buf, len(buf)).decode()
            choices = tuple(x.decode() for x in c.choices if x)
            out[c.name.decode()] = ConfigKey(c.name.decode(), "--" + c.flag.decode(), default, rng, choices,
                                             c.help.decode())
        _config_keys = out
    return _config_keys


def planner_flags(settings: Dict[str, object]) -> List[str]:
    """The command-line flags of gmmrrt-plan and gmmrrtd for planner settings given by name, e.g.
    {"gmm_bias": 0.5, "delta": 0.001} -> ["--gmm-bias", "0.5", "--delta", "0.001"]. KeyError naming
    the known settings for a name the core does not have; the value's range is checked by the
    program that reads the flag (the core's gmmrrt_config_key_set)."""
    keys = config_keys()
    argv: List[str] = []
    for name, value in settings.items():
        if name not in keys:
            raise KeyError(f"no planner setting {name!r}; the core's are: {', '.join(keys)}")
        argv += [keys[name].flag, repr(float(value)) if isinstance(value, float) else str(value)]
    return argv


# ------------------------------------------------------------------ planning bounds (problem_bounds.h)

def problem_bounds(start: Tuple[float, float], goal: Tuple[float, float],
                   margin_m: Optional[float] = None) -> Tuple[float, float, float, float]:
    """(xmin, ymin, xmax, ymax) of the problem from start to goal by the core's one rule, the one
    gmmrrtd and gmmrrt-plan plan with (gmmrrt_problem_bounds): the box around start and goal grown
    by margin_m (default GMMRRT_DEFAULT_BOUNDS_MARGIN_M). ValueError for a point or margin that is
    not finite or a margin <= 0."""
    if margin_m is None:
        import gmmrrt_constants
        margin_m = gmmrrt_constants.GMMRRT_DEFAULT_BOUNDS_MARGIN_M
    out = (ctypes.c_double * 4)()
    st = lib().gmmrrt_problem_bounds(float(start[0]), float(start[1]), float(goal[0]), float(goal[1]),
                                     float(margin_m), ctypes.byref(out))
    if st != 0:
        raise ValueError(f"no planning bounds for start {start}, goal {goal}, margin {margin_m}: "
                         f"{lib().gmmrrt_status_str(st).decode()}")
    return (out[0], out[1], out[2], out[3])


def _pair(fn, person: Tuple[float, float, float], a: float, b: float) -> Tuple[float, float]:
    p = Pose(*person)
    out1, out2 = ctypes.c_double(), ctypes.c_double()
    fn(ctypes.byref(p), float(a), float(b), ctypes.byref(out1), ctypes.byref(out2))
    return out1.value, out2.value


def approach_direction_name(direction: int) -> str:
    """Name of approach direction 0..7 ("1-front" ... "8-45_left"), the file stem of a model set's
    member (gmmrrt_approach_direction_name, model_set.h); ValueError outside 0..7."""
    name = lib().gmmrrt_approach_direction_name(int(direction))
    if name is None:
        raise ValueError("approach direction %r is not in 0..7" % (direction,))
    return name.decode()


# gmmrrt_status_t codes a path comes with (planner/include/gmmrrt/status.h; wire-stable, they are
# PLAN.status values): a plan that first escapes a contact, and one flagged for a corner tighter
# than the turning radius. Read from the header at build time (gmmrrt_constants, generated beside the
# message package), not written again; looked up on first use, like the library itself.
_STATUS_CONSTANTS = {"STATUS_ESCAPE": "GMMRRT_ESCAPE", "STATUS_TIGHT_TURNS": "GMMRRT_TIGHT_TURNS"}


def __getattr__(name: str):
    if name in _STATUS_CONSTANTS:
        import gmmrrt_constants
        return getattr(gmmrrt_constants, _STATUS_CONSTANTS[name])
    raise AttributeError("module %r has no attribute %r" % (__name__, name))


def status_str(code: int) -> str:
    """The core's text for a gmmrrt_status_t code (gmmrrt_status_str), as gmmrrt-plan prints it."""
    return lib().gmmrrt_status_str(int(code)).decode()


def wrap_angle(a: float) -> float:
    """Angle wrapped to (-pi, pi] (gmmrrt_wrap_angle)."""
    return lib().gmmrrt_wrap_angle(float(a))


def _xy_buffer(xy) -> Tuple[ctypes.Array, int]:
    flat = [float(v) for p in xy for v in (p[0], p[1])]
    return (ctypes.c_double * max(len(flat), 1))(*flat), len(flat) // 2


def path_swept_angle(person: Tuple[float, float, float], xy) -> float:
    """Signed angle [rad] the bearing from the person sweeps along the path (N x 2 points),
    counter-clockwise positive (gmmrrt_path_swept_angle)."""
    buf, n = _xy_buffer(xy)
    return lib().gmmrrt_path_swept_angle(ctypes.byref(Pose(*person)), buf, n)


def path_passing_side(person: Tuple[float, float, float], xy) -> int:
    """+1 (left) / -1 (right): theta's sign at the path point closest to the person; 0 for no
    point (gmmrrt_path_passing_side)."""
    buf, n = _xy_buffer(xy)
    return lib().gmmrrt_path_passing_side(ctypes.byref(Pose(*person)), buf, n)


def features_from_xy(person: Tuple[float, float, float], x: float, y: float) -> Tuple[float, float]:
    """(d [m], theta [rad]) of the robot at (x, y) relative to person (x, y, yaw) (gmmrrt_features_from_xy)."""
    return _pair(lib().gmmrrt_features_from_xy, person, x, y)


def features_to_xy(person: Tuple[float, float, float], d: float, theta: float) -> Tuple[float, float]:
    """World (x, y) of features (d, theta) around person (gmmrrt_features_to_xy)."""
    return _pair(lib().gmmrrt_features_to_xy, person, d, theta)


def world_to_person(person: Tuple[float, float, float], x: float, y: float) -> Tuple[float, float]:
    """World point -> person frame (x', y') (gmmrrt_world_to_person)."""
    return _pair(lib().gmmrrt_world_to_person, person, x, y)


def person_to_world(person: Tuple[float, float, float], xp: float, yp: float) -> Tuple[float, float]:
    """Person frame (x', y') -> world point (gmmrrt_person_to_world)."""
    return _pair(lib().gmmrrt_person_to_world, person, xp, yp)


# ------------------------------------------------------------------ messages (msg_decode.h)

# The message types of lcmtypes/ that msg_decode.h validates, by their gmmrrt_msg_decode_<name>.
MESSAGE_TYPES = ("pose2d", "people", "nav_goal", "obstacles", "waypoints", "planner_status", "demo_info", "planar_scan",
                 "occupancy_grid")
# A decoded message is written here; larger than any generated gmmrrt_*_t struct (fixed-capacity
# arrays of a few hundred doubles), so Python does not mirror the structs' layouts.
_MSG_SCRATCH_BYTES = 1 << 20
_msg_scratch = None
# The types with a frame string (msg_decode.h): the decoder allocates it, the binding releases it.
# In the generated struct it follows the int64_t utime: a char * at offset 8.
FRAMED_TYPES = ("pose2d", "people", "nav_goal", "obstacles", "waypoints", "occupancy_grid")
MSG_WRONG_FRAME = 6  # GMMRRT_MSG_WRONG_FRAME


def validate_message(type_name: str, data: bytes, frame: Optional[str] = None) -> Tuple[int, str]:
    """(result, reason) of gmmrrt_msg_decode_<type_name> on the encoded message `data`: result 0 is
    GMMRRT_MSG_OK, else the gmmrrt_msg_result_t the daemon would count (decode failed, count over
    bound, not finite, bad value, unknown command) and a reason naming the type and field. With
    `frame`, a message of a framed type in another frame is GMMRRT_MSG_WRONG_FRAME
    (gmmrrt_msg_check_frame), as gmmrrtd judges it against its [world] frame."""
    global _msg_scratch
    if type_name not in MESSAGE_TYPES:
        raise ValueError(f"no validating decoder for message type {type_name!r}; known: {', '.join(MESSAGE_TYPES)}")
    fn = getattr(msg_lib(), "gmmrrt_msg_decode_" + type_name)
    if _msg_scratch is None:
        _msg_scratch = ctypes.create_string_buffer(_MSG_SCRATCH_BYTES)
    err = ctypes.create_string_buffer(256)
    r = fn(bytes(data), len(data), _msg_scratch, err, len(err))
    if r == 0 and type_name in FRAMED_TYPES:
        lib_ = msg_lib()
        if frame is not None:
            got = ctypes.c_void_p.from_buffer(_msg_scratch, 8).value
            r = lib_.gmmrrt_msg_check_frame((type_name + "_t").encode(), ctypes.cast(got, ctypes.c_char_p).value,
                                            frame.encode(), err, len(err))
        getattr(lib_, "gmmrrt_msg_release_" + type_name)(_msg_scratch)
    return int(r), err.value.decode(errors="replace")


# ------------------------------------------------------------------ model files (model.h)

class ModelError(ValueError):
    """A model the C core rejects; the message is the core's status and reason."""


def _status_text(st: int, err) -> str:
    return f"{lib().gmmrrt_status_str(st).decode()}: {err.value.decode(errors='replace')}"


def _darray(values):
    vals = [float(v) for v in values]
    return (ctypes.c_double * max(len(vals), 1))(*vals)


def model_from_arrays(kind: int, task: int, homotopy: int, weights, means, chols, angle_mask: int = 0,
                      delta: float = 0.001) -> ctypes.Array:
    """A prepared gmmrrt_model_t (as a ctypes buffer) from K weights, K means of D values and K
    packed lower-triangular Cholesky factors (L00, L10, L11, ...), validated by the core
    (gmmrrt_model_from_arrays). Raises ModelError with the core's reason."""
    core = lib()
    k = len(weights)
    dim = len(means[0]) if k else 0
    buf = ctypes.create_string_buffer(core.gmmrrt_model_sizeof())
    err = ctypes.create_string_buffer(256)
    st = core.gmmrrt_model_from_arrays(kind, task, homotopy, dim, k, angle_mask, float(delta), _darray(weights),
                                       _darray([v for m in means for v in m]),
                                       _darray([v for c in chols for v in c]), buf, err, len(err))
    if st != 0:
        raise ModelError("model rejected by the core (" + _status_text(st, err) + ")")
    return buf


def encode_model(model: ctypes.Array, provenance: Optional[str] = None,
                 background: Optional[ctypes.Array] = None) -> bytes:
    """The file bytes of a prepared model (gmmrrt_model_encode_file; docs/model-format.md), with a
    background section holding the prepared model `background` and a provenance trailer holding the
    text `provenance` when given."""
    core = lib()
    cap = core.gmmrrt_model_max_file_size()
    out = ctypes.create_string_buffer(cap)
    n = ctypes.c_size_t()
    err = ctypes.create_string_buffer(320)
    text = None if provenance is None else provenance.encode("utf-8")
    st = core.gmmrrt_model_encode_file(model, background, text, len(text) if text is not None else 0, out, cap,
                                       ctypes.byref(n), err, len(err))
    if st != 0:
        raise ModelError("cannot encode the model (" + _status_text(st, err) + ")")
    return out.raw[:n.value]


def save_model(path: str, model: ctypes.Array, provenance: Optional[str] = None) -> None:
    """Writes a prepared model to `path` atomically (gmmrrt_model_save_file: never a partial file),
    with a provenance trailer holding `provenance` when given (gmmrrt_model_save_file_provenance)."""
    err = ctypes.create_string_buffer(512)
    if provenance is None:
        st = lib().gmmrrt_model_save_file(os.fsencode(path), model, err, len(err))
    else:
        text = provenance.encode("utf-8")
        st = lib().gmmrrt_model_save_file_provenance(os.fsencode(path), model, text, len(text), err, len(err))
    if st != 0:
        raise ModelError(_status_text(st, err))


def model_provenance(data: bytes) -> Optional[str]:
    """The provenance text of a model file's bytes (gmmrrt_model_provenance), None when the file has
    no trailer. Checks the framing only (header, lengths, both CRC-32s); decode_model checks the rest.
    The learner's text is a JSON object (docs/learner.md); raises ModelError with the core's reason."""
    core = lib()
    text = ctypes.create_string_buffer(core.gmmrrt_model_max_file_size())
    n = ctypes.c_size_t()
    has = ctypes.c_int()
    err = ctypes.create_string_buffer(320)
    st = core.gmmrrt_model_provenance(bytes(data), len(data), text, len(text), ctypes.byref(n), ctypes.byref(has),
                                      err, len(err))
    if st != 0:
        raise ModelError("not a valid model (" + _status_text(st, err) + ")")
    return text.raw[:n.value].decode("utf-8") if has.value else None


def model_background(data: bytes) -> Optional[ctypes.Array]:
    """The background model of a model file's bytes (gmmrrt_model_background: decoded, validated and
    checked against the task model), None when the file has no background section. Raises
    ModelError with the core's reason."""
    core = lib()
    buf = ctypes.create_string_buffer(core.gmmrrt_model_sizeof())
    has = ctypes.c_int()
    err = ctypes.create_string_buffer(320)
    st = core.gmmrrt_model_background(bytes(data), len(data), buf, ctypes.byref(has), err, len(err))
    if st != 0:
        raise ModelError("not a valid model (" + _status_text(st, err) + ")")
    return buf if has.value else None


def decode_model(data: bytes) -> ctypes.Array:
    """A model file's bytes decoded and validated by the core (gmmrrt_model_decode)."""
    core = lib()
    buf = ctypes.create_string_buffer(core.gmmrrt_model_sizeof())
    err = ctypes.create_string_buffer(256)
    st = core.gmmrrt_model_decode(bytes(data), len(data), buf, err, len(err))
    if st != 0:
        raise ModelError("not a valid model (" + _status_text(st, err) + ")")
    return buf


def model_fields(model: ctypes.Array) -> dict:
    """The stored fields of a decoded or prepared model (gmmrrt_model_to_arrays): kind, task,
    homotopy, dim, k, angle_mask, delta, weights [K], means [K][D], chols [K][D(D+1)/2]."""
    core = lib()
    head = (ctypes.c_int32 * 6)()
    delta = ctypes.c_double()
    # The sizes of the largest model limits.h may allow (D <= 16, K <= 1024).
    w, m, c = (ctypes.c_double * 1024)(), (ctypes.c_double * (1024 * 16))(), (ctypes.c_double * (1024 * 136))()
    core.gmmrrt_model_to_arrays(model, head, ctypes.byref(delta), w, m, c)
    kind, task, homotopy, dim, k, mask = (int(v) for v in head)
    tri = dim * (dim + 1) // 2
    return {"kind": kind, "task": task, "homotopy": homotopy, "dim": dim, "k": k, "angle_mask": mask & 0xFFFFFFFF,
            "delta": delta.value, "weights": list(w[:k]),
            "means": [list(m[i * dim:(i + 1) * dim]) for i in range(k)],
            "chols": [list(c[i * tri:(i + 1) * tri]) for i in range(k)]}


__all__ = ["CoreNotBuilt", "Pose", "lib", "msg_lib", "wrap_angle", "features_from_xy", "features_to_xy",
           "world_to_person", "person_to_world", "MESSAGE_TYPES", "validate_message", "ModelError",
           "model_from_arrays", "encode_model", "save_model", "decode_model", "model_fields", "model_provenance"]
