"""Input checks shared by every module: one clear ValueError message per bad input."""

from __future__ import annotations

import math

import numpy as np


def show(value) -> str:
    """A value as a message shows it: plain numbers (no ``np.float64(...)``), sequences of
    them as ``(0.3, 1)``, text cut at 60 characters."""
    if isinstance(value, (bool, np.bool_)):
        return str(bool(value))
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        return f"{float(value):g}"
    if isinstance(value, (tuple, list, np.ndarray)) and np.ndim(value) == 1 and len(value) < 20:
        inner = ", ".join(show(v) for v in value)
        text = f"[{inner}]" if isinstance(value, list) else f"({inner})"
    else:
        text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


_show = show


def _kind(value) -> str:
    return type(value).__name__


def _what(value) -> str:
    """A wrong value as a message names it: its type and the value (``None`` alone)."""
    return "None" if value is None else f"{_kind(value)} {_show(value)}"


def number(name: str, value) -> float:
    """Return a real number ``value`` as float; TypeError naming ``name`` for anything else
    (a bool, a string, a list, None: ``alpha=True`` is not 1 rad, ``ratio=[2, 3]`` is not
    one ratio)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer,
                                                                      np.floating)):
        if isinstance(value, np.ndarray) and value.ndim == 0 and value.dtype.kind in "iuf":
            return float(value)
        raise TypeError(f"{name} must be a number, got {_what(value)}")
    return float(value)


def numbers(name: str, values) -> np.ndarray:
    """``values`` (a number or an array of them) as a float array; TypeError naming
    ``name`` for None, text (``"1,2"`` is not two numbers) or booleans."""
    if values is None or isinstance(values, (str, bytes, bool, np.bool_)):
        raise TypeError(f"{name} must be a number or an array of numbers, got {_what(values)}")
    try:
        arr = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be a number or an array of numbers, got "
                        f"{_kind(values)}") from None
    kind = np.asarray(values).dtype.kind
    if kind not in "iuf":
        raise TypeError(f"{name} must hold numbers, got {'booleans' if kind == 'b' else kind}")
    return arr


def integer(name: str, value) -> int:
    """Return a whole number ``value`` as int (an int, or a float such as 20.0); TypeError
    naming ``name`` for a bool, a fraction (``blocks=20.9`` is not 20) or a non-number."""
    if isinstance(value, (int, np.integer)) and not isinstance(value, (bool, np.bool_)):
        return int(value)
    v = number(name, value)
    if not (math.isfinite(v) and v.is_integer()):
        raise TypeError(f"{name} must be a whole number, got {_show(value)}")
    return int(v)


def positive(name: str, value: float) -> float:
    """Return ``value`` as float if it is finite and > 0, else raise ValueError (TypeError
    if it is not a number)."""
    v = number(name, value)
    if not math.isfinite(v) or v <= 0.0:
        raise ValueError(f"{name} must be a finite number > 0, got {_show(value)}")
    return v


#: Largest frequency parameter p [1/s] accepted: a rigid block of half-diagonal
#: R = 3g/(4p²) ≈ 74 nm; larger values only overflow (p² and the step count p·t/h).
P_MAX = 1e4


#: Smallest frequency parameter p [1/s] accepted: a rigid block of half-diagonal
#: R = 3g/(4p²) ≈ 7000 km; smaller values only underflow the OAS grids.
P_MIN = 1e-3
#: Largest ratio ap/ap,min accepted (a motion a million times the one that starts rocking:
#: beyond it only the products overflow).
RATIO_MAX = 1e6


def frequency(name: str, value: float) -> float:
    """Return a frequency parameter p as float if :data:`P_MIN` <= p <= :data:`P_MAX`, else
    ValueError."""
    return in_range(name, value, P_MIN, P_MAX)


#: Smallest bisection tolerance of an OAS boundary (ratio units) other than 0 (no
#: bisection): each halving is a sweep of the p values (about 42 rounds from a ratio step of
#: 5 to 1e-12, a few thousand ulps of a ratio near 1); 1e-300 would be ~1000 rounds.
TOL_MIN = 1e-12


def tolerance(name: str, value) -> float:
    """A boundary tolerance: 0 (no bisection) or in [:data:`TOL_MIN`, 1e3]."""
    v = number(name, value)
    if v != 0.0:
        in_range(name, v, TOL_MIN, 1e3)
    return v


def ratio_value(name: str, value) -> float:
    """A ratio ap/ap,min in (0, :data:`RATIO_MAX`] (TypeError for a non-number): 0 is no
    ground motion at all."""
    return in_range(name, value, 0.0, RATIO_MAX, lo_open=True)


def in_range(name: str, value: float, lo: float, hi: float, *, lo_open: bool = False,
             hi_open: bool = False) -> float:
    """Return ``value`` as float if it lies in the interval [lo, hi] (open ends on request);
    ValueError outside it, TypeError if it is not a number."""
    v = number(name, value)
    bad = (not math.isfinite(v) or (v <= lo if lo_open else v < lo)
           or (v >= hi if hi_open else v > hi))
    if bad:
        left = "(" if lo_open else "["
        right = ")" if hi_open else "]"
        raise ValueError(f"{name} must lie in {left}{lo:g}, {hi:g}{right}, got {_show(value)}")
    return v


def finite_array(name: str, values, *, ndim: int = 1, min_len: int = 1) -> np.ndarray:
    """Return ``values`` as a float64 array of the given ndim with only finite entries
    (TypeError naming ``name`` if they are not numbers)."""
    if isinstance(values, (str, bytes, dict)) or values is None:
        raise TypeError(f"{name} must be an array of numbers, got {_what(values)}")
    try:
        arr = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be an array of numbers, got {_show(values)}") from None
    if np.asarray(values).dtype.kind == "b":
        raise TypeError(f"{name} must be an array of numbers, not of booleans")
    if arr.ndim != ndim:
        raise ValueError(f"{name} must be a {ndim}-D array, got shape {arr.shape}")
    if arr.shape[0] < min_len:
        raise ValueError(f"{name} needs at least {min_len} values, got {arr.shape[0]}")
    if not np.all(np.isfinite(arr)):
        bad = int(np.flatnonzero(~np.isfinite(arr.ravel()))[0])
        raise ValueError(f"{name} contains a non-finite value (NaN or inf) at index {bad}")
    return arr
