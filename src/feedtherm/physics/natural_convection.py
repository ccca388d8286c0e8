"""Natural convection of the paper's §3.2 (Eqs. 24-26), corrected.

Nusselt correlations of a stationary surface in still air (pure functions of Ra;
scalars or arrays) and :func:`h_natural`, the film coefficient h [W/(m²·K)] with air
properties at the film temperature (the paper's "qualitative temperature" ε).
Temperatures in K.

Corrections to the printed paper (docs/paper-audit.md §1): Eq. 24 L in m; Eq. 25 C and n per
geometry and regime, ε = film temperature; Eq. 26 ν in m²/s, β = 1/T_f.

"Incropera (2007)" is F. P. Incropera, D. P. DeWitt, T. L. Bergman, A. S. Lavine,
*Fundamentals of Heat and Mass Transfer*, 6th ed., Wiley, 2007.
"""

from __future__ import annotations

import math

import numpy as np

from feedtherm.physics._arrays import scalar_or_array as _out
from feedtherm.physics._checks import absolute_temperature as _temperature
from feedtherm.physics._checks import check_range_nonzero as _check_nonzero
from feedtherm.physics._checks import finite_array as _arr
from feedtherm.physics.air import film_temperature, properties_air
from feedtherm.physics.dimensionless import grashof, h_from_nusselt, rayleigh

#: Orientation keywords accepted by :func:`h_natural`.
NATURAL_ORIENTATIONS = (
    "horizontal_cylinder", "vertical_plate", "horizontal_plate_up", "horizontal_plate_down",
)

# Morgan (Incropera 2007, Table 9.1): (upper bound of Ra_D, C, n) per regime.
_MORGAN = ((1e-2, 0.675, 0.058), (1e2, 1.02, 0.148), (1e4, 0.850, 0.188),
           (1e7, 0.480, 0.250), (math.inf, 0.125, 0.333))


def _power_law(x, regimes):
    """Piecewise C·x^n; regime i covers [upper_{i-1}, upper_i)."""
    if np.ndim(x) == 0:  # the common scalar case, without building arrays
        v = float(x)
        _, C, n = next(r for r in regimes if v < r[0] or r[0] == math.inf)
        return C * v**n
    idx = np.searchsorted([r[0] for r in regimes], x, side="right")
    C = np.array([r[1] for r in regimes])[idx]
    n = np.array([r[2] for r in regimes])[idx]
    return C * x**n


def Nu_natural_horizontal_cylinder_Morgan(Ra):
    r"""Isothermal horizontal cylinder, Morgan's table (Eq. 25 with C, n).

    .. math:: Nu_D = C \, Ra_D^{\,n}

    with (Ra_D range: C, n) = (1e-10-1e-2: 0.675, 0.058), (1e-2-1e2: 1.02, 0.148),
    (1e2-1e4: 0.850, 0.188), (1e4-1e7: 0.480, 0.250), (1e7-1e12: 0.125, 0.333).

    Parameters
    ----------
    Ra : float or array_like
        Rayleigh number on the diameter, properties at the film temperature, [-].

    Returns
    -------
    float or ndarray
        Nu_D, [-].

    Notes
    -----
    Valid 1e-10 ≤ Ra_D ≤ 1e12 (warns outside). Ra = 0 returns the lowest regime's
    limit 0 without warning. A boundary value belongs to the upper regime; adjacent
    regimes differ there by < 1 %. The name carries the source because Incropera §9.6.3
    gives a second correlation for the same case (Churchill & Chu, Eq. 9.34).

    References
    ----------
    .. [1] Paper, Eq. 25; docs/paper-audit.md §1, Eq. 25.
    .. [2] Incropera (2007), §9.6.3, Table 9.1 (V. T. Morgan, Adv. Heat Transfer 11,
       1975, 199-264).

    Examples
    --------
    Incropera Table 9.1, Ra_D = 1e5 (regime 1e4-1e7): 0.480·(1e5)^0.25 = 0.480·17.7828 = 8.536.

    >>> round(Nu_natural_horizontal_cylinder_Morgan(1e5), 3)
    8.536
    """
    Ra = _arr(Ra, "Ra")
    _check_nonzero("Nu_natural_horizontal_cylinder_Morgan", "Ra_D", Ra, 1e-10, 1e12)
    return _out(_power_law(Ra, _MORGAN))


def Nu_natural_vertical_plate_McAdams(Ra):
    r"""Isothermal vertical plate, McAdams constants (Eq. 25 with C, n).

    .. math::

        Nu_L = 0.59 \, Ra_L^{1/4} \ (Ra_L < 10^9), \qquad
        Nu_L = 0.10 \, Ra_L^{1/3} \ (Ra_L \ge 10^9)

    Parameters
    ----------
    Ra : float or array_like
        Rayleigh number on the plate height L, [-].

    Returns
    -------
    float or ndarray
        Nu_L, [-].

    Notes
    -----
    Valid 1e4-1e9 (laminar) and 1e9-1e13 (turbulent); warns outside [1e4, 1e13]
    (0.59 Ra^¼ is still used below 1e4). Ra = 0 returns 0 without warning. The two
    regimes step by 4.7 % at 1e9 (104.9 vs 100.0). The name carries the source because
    Incropera §9.6.1 gives a second correlation for the same case (Churchill & Chu,
    Eqs. 9.26-9.27).

    References
    ----------
    .. [1] Paper, Eq. 25; docs/paper-audit.md §1, Eq. 25.
    .. [2] Incropera (2007), §9.6.1 (Nu = C Ra^n, McAdams' C and n; W. H. McAdams,
       *Heat Transmission*, 3rd ed., 1954).

    Examples
    --------
    Laminar 0.59·(1e8)^(1/4) = 0.59·100 = 59.0; turbulent 0.10·(1e12)^(1/3) = 0.10·1e4 = 1000.

    >>> round(Nu_natural_vertical_plate_McAdams(1e8), 9), round(Nu_natural_vertical_plate_McAdams(1e12), 9)
    (59.0, 1000.0)
    """
    Ra = _arr(Ra, "Ra")
    _check_nonzero("Nu_natural_vertical_plate_McAdams", "Ra_L", Ra, 1e4, 1e13)
    return _out(_power_law(Ra, ((1e9, 0.59, 0.25), (math.inf, 0.10, 1.0 / 3.0))))


def Nu_natural_horizontal_plate_up(Ra):
    r"""Upper face of a hot plate, or lower face of a cold plate.

    .. math::

        Nu_L = 0.54 \, Ra_L^{1/4} \ (Ra_L < 10^7), \qquad
        Nu_L = 0.15 \, Ra_L^{1/3} \ (Ra_L \ge 10^7)

    Parameters
    ----------
    Ra : float or array_like
        Rayleigh number on L = A/P (area over perimeter), [-].

    Returns
    -------
    float or ndarray
        Nu_L, [-].

    Notes
    -----
    Valid 1e4 ≤ Ra_L ≤ 1e11 (warns outside; 0.54 Ra^¼ is still used below 1e4).
    Ra = 0 returns 0 without warning.

    References
    ----------
    .. [1] Paper, Eq. 25; docs/paper-audit.md §1, Eq. 25.
    .. [2] Incropera (2007), §9.6.2, Eqs. 9.29 (L = A/P), 9.30 and 9.31.

    Examples
    --------
    Incropera Eqs. 9.30-9.31: 0.54·(1e6)^(1/4) = 0.54·31.623 = 17.076; 0.15·(1e9)^(1/3) = 150.

    >>> round(Nu_natural_horizontal_plate_up(1e6), 3), round(Nu_natural_horizontal_plate_up(1e9), 9)
    (17.076, 150.0)
    """
    Ra = _arr(Ra, "Ra")
    _check_nonzero("Nu_natural_horizontal_plate_up", "Ra_L", Ra, 1e4, 1e11)
    return _out(_power_law(Ra, ((1e7, 0.54, 0.25), (math.inf, 0.15, 1.0 / 3.0))))


def Nu_natural_horizontal_plate_down(Ra):
    r"""Lower face of a hot plate, or upper face of a cold plate.

    .. math:: Nu_L = 0.27 \, Ra_L^{1/4}

    Parameters
    ----------
    Ra : float or array_like
        Rayleigh number on L = A/P, [-].

    Returns
    -------
    float or ndarray
        Nu_L, [-].

    Notes
    -----
    Valid 1e5 ≤ Ra_L ≤ 1e10 (warns outside). Ra = 0 returns 0 without warning.

    References
    ----------
    .. [1] Paper, Eq. 25; docs/paper-audit.md §1, Eq. 25.
    .. [2] Incropera (2007), §9.6.2, Eq. 9.32.

    Examples
    --------
    Incropera Eq. 9.32: 0.27·(1e8)^(1/4) = 0.27·100 = 27.0.

    >>> round(Nu_natural_horizontal_plate_down(1e8), 9)
    27.0
    """
    Ra = _arr(Ra, "Ra")
    _check_nonzero("Nu_natural_horizontal_plate_down", "Ra_L", Ra, 1e5, 1e10)
    return _out(0.27 * Ra**0.25)


_NATURAL_NU = {
    "horizontal_cylinder": Nu_natural_horizontal_cylinder_Morgan,
    "vertical_plate": Nu_natural_vertical_plate_McAdams,
    "horizontal_plate_up": Nu_natural_horizontal_plate_up,
    "horizontal_plate_down": Nu_natural_horizontal_plate_down,
}
_SWAP = {"horizontal_plate_up": "horizontal_plate_down",
         "horizontal_plate_down": "horizontal_plate_up"}


def h_natural(orientation, L, T_surface, T_ambient):
    r"""Natural-convection film coefficient of a stationary surface in still air.

    .. math::

        h = \frac{k}{L} Nu(Ra), \quad
        Ra = \frac{g \beta |T_s - T_\infty| L^3}{\nu \alpha}, \quad \beta = 1/T_f,
        \quad \text{properties at } T_f = (T_s + T_\infty)/2

    Parameters
    ----------
    orientation : str
        ``"horizontal_cylinder"`` (L = diameter, Morgan), ``"vertical_plate"``
        (L = height), ``"horizontal_plate_up"`` / ``"horizontal_plate_down"`` (the way
        the face points; L = A/P).
    L : float
        Characteristic length, [m].
    T_surface, T_ambient : float
        Surface and ambient temperatures, [K].

    Returns
    -------
    float
        h, [W/(m²·K)].

    Raises
    ------
    ValueError
        Unknown ``orientation`` (the message lists the valid ones), L ≤ 0 or a
        non-positive temperature.

    Notes
    -----
    A cold face pointing up behaves like a hot face pointing down and vice versa
    (Incropera 2007, §9.6.2): for T_s < T_∞ the two plate orientations are swapped.
    The vertical plate and the cylinder are symmetric in the sign of ΔT. For
    T_s = T_∞, Ra = 0 and every correlation gives its limit Nu = 0, so h = 0 (no
    division by zero, no warning; the flux is zero anyway). Range warnings come from
    the Nusselt functions and from :func:`~feedtherm.physics.air.properties_air`.

    References
    ----------
    .. [1] Paper, Eqs. 24-26; docs/paper-audit.md §1, Eqs. 24-26. Incropera (2007), §9.6.

    Examples
    --------
    docs/paper-audit.md §1, Eq. 25: a 0.1 m vertical plate 10 K above 20 °C air has
    h = 4.8 W/(m²·K) (Incropera's air at 300 K). With CoolProp air at T_f = 298.15 K
    (k = 0.026247 W/(m·K), ν = 1.55770e-5 m²/s, α = 2.20231e-5 m²/s): Ra = 9.80665/298.15·10·0.1³
    /(1.55770e-5·2.20231e-5) = 9.5879e5, Ra^(1/4) = 31.292, Nu = 0.59·31.292 = 18.462,
    h = 18.462·0.026247/0.1 = 4.846 W/(m²·K).

    >>> round(h_natural("vertical_plate", 0.1, 303.15, 293.15), 3)
    4.846
    """
    if orientation not in _NATURAL_NU:
        raise ValueError(f"unknown orientation {orientation!r}; valid choices: "
                         + ", ".join(repr(o) for o in NATURAL_ORIENTATIONS))
    Ts, Ta = _temperature("T_surface", T_surface), _temperature("T_ambient", T_ambient)
    L = float(_arr(L, "L", positive=True))
    if Ts < Ta:
        orientation = _SWAP.get(orientation, orientation)
    air = properties_air(film_temperature(Ts, Ta))
    Ra = rayleigh(grashof(L, Ts, Ta, air.kinematic_viscosity, air.expansion_coefficient),
                  air.prandtl)
    return h_from_nusselt(_NATURAL_NU[orientation](Ra), air.conductivity, L)
