"""ctypes access to a learned model file through the C core: decode (model.h) and density (gmm.h, eq. (1)).

Used for plots only (the mixture's density in the person's frame). The file is decoded and validated
by gmmrrt_model_decode, the one reader of the format (docs/model-format.md), and evaluated by
gmmrrt_gmm_density, the planner's own code, so a plot shows exactly what the planner uses.
"""
from __future__ import annotations

import ctypes
from pathlib import Path

import numpy as np

from gmmrrt_tools import core

# The decoded model lives in a caller buffer larger than any gmmrrt_model_t the limits allow
# (K <= 1024, D <= 16: under 2.5 MB), so Python never needs the struct's exact size.
_MODEL_BUFFER_BYTES = 8 << 20
_KIND_NAMES = {1: "features", 2: "xy", 3: "generic"}


def _bind():
    lib = core.lib()
    if not hasattr(lib, "gmmrrt_model_decode"):
        raise core.CoreNotBuilt("libgmmrrt.so has no gmmrrt_model_decode: rebuild with the mixture core")
    lib.gmmrrt_model_decode.argtypes = [ctypes.c_char_p, ctypes.c_size_t, ctypes.c_void_p, ctypes.c_char_p,
                                        ctypes.c_size_t]
    lib.gmmrrt_model_decode.restype = ctypes.c_int
    lib.gmmrrt_gmm_density.argtypes = [ctypes.c_void_p, ctypes.POINTER(ctypes.c_double)]
    lib.gmmrrt_gmm_density.restype = ctypes.c_double
    lib.gmmrrt_status_str.argtypes = [ctypes.c_int]
    lib.gmmrrt_status_str.restype = ctypes.c_char_p
    return lib


class Model:
    """A decoded model file. kind: 'features' (d, theta) | 'xy' (s, x', y') | 'generic'."""

    def __init__(self, path: str):
        lib = _bind()
        data = Path(path).read_bytes()
        self._buf = ctypes.create_string_buffer(_MODEL_BUFFER_BYTES)
        err = ctypes.create_string_buffer(256)
        st = lib.gmmrrt_model_decode(data, len(data), self._buf, err, len(err))
        if st != 0:
            raise ValueError(f"{path}: not a valid model ({lib.gmmrrt_status_str(st).decode()}: "
                             f"{err.value.decode(errors='replace')})")
        head = np.frombuffer(self._buf.raw[:20], dtype=np.int32)  # kind, task, homotopy, dim, k
        self.kind = _KIND_NAMES.get(int(head[0]), str(int(head[0])))
        self.task, self.homotopy, self.dim, self.k = (int(v) for v in head[1:5])
        self._lib = lib

    def density(self, f) -> np.ndarray:
        """p(f) for each row of f (N x dim)."""
        arr = np.ascontiguousarray(np.atleast_2d(np.asarray(f, dtype=float)))
        if arr.shape[1] != self.dim:
            raise ValueError(f"model has dimension {self.dim}, got points of dimension {arr.shape[1]}")
        out = np.empty(arr.shape[0])
        row = (ctypes.c_double * self.dim)()
        for i, r in enumerate(arr):
            row[:] = r.tolist()
            out[i] = self._lib.gmmrrt_gmm_density(self._buf, row)
        return out

    def density_person_frame(self, xs, ys) -> np.ndarray:
        """Density of a features model on a grid of person-frame points (person at origin facing +x):
        f = (d, theta) of each point from the C features. Shape (len(ys), len(xs))."""
        if self.kind != "features":
            raise ValueError(f"density_person_frame needs a features model, this one is {self.kind}")
        pts = [core.features_from_xy((0.0, 0.0, 0.0), x, y) for y in ys for x in xs]
        return self.density(pts).reshape(len(ys), len(xs))


__all__ = ["Model"]
