"""Fit and use gmmrrt mixtures from Python, with a scikit-learn-like surface, over the C API of the
learner (learner/capi/gmmrrt_learn.h, build/lib/libgmmrrt_learn.so, ctypes).

    from gmmrrt_tools.learn import GaussianMixture
    gm = GaussianMixture(n_components=19, random_state=1).fit(X)      # X: n x d
    gm.score_samples(X); gm.score(X); gm.bic(X); gm.sample(1000)
    gm.save("m.gmm"); GaussianMixture.load("m.gmm")                   # the gmmrrt-learn file format

The fit is the learner's FitMixture (k-means++ candidates, SQUAREM-accelerated EM, the same result
for the same seed on any thread count), the density the C core's gmmrrt_gmm_log_density (wrapped
normal on angle dimensions), sampling gmmrrt_gmm_sample, the file format model.c: nothing is
computed twice. Attributes after fit/load: weights_ (K), means_ (K x d), covariances_ (K x d x d),
n_iter_, converged_, lower_bound_ (mean log-likelihood per training point); after load also
provenance_ (what the file says it was learned from, docs/learner.md "Provenance").
"""
from __future__ import annotations

import ctypes
import json
import math
import os
from pathlib import Path
from typing import Optional, Tuple

import numpy as np

_REPO = Path(__file__).resolve().parents[2]


class LearnerNotBuilt(RuntimeError):
    """libgmmrrt_learn.so was not found: run `tools/run build` first."""


class _Options(ctypes.Structure):
    _fields_ = [("k", ctypes.c_int32), ("seed", ctypes.c_uint64), ("threads", ctypes.c_int32),
                ("max_iter", ctypes.c_int32), ("tol", ctypes.c_double), ("restarts", ctypes.c_int32),
                ("accelerate", ctypes.c_int32)]


class _Summary(ctypes.Structure):
    _fields_ = [("mean_log_likelihood", ctypes.c_double), ("bic", ctypes.c_double), ("iterations", ctypes.c_int32),
                ("converged", ctypes.c_int32), ("k_final", ctypes.c_int32)]


_lib = None


def _load_lib() -> ctypes.CDLL:
    global _lib
    if _lib is not None:
        return _lib
    dirs = ([Path(os.environ["GMMRRT_BUILD_DIR"]) / "lib"] if os.environ.get("GMMRRT_BUILD_DIR") else []) + \
        [_REPO / "build" / "lib"]
    for d in dirs:
        if (d / "libgmmrrt_learn.so").is_file():
            lib = ctypes.CDLL(str(d / "libgmmrrt_learn.so"))
            break
    else:
        raise LearnerNotBuilt(f"libgmmrrt_learn.so not found in {', '.join(map(str, dirs))}: run `tools/run build`")
    pd, vp, err = ctypes.POINTER(ctypes.c_double), ctypes.c_void_p, ctypes.c_char_p
    lib.gmmrrt_learn_options_default.restype = _Options
    lib.gmmrrt_learn_fit.argtypes = [pd, ctypes.c_int64, ctypes.c_int32, ctypes.c_uint32, ctypes.POINTER(_Options),
                                     ctypes.POINTER(vp), ctypes.POINTER(_Summary), err, ctypes.c_size_t]
    lib.gmmrrt_learn_load.argtypes = [ctypes.c_char_p, ctypes.POINTER(vp), err, ctypes.c_size_t]
    lib.gmmrrt_learn_save.argtypes = [vp, ctypes.c_char_p, err, ctypes.c_size_t]
    lib.gmmrrt_learn_free.argtypes = [vp]
    lib.gmmrrt_learn_free.restype = None
    for f in ("gmmrrt_learn_dim", "gmmrrt_learn_k"):
        getattr(lib, f).argtypes = [vp]
        getattr(lib, f).restype = ctypes.c_int32
    lib.gmmrrt_learn_angle_mask.argtypes = [vp]
    lib.gmmrrt_learn_angle_mask.restype = ctypes.c_uint32
    lib.gmmrrt_learn_component.argtypes = [vp, ctypes.c_int32, pd, pd, pd]
    lib.gmmrrt_learn_log_density.argtypes = [vp, pd, ctypes.c_int64, pd]
    lib.gmmrrt_learn_sample.argtypes = [vp, ctypes.c_uint64, ctypes.c_int64, pd, ctypes.POINTER(ctypes.c_int32)]
    _lib = lib
    return lib


def _ptr(a: np.ndarray):
    return a.ctypes.data_as(ctypes.POINTER(ctypes.c_double))


class GaussianMixture:
    """A mixture fitted by gmmrrt's learner. n_components: K; random_state: the seed (an int);
    angle_dims: 0-based dimensions that are wrapped angles [rad]; n_threads: 0 = all cores;
    tol / max_iter / n_init (candidate starts) / accelerate: as `gmmrrt-learn fit`'s --tol,
    --max-iter, --restarts, --accel (their defaults when None)."""

    def __init__(self, n_components: int = 19, random_state: int = 1, angle_dims: Tuple[int, ...] = (),
                 tol: Optional[float] = None, max_iter: Optional[int] = None, n_init: Optional[int] = None,
                 n_threads: int = 0, accelerate: bool = True):
        self.n_components, self.random_state, self.angle_dims = n_components, random_state, tuple(angle_dims)
        self.tol, self.max_iter, self.n_init, self.n_threads, self.accelerate = tol, max_iter, n_init, n_threads, accelerate
        self._handle = None

    # ---------------------------------------------------------------- fitting and files
    def fit(self, X) -> "GaussianMixture":
        lib = _load_lib()
        x = np.ascontiguousarray(np.asarray(X, dtype=float))
        if x.ndim != 2:
            raise ValueError(f"X must be 2-D (n x d), got shape {x.shape}")
        if not isinstance(self.random_state, (int, np.integer)) or self.random_state < 0:
            raise ValueError("random_state must be a non-negative int (the learner's seed)")
        o = lib.gmmrrt_learn_options_default()
        o.k, o.seed, o.threads, o.accelerate = self.n_components, int(self.random_state), self.n_threads, int(self.accelerate)
        if self.tol is not None:
            o.tol = self.tol
        if self.max_iter is not None:
            o.max_iter = self.max_iter
        if self.n_init is not None:
            o.restarts = self.n_init
        mask = 0
        for j in self.angle_dims:
            if not 0 <= j < x.shape[1]:
                raise ValueError(f"angle dimension {j} outside 0..{x.shape[1] - 1}")
            mask |= 1 << j
        handle, summary = ctypes.c_void_p(), _Summary()
        err = ctypes.create_string_buffer(512)
        st = lib.gmmrrt_learn_fit(_ptr(x), x.shape[0], x.shape[1], mask, ctypes.byref(o), ctypes.byref(handle),
                                  ctypes.byref(summary), err, len(err))
        if st != 0:
            raise ValueError(f"fit failed: {err.value.decode(errors='replace')}")
        self._set_handle(handle)
        self.provenance_text_ = self.provenance_ = None  # a Python fit records none (save writes none)
        self.n_iter_, self.converged_ = int(summary.iterations), bool(summary.converged)
        self.lower_bound_ = float(summary.mean_log_likelihood)
        return self

    def save(self, path) -> None:
        """Writes the model file (atomically; the format gmmrrt-learn and the planner read)."""
        err = ctypes.create_string_buffer(512)
        st = _load_lib().gmmrrt_learn_save(self._need(), str(path).encode(), err, len(err))
        if st != 0:
            raise OSError(err.value.decode(errors="replace"))

    @classmethod
    def load(cls, path) -> "GaussianMixture":
        """A model file, validated by the C loader (a corrupt file raises ValueError).

        provenance_text_: the file's provenance trailer as the C core reads it
        (core.model_provenance, gmmrrt_model_provenance), None for a file without one;
        provenance_: that text parsed as JSON (the object `gmmrrt-learn fit` writes: data_sha256,
        command_line, seed, k, bic, ...), None without a trailer; a trailer that is not a JSON
        object raises ValueError naming the file."""
        from gmmrrt_tools import core

        lib = _load_lib()
        handle = ctypes.c_void_p()
        err = ctypes.create_string_buffer(512)
        st = lib.gmmrrt_learn_load(str(path).encode(), ctypes.byref(handle), err, len(err))
        if st != 0:
            raise ValueError(err.value.decode(errors="replace"))
        gm = cls(n_components=lib.gmmrrt_learn_k(handle))
        gm._set_handle(handle)
        try:
            gm.provenance_text_ = core.model_provenance(Path(path).read_bytes())
        except (OSError, core.ModelError) as e:  # the file changed after the C loader read it
            raise ValueError(f"{path}: {e}") from None
        gm.provenance_ = None
        if gm.provenance_text_ is not None:
            try:
                gm.provenance_ = json.loads(gm.provenance_text_)
            except json.JSONDecodeError as e:
                raise ValueError(f"{path}: the provenance trailer is not JSON ({e})") from None
            if not isinstance(gm.provenance_, dict):
                raise ValueError(f"{path}: the provenance trailer is not a JSON object")
        mask = lib.gmmrrt_learn_angle_mask(handle)
        gm.angle_dims = tuple(j for j in range(gm.means_.shape[1]) if (mask >> j) & 1)
        return gm

    # ---------------------------------------------------------------- using the model
    def score_samples(self, X) -> np.ndarray:
        """log p(x) per row of X."""
        handle = self._need()
        x = self._points(X)
        out = np.empty(x.shape[0])
        _load_lib().gmmrrt_learn_log_density(handle, _ptr(x), x.shape[0], _ptr(out))
        return out

    def score(self, X) -> float:
        """Mean log-likelihood per point."""
        return float(np.mean(self.score_samples(X)))

    def _n_parameters(self) -> int:
        k, d = self.means_.shape
        return (k - 1) + k * d + k * d * (d + 1) // 2

    def bic(self, X) -> float:
        """-2 log L + p ln N (lower is better), as the learner's BIC sweep and scikit-learn compute it."""
        x = self._points(X)
        return float(-2.0 * np.sum(self.score_samples(x)) + self._n_parameters() * math.log(x.shape[0]))

    def aic(self, X) -> float:
        return float(-2.0 * np.sum(self.score_samples(X)) + 2 * self._n_parameters())

    def sample(self, n_samples: int = 1, random_state: int = 0) -> Tuple[np.ndarray, np.ndarray]:
        """(X, labels): n_samples draws by the C core's sampler (angles wrapped), seeded."""
        d = self.means_.shape[1]
        out = np.empty((int(n_samples), d))
        labels = np.empty(int(n_samples), dtype=np.int32)
        _load_lib().gmmrrt_learn_sample(self._need(), int(random_state), int(n_samples), _ptr(out),
                                        labels.ctypes.data_as(ctypes.POINTER(ctypes.c_int32)))
        return out, labels

    # ---------------------------------------------------------------- internals
    def _need(self):
        if self._handle is None:
            raise RuntimeError("not fitted: call fit() or load() first")
        return self._handle

    def _points(self, X) -> np.ndarray:
        x = np.ascontiguousarray(np.atleast_2d(np.asarray(X, dtype=float)))
        if x.shape[1] != self.means_.shape[1]:
            raise ValueError(f"model has dimension {self.means_.shape[1]}, got points of dimension {x.shape[1]}")
        return x

    def _set_handle(self, handle) -> None:
        lib = _load_lib()
        if self._handle is not None:
            lib.gmmrrt_learn_free(self._handle)
        self._handle = handle
        k, d = lib.gmmrrt_learn_k(handle), lib.gmmrrt_learn_dim(handle)
        self.weights_, self.means_, self.covariances_ = np.empty(k), np.empty((k, d)), np.empty((k, d, d))
        w = ctypes.c_double()
        for i in range(k):
            mean, cov = np.empty(d), np.empty((d, d))
            lib.gmmrrt_learn_component(handle, i, ctypes.byref(w), _ptr(mean), _ptr(cov))
            self.weights_[i], self.means_[i], self.covariances_[i] = w.value, mean, cov

    def __del__(self):
        if getattr(self, "_handle", None) is not None and _lib is not None:
            _lib.gmmrrt_learn_free(self._handle)
            self._handle = None
