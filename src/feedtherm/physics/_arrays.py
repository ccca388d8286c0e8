"""Array helpers shared by several physics modules (private).

The modules import them under short private names (``_out``, ``_finite``).
"""

from __future__ import annotations

import math

import numpy as np


#: The scalar types a physics function takes without numpy (``type(x) in FLOATS``: a boundary-condition
#: evaluation calls the checks thousands of times, where a 0-d array's reductions cost several times more).
FLOATS = (float, np.float64)


def scalar_or_array(value):
    """Return a Python float for 0-d results so scalars stay scalars."""
    if type(value) is float:
        return value
    if type(value) is np.float64:
        return float(value)
    arr = np.asarray(value, dtype=float)
    return float(arr) if arr.ndim == 0 else arr


def finite(value, label, unit):
    """``value`` as floats (a Python float for a float, else an array); ValueError naming ``label`` and
    ``unit`` if not finite."""
    if type(value) in FLOATS:
        if not math.isfinite(value):
            raise ValueError(f"{label} must be finite {unit}, got {value!r}")
        return float(value)
    arr = np.asarray(value, dtype=float)
    if not (math.isfinite(float(arr)) if arr.ndim == 0 else bool(np.all(np.isfinite(arr)))):
        raise ValueError(f"{label} must be finite {unit}, got {value!r}")
    return arr


def any_true(condition) -> bool:
    """``numpy.any(condition)`` as a bool, without numpy's reduction for a scalar condition."""
    if type(condition) is bool or type(condition) is np.bool_:
        return bool(condition)
    return bool(np.any(condition))
