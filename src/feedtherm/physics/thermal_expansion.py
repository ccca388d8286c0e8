r"""Axial thermal displacement of a shaft from its temperature along the axis.

Free thermal strain integrated from the axially fixed point (the 1-D limit of linear
thermo-elasticity for a shaft free to expand beyond its fixed bearing; the paper's rear
bearing "cannot limit the axial displacement", docs/paper-audit.md §4):

.. math:: u(x) = \int_{x_f}^{x} \alpha\,(\bar T(\xi) - T_{ref})\, d\xi

with :math:`\bar T` the cross-section mean temperature, α the linear expansion coefficient
and :math:`T_{ref}` the zero-strain temperature.  The fast model reads every part as such a
bar, carried by its neighbours along the structure's axial load path (models/fast/bars.py).
"""

from __future__ import annotations

import numpy as np


def displacement_weights_axial(edges, x_fixed: float, x) -> np.ndarray:
    r"""Signed length [m] of each cell between the fixed point and each position.

    .. math:: w_{ij} = \operatorname{sign}(x_i - x_f)\,
              \big|[e_j, e_{j+1}] \cap [\min(x_f, x_i), \max(x_f, x_i)]\big|

    so that :math:`u(x_i) = \alpha \sum_j w_{ij} (\bar T_j - T_{ref})` for cell-wise constant
    temperatures (exact for them).

    Parameters
    ----------
    edges : array_like, shape (m+1,)
        Increasing cell edges along the axis, [m].
    x_fixed : float
        Axially fixed point, [m].
    x : array_like, shape (p,)
        Positions where the displacement is wanted, [m]; may lie outside the edges (the
        part beyond them has no strain).

    Returns
    -------
    ndarray, shape (p, m)
        Weights, [m]: negative for positions behind the fixed point.

    Notes
    -----
    Pure geometry (interval overlap); valid for any cells.  Source: the definition of
    the axial displacement as the integral of the free thermal strain (Timoshenko & Goodier,
    Theory of Elasticity, 3rd ed., §150, uniaxial case).

    Examples
    --------
    Cells [0, 0.1], [0.1, 0.2], [0.2, 0.3] m, fixed at 0.1 m; at x = 0.25 m the second cell
    counts 0.1 m and the third 0.05 m; at x = 0 the first counts −0.1 m:

    >>> displacement_weights_axial([0.0, 0.1, 0.2, 0.3], 0.1, [0.25, 0.0]).round(12).tolist()
    [[0.0, 0.1, 0.05], [-0.1, -0.0, -0.0]]
    """
    edges = np.asarray(edges, dtype=float)
    x = np.atleast_1d(np.asarray(x, dtype=float))
    lo = np.minimum(x_fixed, x)[:, None]
    hi = np.maximum(x_fixed, x)[:, None]
    inside = np.clip(np.minimum(edges[1:], hi) - np.maximum(edges[:-1], lo), 0.0, None)
    return inside * np.where(x >= x_fixed, 1.0, -1.0)[:, None]


def displacement_axial(edges, temperature, alpha: float, t_ref: float, x_fixed: float, x) -> np.ndarray:
    r"""Axial thermal displacement [m] at positions ``x`` of a shaft with cell-wise constant temperature.

    .. math:: u(x) = \alpha \sum_j w_j(x)\,(\bar T_j - T_{ref})

    with the weights of :func:`displacement_weights_axial`.

    Parameters
    ----------
    edges : array_like, shape (m+1,)
        Cell edges along the axis, [m].
    temperature : array_like, shape (..., m)
        Cross-section mean temperature of each cell, [K]; leading axes (time) allowed.
    alpha : float
        Linear expansion coefficient, [1/K].
    t_ref : float
        Zero-strain reference temperature, [K].
    x_fixed : float
        Axially fixed point, [m].
    x : array_like, shape (p,)
        Positions, [m].

    Returns
    -------
    ndarray, shape (..., p)
        Displacement, [m], positive towards +x.

    Notes
    -----
    Valid for small strains (α ΔT ≪ 1) and a shaft free to expand beyond its fixed point;
    the 1-D limit of linear thermo-elasticity (Timoshenko & Goodier, §150).

    Examples
    --------
    A 0.4 m steel screw 5 K above the reference, α = 12e-6 1/K: D = α L ΔT =
    12e-6 · 0.4 · 5 = 24e-6 m.

    >>> float(displacement_axial([0.0, 0.2, 0.4], [298.15, 298.15], 12e-6, 293.15, 0.0, [0.4])[0])
    2.4e-05
    """
    strain = alpha * (np.asarray(temperature, dtype=float) - t_ref)
    return strain @ displacement_weights_axial(edges, x_fixed, x).T


def elongation_axial(edges, temperature, alpha: float, t_ref: float, x_fixed: float, x_read: float):
    r"""Elongation D [m]: the axial displacement at ``x_read`` relative to the fixed point.

    .. math:: D = u(x_{read})

    Parameters
    ----------
    edges, temperature, alpha, t_ref, x_fixed
        As in :func:`displacement_axial`.
    x_read : float
        Where the elongation is read, [m].

    Returns
    -------
    float or ndarray, shape (...)
        D, [m].

    Notes
    -----
    Valid as :func:`displacement_axial`.  Source: Timoshenko & Goodier, §150.

    Examples
    --------
    Cells of 0.1 m at +10, 0 and +20 K over the reference, α = 1e-5 1/K, fixed at 0.1 m,
    read at 0.3 m: D = 1e-5 · (0 · 0.1 + 20 · 0.1) = 2e-5 m.

    >>> round(float(elongation_axial([0, 0.1, 0.2, 0.3], [303.15, 293.15, 313.15], 1e-5, 293.15, 0.1, 0.3)), 12)
    2e-05
    """
    return displacement_axial(edges, temperature, alpha, t_ref, x_fixed, np.array([x_read]))[..., 0]
