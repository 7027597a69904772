"""ctypes binding to the gmmrrt C core (build/lib/libgmmrrt.so): one definition of the features.

The library is looked up in $GMMRRT_BUILD_DIR/lib, then <repo>/build/lib. Build it with `tools/run build`.
"""
from __future__ import annotations

import ctypes
import math
import os
from pathlib import Path
from typing import Tuple

_REPO = Path(__file__).resolve().parents[2]


class CoreNotBuilt(RuntimeError):
    """libgmmrrt.so was not found: run `tools/run build` first."""


class Pose(ctypes.Structure):
    """gmmrrt_pose_t: x, y [m], yaw [rad]."""

    _fields_ = [("x", ctypes.c_double), ("y", ctypes.c_double), ("yaw", ctypes.c_double)]


def _candidates():
    env = os.environ.get("GMMRRT_BUILD_DIR")
    if env:
        yield Path(env) / "lib" / "libgmmrrt.so"
    yield _REPO / "build" / "lib" / "libgmmrrt.so"


_lib = None


def lib() -> ctypes.CDLL:
    """The loaded core library (loaded once)."""
    global _lib
    if _lib is None:
        for path in _candidates():
            if path.is_file():
                _lib = ctypes.CDLL(str(path))
                break
        else:
            raise CoreNotBuilt(
                "libgmmrrt.so not found in " + ", ".join(str(p) for p in _candidates())
                + ": run `tools/run build` (or set GMMRRT_BUILD_DIR)")
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
        _lib.gmmrrt_approach_direction_name.argtypes = [ctypes.c_int32]
        _lib.gmmrrt_approach_direction_name.restype = ctypes.c_char_p
    return _lib


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


__all__ = ["CoreNotBuilt", "Pose", "lib", "wrap_angle", "features_from_xy", "features_to_xy",
           "world_to_person", "person_to_world"]
