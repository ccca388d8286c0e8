"""Array helpers shared by several physics modules (private).

The modules import them under short private names (``_out``, ``_finite``).
"""

from __future__ import annotations

import math

import numpy as np


def scalar_or_array(value):
    """Return a Python float for 0-d results so scalars stay scalars."""
    arr = np.asarray(value, dtype=float)
    return float(arr) if arr.ndim == 0 else arr


def finite(value, label, unit):
    """``value`` as a float array; ValueError naming ``label`` and ``unit`` if not finite."""
    arr = np.asarray(value, dtype=float)
    if not (math.isfinite(float(arr)) if arr.ndim == 0 else bool(np.all(np.isfinite(arr)))):
        raise ValueError(f"{label} must be finite {unit}, got {value!r}")
    return arr
