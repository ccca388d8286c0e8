"""Argument checks shared by the physics modules of one model (private).

Two families, each with its own messages and semantics:

- screw–nut (:mod:`~feedtherm.physics.screw_nut_rolling` and
  :mod:`~feedtherm.physics.screw_nut`): :func:`positive`, :func:`nonnegative` (no
  finiteness check: ``inf`` passes, ``nan`` fails) and :func:`coulomb_mu`;
- convection (:mod:`~feedtherm.physics.dimensionless`,
  :mod:`~feedtherm.physics.natural_convection`,
  :mod:`~feedtherm.physics.forced_convection`, :mod:`~feedtherm.physics.convection`):
  :func:`finite_array`, :func:`absolute_temperature` and :func:`check_range_nonzero`.

The modules import them under short private names (``_positive``, ``_arr`` …).
"""

from __future__ import annotations

import math

import numpy as np

from feedtherm.physics._arrays import FLOATS
from feedtherm.physics.validity import check_range

_MIN_MU = float(np.nextafter(0.0, 1.0))  # 0, exclusive


# ------------------------------------------------------------------------- screw–nut
def positive(name: str, value) -> np.ndarray:
    arr = np.asarray(value, dtype=float)
    if not np.all(arr > 0.0):
        raise ValueError(f"{name} must be positive (got {value!r})")
    return arr


def nonnegative(name: str, value) -> np.ndarray:
    arr = np.asarray(value, dtype=float)
    if not np.all(arr >= 0.0):
        raise ValueError(f"{name} must not be negative (got {value!r})")
    return arr


def coulomb_mu(correlation: str, mu) -> np.ndarray:
    """Coulomb coefficient: negative raises, outside (0, 0.5] warns."""
    mu = nonnegative("mu", mu)
    check_range(correlation, "mu", mu, _MIN_MU, 0.5)
    return mu


# ------------------------------------------------------------------------ convection
def finite_array(x, name, *, positive=False):
    """``x`` as floats, finite and ≥ 0 (> 0 with ``positive``); ValueError naming ``name`` otherwise.

    A Python or NumPy float comes back as a Python float (the common call inside a boundary-condition
    evaluation: arithmetic on it is several times cheaper than on a 0-d array), anything else as an array.
    """
    if type(x) in FLOATS:
        v = float(x)
        if not math.isfinite(v) or (v <= 0.0 if positive else v < 0.0):
            raise ValueError(f"{name} must be finite and {'>' if positive else '>='} 0, got {x!r}")
        return v
    a = np.asarray(x, dtype=float)
    if a.ndim == 0:  # the common scalar case, without numpy's reductions
        v = float(a)
        bad = not math.isfinite(v) or (v <= 0.0 if positive else v < 0.0)
    else:
        bad = bool(np.any(~np.isfinite(a)) or np.any(a <= 0.0 if positive else a < 0.0))
    if bad:
        raise ValueError(f"{name} must be finite and {'>' if positive else '>='} 0, got {x!r}")
    return a


def absolute_temperature(name, T):
    T = float(T)
    if not math.isfinite(T) or T <= 0.0:
        raise ValueError(f"{name} must be an absolute temperature in K (> 0), got {T!r}")
    return T


def check_range_nonzero(correlation, quantity, a, low, high):
    """check_range on the non-zero entries: 0 is the no-driving-force limit (Nu = 0)."""
    if np.ndim(a) == 0:  # the common scalar case, without numpy's masking
        if float(a) > 0.0:
            check_range(correlation, quantity, float(a), low, high)
        return
    nz = a[a > 0.0]
    if nz.size:
        check_range(correlation, quantity, nz, low, high)
