"""Convection correlations of the paper's §3.2 (Eqs. 24-29), corrected.

Dimensionless groups, Nusselt correlations (pure functions of Ra or Re, Pr; scalars or
arrays) and surface-level helpers returning h [W/(m²·K)] with air properties at the
film temperature (the paper's "qualitative temperature" ε).  Temperatures in K.

Corrections to the printed paper (docs/paper-audit.md §1): Eq. 24 L in m; Eq. 25 C and n per
geometry and regime, ε = film temperature; Eq. 26 ν in m²/s, β = 1/T_f; Eq. 27
Re = ωd²/ν; Eq. 28 plate average 0.664 (the printed local 0.332 is kept as the named
variant :func:`Nu_flat_plate_laminar_local`); Eq. 29 valid only for 4e3 < Re < 1.5e4,
so at feed speeds blend with natural convection (:func:`Nu_mixed`, :func:`h_mixed`).

"Incropera (2007)" is F. P. Incropera, D. P. DeWitt, T. L. Bergman, A. S. Lavine,
*Fundamentals of Heat and Mass Transfer*, 6th ed., Wiley, 2007.

Layout: this module holds mixed convection (:func:`Nu_mixed`, :func:`h_mixed`) and
re-exports the rest, so ``convection.<name>`` reaches every convection function: the
dimensionless groups and Eq. 24 from :mod:`~feedtherm.physics.dimensionless`, natural
convection (Eq. 25) from :mod:`~feedtherm.physics.natural_convection` and forced
convection (Eqs. 27-29) from :mod:`~feedtherm.physics.forced_convection`.
"""

from __future__ import annotations

import numpy as np

from feedtherm.physics._arrays import scalar_or_array as _out
from feedtherm.physics._checks import finite_array as _arr
from feedtherm.physics.dimensionless import (
    G_STANDARD,
    grashof,
    h_from_nusselt,
    rayleigh,
    reynolds,
    reynolds_rotating,
)
from feedtherm.physics.forced_convection import (
    Nu_cylinder_crossflow_Churchill_Bernstein,
    Nu_flat_plate_laminar_average,
    Nu_flat_plate_laminar_local,
    Nu_plate_normal_to_flow,
    Nu_rotating_cylinder,
    h_cylinder_crossflow,
    h_flat_plate_laminar_average,
    h_plate_normal_to_flow,
    h_rotating_cylinder,
)
from feedtherm.physics.natural_convection import (
    NATURAL_ORIENTATIONS,
    Nu_natural_horizontal_cylinder_Morgan,
    Nu_natural_horizontal_plate_down,
    Nu_natural_horizontal_plate_up,
    Nu_natural_vertical_plate_McAdams,
    h_natural,
)

__all__ = [
    # dimensionless groups and Eq. 24 (feedtherm.physics.dimensionless)
    "G_STANDARD",
    "grashof",
    "rayleigh",
    "reynolds",
    "reynolds_rotating",
    "h_from_nusselt",
    # natural convection, Eq. 25 (feedtherm.physics.natural_convection)
    "NATURAL_ORIENTATIONS",
    "Nu_natural_horizontal_cylinder_Morgan",
    "Nu_natural_vertical_plate_McAdams",
    "Nu_natural_horizontal_plate_up",
    "Nu_natural_horizontal_plate_down",
    "h_natural",
    # forced convection, Eqs. 27-29 (feedtherm.physics.forced_convection)
    "Nu_rotating_cylinder",
    "Nu_flat_plate_laminar_average",
    "Nu_flat_plate_laminar_local",
    "Nu_plate_normal_to_flow",
    "h_rotating_cylinder",
    "h_flat_plate_laminar_average",
    "h_plate_normal_to_flow",
    # forced convection of the room's air on a cylinder
    "Nu_cylinder_crossflow_Churchill_Bernstein",
    "h_cylinder_crossflow",
    # mixed convection (this module)
    "Nu_mixed",
    "h_mixed",
]


def Nu_mixed(Nu_forced, Nu_natural, n=3.0, assisting=True):
    r"""Mixed forced and natural convection, Churchill's blend.

    .. math:: Nu^n = Nu_F^n \pm Nu_N^n

    Parameters
    ----------
    Nu_forced, Nu_natural : float or array_like
        Forced and natural Nusselt numbers based on the **same** length and k, [-].
    n : float, optional
        Exponent, [-]: 3 in general; 3.5 (plates) and 4 (cylinders, spheres) fit
        transverse flow slightly better.
    assisting : bool, optional
        True: ``+``, for assisting flow (forced flow along the buoyant motion) and for
        transverse flow (motion perpendicular to gravity, e.g. a horizontally moving
        table; the usual engineering choice). False: ``−`` for opposing flow,
        evaluated as :math:`|Nu_F^n - Nu_N^n|^{1/n}`.

    Returns
    -------
    float or ndarray
        Nu, [-].

    Notes
    -----
    Matters where Gr/Re² ~ 1 and tends to the dominant mode on either side. The
    opposing form is unreliable when Nu_F ≈ Nu_N (it tends to 0). For Nusselt numbers
    on different lengths, blend film coefficients with :func:`h_mixed`.

    References
    ----------
    .. [1] docs/paper-audit.md §1, Eq. 29. Incropera (2007), §9.9.
    .. [2] S. W. Churchill, AIChE J. 23 (1977) 10-16.

    Examples
    --------
    Churchill's blend with n = 3: assisting (3³ + 4³)^(1/3) = 91^(1/3) = 4.4979; opposing
    (4³ − 3³)^(1/3) = 37^(1/3) = 3.3322.

    >>> round(Nu_mixed(3.0, 4.0), 4), round(Nu_mixed(4.0, 3.0, assisting=False), 4)
    (4.4979, 3.3322)
    """
    if not n > 0:
        raise ValueError(f"n must be > 0, got {n!r}")
    F, N = _arr(Nu_forced, "Nu_forced"), _arr(Nu_natural, "Nu_natural")
    return _out((F**n + N**n if assisting else np.abs(F**n - N**n)) ** (1.0 / n))


def h_mixed(h_forced, h_natural, n=3.0):
    r"""Mixed-convection film coefficient, assisting/transverse form.

    .. math:: h = \left(h_F^{\,n} + h_N^{\,n}\right)^{1/n}

    Parameters
    ----------
    h_forced, h_natural : float or array_like
        Forced and natural film coefficients, [W/(m²·K)].
    n : float, optional
        Exponent, [-] (see :func:`Nu_mixed`).

    Returns
    -------
    float or ndarray
        h, [W/(m²·K)].

    Notes
    -----
    Equals :func:`Nu_mixed` (assisting) for *any* common length L and conductivity k:
    with Nu_i' = h_i L/k the blend is homogeneous of degree one, so
    h = (k/L)(Nu_F'^n + Nu_N'^n)^{1/n}. It is therefore correct even when h_F and h_N
    used different lengths (length along the motion vs. A/P), whereas blending Nu
    values on different lengths directly is not. Evaluate both at the same film
    temperature. For opposing flow use :func:`Nu_mixed` with ``assisting=False``.

    References
    ----------
    .. [1] Incropera (2007), §9.9; S. W. Churchill, AIChE J. 23 (1977) 10-16.

    Examples
    --------
    docs/paper-audit.md §1, Eq. 29: at 3 mm/s h_F ≈ 0.39 beside h_N ≈ 4.8 W/(m²·K), so the blend
    is natural convection: (0.39³ + 4.8³)^(1/3) = 110.6513^(1/3) = 4.8·(1 + 0.059319/110.592)^(1/3)
    = 4.8·1.000179 = 4.8009.

    >>> round(h_mixed(0.39, 4.8), 4)
    4.8009
    """
    if not n > 0:
        raise ValueError(f"n must be > 0, got {n!r}")
    F, N = _arr(h_forced, "h_forced"), _arr(h_natural, "h_natural")
    return _out((F**n + N**n) ** (1.0 / n))
