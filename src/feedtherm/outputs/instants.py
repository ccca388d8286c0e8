"""Which instants a figure of profiles shows, and how it labels them.

Shared by the run plots (the positioning error along the stroke) and the field images (the
screw's displacement along its axis), so that both pick and label their curves alike.
"""

from __future__ import annotations

import numpy as np

_HOURS = 3600.0


def spread_instants(times: np.ndarray, count: int) -> list[int]:
    """Indices of up to ``count`` instants nearest to evenly spaced times after the first; the last always.

    Parameters
    ----------
    times : ndarray, shape (n,)
        Increasing times [s].
    count : int
        How many instants at most; fewer when several targets share a nearest sample.

    Returns
    -------
    list of int
        Increasing indices into ``times``, ending with ``n - 1``.
    """
    times = np.asarray(times, dtype=float)
    last = len(times) - 1
    if count <= 1 or last <= 0:
        return [max(last, 0)]
    targets = times[0] + (times[-1] - times[0]) * np.arange(1, count + 1) / count
    return sorted({int(np.argmin(np.abs(times - target))) for target in targets} | {last})


def time_unit(times: np.ndarray) -> str:
    """``h`` when the times reach an hour, else ``s``: one unit for every label of a figure."""
    return "h" if len(times) and times[-1] >= _HOURS else "s"


def time_label(seconds: float, unit: str) -> str:
    """``1.50 h`` or ``90 s``, in the figure's ``unit`` (see :func:`time_unit`)."""
    return f"{seconds / _HOURS:.2f} h" if unit == "h" else f"{seconds:.0f} s"
