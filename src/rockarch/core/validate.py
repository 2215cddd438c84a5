"""Input checks shared by every module: one clear ValueError message per bad input."""

from __future__ import annotations

import math

import numpy as np


def positive(name: str, value: float) -> float:
    """Return ``value`` as float if it is finite and > 0, else raise ValueError."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(v) or v <= 0.0:
        raise ValueError(f"{name} must be a finite number > 0, got {value!r}")
    return v


#: Largest frequency parameter p [1/s] accepted: a rigid block of half-diagonal
#: R = 3g/(4p²) ≈ 74 nm; larger values only overflow (p² and the step count p·t/h).
P_MAX = 1e4


def frequency(name: str, value: float) -> float:
    """Return a frequency parameter p as float if 0 < p ≤ :data:`P_MAX`, else ValueError."""
    return in_range(name, value, 0.0, P_MAX, lo_open=True)


def in_range(name: str, value: float, lo: float, hi: float, *, lo_open: bool = False,
             hi_open: bool = False) -> float:
    """Return ``value`` as float if it lies in the interval [lo, hi] (open ends on request)."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {value!r}") from None
    bad = (not math.isfinite(v) or (v <= lo if lo_open else v < lo)
           or (v >= hi if hi_open else v > hi))
    if bad:
        left = "(" if lo_open else "["
        right = ")" if hi_open else "]"
        raise ValueError(f"{name} must lie in {left}{lo:g}, {hi:g}{right}, got {value!r}")
    return v


def finite_array(name: str, values, *, ndim: int = 1, min_len: int = 1) -> np.ndarray:
    """Return ``values`` as a float64 array of the given ndim with only finite entries."""
    arr = np.asarray(values, dtype=float)
    if arr.ndim != ndim:
        raise ValueError(f"{name} must be a {ndim}-D array, got shape {arr.shape}")
    if arr.shape[0] < min_len:
        raise ValueError(f"{name} needs at least {min_len} values, got {arr.shape[0]}")
    if not np.all(np.isfinite(arr)):
        bad = int(np.flatnonzero(~np.isfinite(arr.ravel()))[0])
        raise ValueError(f"{name} contains a non-finite value (NaN or inf) at index {bad}")
    return arr
