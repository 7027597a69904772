"""ctypes binding to the gmmrrt C libraries: one definition of each rule, in C.

- build/lib/libgmmrrt.so (planner/src + planner/io): the features (d, theta), angle wrapping,
  the mixture, the model file format (gmmrrt_model_encode/decode, atomic gmmrrt_model_save_file);
- build/lib/libgmmrrt_msg.so (lcmtypes/msg_decode.c): the validating message decoders that gmmrrtd
  uses, so a Python check judges a message exactly as the daemon does.

The libraries are looked up in $GMMRRT_BUILD_DIR/lib, then <repo>/build/lib. Build them with
`tools/run build`.
"""
from __future__ import annotations

import ctypes
import math
import os
from pathlib import Path
from typing import Optional, Tuple

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
        _lib.gmmrrt_approach_direction_name.argtypes = [ctypes.c_int32]
        _lib.gmmrrt_approach_direction_name.restype = ctypes.c_char_p
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


def wrap_angle(a: float) -> float:
    """Angle wrapped to (-pi, pi] (gmmrrt_wrap_angle)."""
    return lib().gmmrrt_wrap_angle(float(a))


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


def encode_model(model: ctypes.Array, provenance: Optional[str] = None) -> bytes:
    """The file bytes of a prepared model (gmmrrt_model_encode; docs/model-format.md), with a
    provenance trailer holding the text `provenance` when given (gmmrrt_model_encode_provenance)."""
    core = lib()
    cap = core.gmmrrt_model_max_file_size()
    out = ctypes.create_string_buffer(cap)
    n = ctypes.c_size_t()
    err = ctypes.create_string_buffer(256)
    if provenance is None:
        st = core.gmmrrt_model_encode(model, out, cap, ctypes.byref(n), err, len(err))
    else:
        text = provenance.encode("utf-8")
        st = core.gmmrrt_model_encode_provenance(model, text, len(text), out, cap, ctypes.byref(n), err, len(err))
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
