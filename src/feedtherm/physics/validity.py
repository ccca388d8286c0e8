"""Validity ranges of correlations, enforced in code.

A correlation used outside the range its source establishes still returns a value (the
paper itself applies Eq. 29 far outside its range), but it never does so silently: it
emits a :class:`CorrelationRangeWarning` naming the correlation, the quantity, its value
and the range.  The boundary-condition step collects these warnings and reports them.
"""

from __future__ import annotations

import warnings

import numpy as np

from feedtherm.physics._arrays import FLOATS


class CorrelationRangeWarning(UserWarning):
    """A correlation was evaluated outside the validity range of its source."""


def check_range(correlation: str, quantity: str, value, low: float, high: float) -> None:
    """Warn when ``value`` lies outside ``[low, high]``.

    Parameters
    ----------
    correlation : str
        Name of the correlation, e.g. ``"Nu_rotating_cylinder (Eq. 27)"``.
    quantity : str
        Name of the checked quantity, e.g. ``"Re"``.
    value : float or array_like
        The value(s) used.
    low, high : float
        Inclusive validity range of the source.

    Examples
    --------
    Eq. 29 (Incropera Table 7.3) holds for 4e3 ≤ Re ≤ 1.5e4; a 0.3 m table at 3 mm/s has
    Re = 0.003·0.3/15.89e-6 = 56.6:

    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     check_range("Nu_plate_normal_to_flow (Eq. 29)", "Re", 56.6, 4e3, 1.5e4)
    >>> print(caught[0].message)
    Nu_plate_normal_to_flow (Eq. 29): Re = 56.6 is outside its validity range [4000, 1.5e+04]
    """
    if type(value) in FLOATS:  # the common scalar case, without numpy
        vmin = vmax = float(value)
    else:
        arr = np.asarray(value, dtype=float)
        if arr.size == 0:
            return
        if arr.ndim == 0:
            vmin = vmax = float(arr)
        else:
            vmin, vmax = float(np.min(arr)), float(np.max(arr))
    if vmin < low or vmax > high:
        shown = f"{vmin:.4g}" if vmin == vmax else f"{vmin:.4g}..{vmax:.4g}"
        warnings.warn(
            f"{correlation}: {quantity} = {shown} is outside its validity range "
            f"[{low:.4g}, {high:.4g}]",
            CorrelationRangeWarning,
            stacklevel=3,
        )
