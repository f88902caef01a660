"""Input checks shared by the core: every error names the parameter and the allowed range."""

from __future__ import annotations

import math

import numpy as np

_NOT_NUMBERS = (bool, np.bool_, str, bytes)


def numeric(value, name: str, what: str = "a number"):
    """Refuse booleans and strings where a number (or an array of numbers) is expected.

    numpy turns ``True`` into 1.0 and ``"1"`` into 1.0 without a word, so ``mass=True`` or
    ``step("0.1")`` would otherwise run with a value the user never wrote as a number."""
    if isinstance(value, _NOT_NUMBERS):
        raise ValueError(f"{name} must be {what}, got {type(value).__name__} {value!r}")
    if isinstance(value, np.ndarray):
        if value.dtype.kind in "bSUO":
            raise ValueError(f"{name} must be {what}, got an array of {value.dtype}")
    elif isinstance(value, (list, tuple)):
        flat = np.asarray(value, dtype=object).reshape(-1)
        if any(isinstance(v, _NOT_NUMBERS) for v in flat):
            raise ValueError(f"{name} must be {what}, got {value!r}")
    return value


def vec3(value, name: str) -> np.ndarray:
    """A finite 3-vector as float64, or a ValueError naming ``name``."""
    numeric(value, name, "a 3-vector of finite numbers")
    try:
        arr = np.asarray(value, dtype=np.float64).reshape(3)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a 3-vector of finite numbers, got {value!r}") from None
    if not np.isfinite(arr).all():
        raise ValueError(f"{name} must be finite, got {tuple(arr.tolist())}")
    return arr


def vec3_array(value, name: str, count: int | None = None) -> np.ndarray:
    """Finite vectors of shape (count, 3) (a single vector broadcasts)."""
    numeric(value, name, "an array of 3-vectors")
    try:
        arr = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be an array of 3-vectors, got {value!r}") from None
    if arr.ndim == 1 and arr.shape == (3,) and count is not None:
        arr = np.broadcast_to(arr, (count, 3))
    if arr.ndim != 2 or arr.shape[1] != 3 or (count is not None and arr.shape[0] != count):
        want = f"({count}, 3)" if count is not None else "(N, 3)"
        raise ValueError(f"{name} must have shape {want}, got {arr.shape}")
    if not np.isfinite(arr).all():
        bad = int(np.flatnonzero(~np.isfinite(arr).all(axis=1))[0])
        raise ValueError(f"{name} must be finite; row {bad} is {tuple(arr[bad].tolist())}")
    return np.ascontiguousarray(arr)


def scalar_array(value, name: str, count: int, *, low: float = -math.inf, high: float = math.inf,
                 low_open: bool = False, high_open: bool = False) -> np.ndarray:
    """Finite scalars of shape (count,) inside [low, high] (or open ends); one value broadcasts."""
    numeric(value, name, "a number or an array of numbers")
    try:
        arr = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number or an array of numbers, got {value!r}") from None
    if arr.ndim == 0:
        arr = np.full(count, float(arr))
    if arr.shape != (count,):
        raise ValueError(f"{name} must be a number or have shape ({count},), got {arr.shape}")
    lo_ok = arr > low if low_open else arr >= low
    hi_ok = arr < high if high_open else arr <= high
    ok = np.isfinite(arr) & lo_ok & hi_ok
    if not ok.all():
        bad = float(arr[np.flatnonzero(~ok)[0]])
        allowed = _range_text(low, high, low_open, high_open)
        raise ValueError(f"{name} must be in {allowed}, got {bad}")
    return np.ascontiguousarray(arr)


def scalar(value, name: str, *, low: float = -math.inf, high: float = math.inf,
           low_open: bool = False, high_open: bool = False) -> float:
    """One finite float inside [low, high] (or open ends)."""
    if np.ndim(value) != 0:
        raise ValueError(f"{name} must be a single number, got {value!r}")
    return float(scalar_array(value, name, 1, low=low, high=high,
                              low_open=low_open, high_open=high_open)[0])


def indices(value, name: str, count: int) -> np.ndarray:
    """Particle indices as int64, each in [0, count)."""
    arr = np.asarray(value)
    if arr.dtype == bool or not (np.issubdtype(arr.dtype, np.integer) or arr.size == 0):
        raise ValueError(f"{name} must be particle indices (integers), got {value!r}")
    arr = np.ascontiguousarray(arr.astype(np.int64).reshape(-1))
    if arr.size and (arr.min() < 0 or arr.max() >= count):
        bad = int(arr[(arr < 0) | (arr >= count)][0])
        raise IndexError(f"{name}: {bad} is not a particle; indices must be in [0, {count - 1}]"
                         if count else f"{name}: {bad} is not a particle; the world has none yet")
    return arr


def _range_text(low, high, low_open, high_open) -> str:
    left = "(" if low_open else "["
    right = ")" if high_open else "]"
    lo = "-inf" if low == -math.inf else f"{low:g}"
    hi = "inf" if high == math.inf else f"{high:g}"
    return f"{left}{lo}, {hi}{right}"
