"""Axial thermal elongation of the screw from its temperature along the axis.

Free thermal strain, integrated from the axially fixed bearing:

.. math:: u(x) = \\int_{x_f}^{x} \\alpha\\,(\\bar T(\\xi) - T_{ref})\\, d\\xi

with :math:`\\bar T` the cross-section mean temperature, α the expansion coefficient and
:math:`T_{ref}` the reference (zero-strain) temperature.  D is u at the read point.  This
is the 1-D limit of linear thermo-elasticity for a shaft free to expand beyond its fixed
bearing (the paper's rear bearing "cannot limit the axial displacement"; docs/paper-audit.md §4).
"""

from __future__ import annotations

import numpy as np


def displacement(edges: np.ndarray, temperature: np.ndarray, alpha: float, t_ref: float, x_fixed: float,
                 x: np.ndarray) -> np.ndarray:
    """Axial displacement [m] at positions ``x`` of a bar with cell-wise constant temperature.

    Parameters
    ----------
    edges : ndarray, shape (m+1,)
        Cell edges along the axis [m].
    temperature : ndarray, shape (..., m)
        Cross-section mean temperature of each cell [K]; leading axes (e.g. time) allowed.
    alpha : float
        Linear expansion coefficient [1/K].
    t_ref : float
        Reference temperature [K] at which the strain is zero.
    x_fixed : float
        Position of the axially fixed point [m].
    x : ndarray
        Positions where the displacement is wanted [m].

    Returns
    -------
    ndarray, shape (..., len(x))
        Displacement [m], positive towards +x.
    """
    strain = alpha * (np.asarray(temperature, dtype=float) - t_ref)
    edges = np.asarray(edges, dtype=float)
    x = np.atleast_1d(np.asarray(x, dtype=float))
    # length of each cell between x_fixed and x, signed (negative where x < x_fixed)
    lo = np.minimum(x_fixed, x)[:, None]
    hi = np.maximum(x_fixed, x)[:, None]
    inside = np.clip(np.minimum(edges[1:], hi) - np.maximum(edges[:-1], lo), 0.0, None)
    sign = np.where(x >= x_fixed, 1.0, -1.0)[:, None]
    weights = inside * sign  # (len(x), m)
    return strain @ weights.T


def elongation(edges, temperature, alpha, t_ref, x_fixed, x_read):
    """D [m]: the displacement at ``x_read`` relative to the fixed point."""
    return displacement(edges, temperature, alpha, t_ref, x_fixed, np.array([x_read]))[..., 0]
