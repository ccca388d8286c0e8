"""Convection correlations of the paper's §3.2 (Eqs. 24-29), corrected.

Dimensionless groups, Nusselt correlations (pure functions of Ra or Re, Pr; scalars or
arrays) and surface-level helpers returning h [W/(m²·K)] with air properties at the
film temperature (the paper's "qualitative temperature" ε).  Temperatures in K.

Corrections to the printed paper (AUDIT §1): Eq. 24 L in m; Eq. 25 C and n per
geometry and regime, ε = film temperature; Eq. 26 ν in m²/s, β = 1/T_f; Eq. 27
Re = ωd²/ν; Eq. 28 plate average 0.664 (the printed local 0.332 is kept as the named
variant :func:`Nu_flat_plate_laminar_local`); Eq. 29 valid only for 4e3 < Re < 1.5e4,
so at feed speeds blend with natural convection (:func:`Nu_mixed`, :func:`h_mixed`).

"Incropera (2007)" is F. P. Incropera, D. P. DeWitt, T. L. Bergman, A. S. Lavine,
*Fundamentals of Heat and Mass Transfer*, 6th ed., Wiley, 2007.
"""

from __future__ import annotations

import math

import numpy as np

from feedtherm.physics.air import air_properties, film_temperature
from feedtherm.physics.validity import check_range

#: Standard gravity, [m/s²].
G_STANDARD = 9.80665

#: Orientation keywords accepted by :func:`h_natural`.
NATURAL_ORIENTATIONS = (
    "horizontal_cylinder", "vertical_plate", "horizontal_plate_up", "horizontal_plate_down",
)

# Morgan (Incropera 2007, Table 9.1): (upper bound of Ra_D, C, n) per regime.
_MORGAN = ((1e-2, 0.675, 0.058), (1e2, 1.02, 0.148), (1e4, 0.850, 0.188),
           (1e7, 0.480, 0.250), (math.inf, 0.125, 0.333))


def _arr(x, name, *, positive=False):
    a = np.asarray(x, dtype=float)
    if np.any(~np.isfinite(a)) or np.any(a <= 0.0 if positive else a < 0.0):
        raise ValueError(f"{name} must be finite and {'>' if positive else '>='} 0, got {x!r}")
    return a


def _out(a):
    a = np.asarray(a, dtype=float)
    return float(a) if a.ndim == 0 else a


def _check_nonzero(correlation, quantity, a, low, high):
    """check_range on the non-zero entries: 0 is the no-driving-force limit (Nu = 0)."""
    nz = a[a > 0.0]
    if nz.size:
        check_range(correlation, quantity, nz, low, high)


def _power_law(x, regimes):
    """Piecewise C·x^n; regime i covers [upper_{i-1}, upper_i)."""
    idx = np.searchsorted([r[0] for r in regimes], x, side="right")
    C = np.array([r[1] for r in regimes])[idx]
    n = np.array([r[2] for r in regimes])[idx]
    return C * x**n


# ------------------------------------------------------------- dimensionless groups
def grashof(L, T_surface, T_ambient, nu, beta, g=G_STANDARD):
    r"""Grashof number (paper Eq. 26 with corrected units).

    .. math:: Gr_L = g \beta |T_s - T_\infty| L^3 / \nu^2

    Parameters
    ----------
    L : float or array_like
        Characteristic length, [m].
    T_surface, T_ambient : float or array_like
        Surface and ambient temperatures, [K]; only |T_s − T_∞| enters.
    nu : float or array_like
        Kinematic viscosity at the film temperature, [m²/s] (the paper prints mm²/s).
    beta : float or array_like
        Expansion coefficient, [1/K]; for air the ideal-gas 1/T_f.
    g : float, optional
        Gravitational acceleration, [m/s²].

    Returns
    -------
    float or ndarray
        Gr, [-], never negative (a cold surface is handled by geometry, see
        :func:`h_natural`).

    References
    ----------
    .. [1] Paper, Eq. 26; AUDIT §1, Eq. 26. Incropera (2007), Eq. 9.12.
    """
    L, nu = _arr(L, "L", positive=True), _arr(nu, "nu", positive=True)
    dT = np.abs(np.asarray(T_surface, dtype=float) - np.asarray(T_ambient, dtype=float))
    return _out(g * _arr(beta, "beta", positive=True) * dT * L**3 / nu**2)


def rayleigh(Gr, Pr):
    r"""Rayleigh number, the product in paper Eq. 25.

    .. math:: Ra = Gr \, Pr

    Parameters
    ----------
    Gr : float or array_like
        Grashof number, [-].
    Pr : float or array_like
        Prandtl number, [-].

    Returns
    -------
    float or ndarray
        Ra, [-].

    References
    ----------
    .. [1] Paper, Eq. 25 ((Gr·Pr)). Incropera (2007), Ch. 9.
    """
    return _out(_arr(Gr, "Gr") * _arr(Pr, "Pr", positive=True))


def reynolds(u, L, nu):
    r"""Reynolds number of a translating surface.

    .. math:: Re_L = |u| L / \nu

    Parameters
    ----------
    u : float or array_like
        Speed relative to still air, [m/s]; sign ignored.
    L : float or array_like
        Characteristic length, [m].
    nu : float or array_like
        Kinematic viscosity, [m²/s].

    Returns
    -------
    float or ndarray
        Re, [-].

    References
    ----------
    .. [1] Paper, Eqs. 28-29 (Re not defined there). Incropera (2007), Ch. 7.
    """
    L, nu = _arr(L, "L", positive=True), _arr(nu, "nu", positive=True)
    return _out(np.abs(np.asarray(u, dtype=float)) * L / nu)


def reynolds_rotating(omega, d, nu):
    r"""Rotational Reynolds number of a cylinder spinning in still air.

    .. math:: Re_\omega = |\omega| d^2 / \nu

    Parameters
    ----------
    omega : float or array_like
        Angular speed, [rad/s]; sign ignored.
    d : float or array_like
        Diameter, [m].
    nu : float or array_like
        Kinematic viscosity, [m²/s].

    Returns
    -------
    float or ndarray
        Re, [-].

    Notes
    -----
    The Re of Eq. 27, which the paper does not state (AUDIT §1, Eq. 27).

    References
    ----------
    .. [1] W. M. Kays, I. S. Bjorklund, "Heat transfer from a rotating cylinder with and
       without crossflow", Trans. ASME 80 (1958) 70-78.
    """
    d, nu = _arr(d, "d", positive=True), _arr(nu, "nu", positive=True)
    return _out(np.abs(np.asarray(omega, dtype=float)) * d**2 / nu)


def h_from_nusselt(Nu, k, L):
    r"""Film coefficient from a Nusselt number (paper Eq. 24, L in m).

    .. math:: h = Nu \, k / L

    Parameters
    ----------
    Nu : float or array_like
        Nusselt number based on ``L``, [-].
    k : float or array_like
        Air conductivity (the paper's λ), [W/(m·K)].
    L : float or array_like
        The length used in ``Nu``, [m] (the paper prints mm: h 1000× too small).

    Returns
    -------
    float or ndarray
        h, [W/(m²·K)].

    References
    ----------
    .. [1] Paper, Eq. 24; AUDIT §1, Eq. 24.
    """
    return _out(_arr(Nu, "Nu") * _arr(k, "k", positive=True) / _arr(L, "L", positive=True))


# ------------------------------------------------------ natural convection (Eq. 25)
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
    regimes differ there by < 1 %.

    References
    ----------
    .. [1] Paper, Eq. 25; AUDIT §1, Eq. 25.
    .. [2] Incropera (2007), §9.6.3, Table 9.1 (V. T. Morgan, Adv. Heat Transfer 11,
       1975, 199-264).
    """
    Ra = _arr(Ra, "Ra")
    _check_nonzero("Nu_natural_horizontal_cylinder_Morgan", "Ra_D", Ra, 1e-10, 1e12)
    return _out(_power_law(Ra, _MORGAN))


def Nu_natural_vertical_plate(Ra):
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
    regimes step by 4.7 % at 1e9 (104.9 vs 100.0).

    References
    ----------
    .. [1] Paper, Eq. 25; AUDIT §1, Eq. 25.
    .. [2] Incropera (2007), §9.6.1 (Nu = C Ra^n, McAdams' C and n; W. H. McAdams,
       *Heat Transmission*, 3rd ed., 1954).
    """
    Ra = _arr(Ra, "Ra")
    _check_nonzero("Nu_natural_vertical_plate", "Ra_L", Ra, 1e4, 1e13)
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
    .. [1] Paper, Eq. 25; AUDIT §1, Eq. 25.
    .. [2] Incropera (2007), §9.6.2, Eqs. 9.29 (L = A/P), 9.30 and 9.31.
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
    .. [1] Paper, Eq. 25; AUDIT §1, Eq. 25.
    .. [2] Incropera (2007), §9.6.2, Eq. 9.32.
    """
    Ra = _arr(Ra, "Ra")
    _check_nonzero("Nu_natural_horizontal_plate_down", "Ra_L", Ra, 1e5, 1e10)
    return _out(0.27 * Ra**0.25)


# ----------------------------------------------------------------- forced convection
def Nu_rotating_cylinder(Re, Pr):
    r"""Cylinder rotating in still air (paper Eq. 27).

    .. math:: Nu_D = 0.133 \, Re_\omega^{2/3} Pr^{1/3}, \qquad Re_\omega = \omega D^2/\nu

    Parameters
    ----------
    Re : float or array_like
        Rotational Reynolds number (:func:`reynolds_rotating`), [-].
    Pr : float or array_like
        Prandtl number, [-].

    Returns
    -------
    float or ndarray
        Nu_D, [-].

    Notes
    -----
    Valid Re_ω < 4.3e5 and 0.7 < Pr < 670 (warns outside; air drops below Pr = 0.7
    near 375 K). At low speed add natural convection with :func:`h_mixed`.

    References
    ----------
    .. [1] Paper, Eq. 27; AUDIT §1, Eq. 27.
    .. [2] Kays & Bjorklund, Trans. ASME 80 (1958) 70-78, as quoted in Incropera
       (2007), Ch. 7.
    """
    Re, Pr = _arr(Re, "Re"), _arr(Pr, "Pr", positive=True)
    check_range("Nu_rotating_cylinder (Eq. 27)", "Re", Re, 0.0, 4.3e5)
    check_range("Nu_rotating_cylinder (Eq. 27)", "Pr", Pr, 0.7, 670.0)
    return _out(0.133 * Re ** (2.0 / 3.0) * Pr ** (1.0 / 3.0))


def _flat_plate(name, C, Re, Pr):
    Re, Pr = _arr(Re, "Re"), _arr(Pr, "Pr", positive=True)
    check_range(name, "Re", Re, 0.0, 5e5)
    check_range(name, "Pr", Pr, 0.6, math.inf)
    return _out(C * Re**0.5 * Pr ** (1.0 / 3.0))


def Nu_flat_plate_laminar_average(Re, Pr):
    r"""Laminar flat plate in parallel flow, plate average (corrected Eq. 28).

    .. math:: \overline{Nu}_L = 0.664 \, Re_L^{1/2} Pr^{1/3}

    Parameters
    ----------
    Re : float or array_like
        Reynolds number on the plate length L along the flow, [-].
    Pr : float or array_like
        Prandtl number, [-].

    Returns
    -------
    float or ndarray
        Average Nu_L over 0..L, [-].

    Notes
    -----
    Valid Re_L < 5e5 (laminar) and Pr ≥ 0.6 (warns outside). Boundary-layer theory
    needs Re ≫ 1; at feed speeds (mm/s, Re ~ 10-200) blend with natural convection.

    References
    ----------
    .. [1] Paper, Eq. 28 (prints the local 0.332); AUDIT §1, Eq. 28.
    .. [2] Incropera (2007), Eq. 7.30.
    """
    return _flat_plate("Nu_flat_plate_laminar_average", 0.664, Re, Pr)


def Nu_flat_plate_laminar_local(Re, Pr):
    r"""Local laminar flat-plate Nusselt number: the paper's Eq. 28 as printed.

    .. math:: Nu_x = 0.332 \, Re_x^{1/2} Pr^{1/3}

    Parameters
    ----------
    Re : float or array_like
        Reynolds number on the distance x from the leading edge, [-].
    Pr : float or array_like
        Prandtl number, [-].

    Returns
    -------
    float or ndarray
        Local Nu_x, [-].

    Notes
    -----
    Named variant for reproducing the paper only: used as a plate average it halves h
    (AUDIT §1, Eq. 28). Valid Re_x < 5e5, Pr ≥ 0.6 (warns outside).

    References
    ----------
    .. [1] Paper, Eq. 28. Incropera (2007), Eq. 7.23.
    """
    return _flat_plate("Nu_flat_plate_laminar_local (Eq. 28 as printed)", 0.332, Re, Pr)


def Nu_plate_normal_to_flow(Re, Pr):
    r"""Flat face normal to the flow, Hilpert form (paper Eq. 29).

    .. math:: Nu_L = 0.228 \, Re_L^{0.731} Pr^{1/3}

    Parameters
    ----------
    Re : float or array_like
        Reynolds number on the face height L across the flow, [-].
    Pr : float or array_like
        Prandtl number, [-].

    Returns
    -------
    float or ndarray
        Nu_L, [-].

    Notes
    -----
    Valid 4e3 ≤ Re ≤ 1.5e4 and Pr ≳ 0.7 (checked as ≥ 0.7); warns outside. Re = 0
    returns 0 without warning. At feed speeds Re is 20-170 (AUDIT §1, Eq. 29): blend
    with natural convection.

    References
    ----------
    .. [1] Paper, Eq. 29; AUDIT §1, Eq. 29.
    .. [2] Incropera (2007), Eq. 7.52, Table 7.3 (vertical flat plate, gas).
    """
    Re, Pr = _arr(Re, "Re"), _arr(Pr, "Pr", positive=True)
    _check_nonzero("Nu_plate_normal_to_flow (Eq. 29)", "Re", Re, 4e3, 1.5e4)
    check_range("Nu_plate_normal_to_flow (Eq. 29)", "Pr", Pr, 0.7, math.inf)
    return _out(0.228 * Re**0.731 * Pr ** (1.0 / 3.0))


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
    .. [1] AUDIT §1, Eq. 29. Incropera (2007), §9.9.
    .. [2] S. W. Churchill, AIChE J. 23 (1977) 10-16.
    """
    if not n > 0:
        raise ValueError(f"n must be > 0, got {n!r}")
    F, N = _arr(Nu_forced, "Nu_forced"), _arr(Nu_natural, "Nu_natural")
    return _out((F**n + N**n if assisting else np.abs(F**n - N**n)) ** (1.0 / n))


# --------------------------------------------- surface-level film coefficients h
def _temperature(name, T):
    T = float(T)
    if not math.isfinite(T) or T <= 0.0:
        raise ValueError(f"{name} must be an absolute temperature in K (> 0), got {T!r}")
    return T


_NATURAL_NU = {
    "horizontal_cylinder": Nu_natural_horizontal_cylinder_Morgan,
    "vertical_plate": Nu_natural_vertical_plate,
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
    the Nusselt functions and from :func:`~feedtherm.physics.air.air_properties`.

    References
    ----------
    .. [1] Paper, Eqs. 24-26; AUDIT §1, Eqs. 24-26. Incropera (2007), §9.6.
    """
    if orientation not in _NATURAL_NU:
        raise ValueError(f"unknown orientation {orientation!r}; valid choices: "
                         + ", ".join(repr(o) for o in NATURAL_ORIENTATIONS))
    Ts, Ta = _temperature("T_surface", T_surface), _temperature("T_ambient", T_ambient)
    L = float(_arr(L, "L", positive=True))
    if Ts < Ta:
        orientation = _SWAP.get(orientation, orientation)
    air = air_properties(film_temperature(Ts, Ta))
    Ra = rayleigh(grashof(L, Ts, Ta, air.kinematic_viscosity, air.expansion_coefficient),
                  air.prandtl)
    return h_from_nusselt(_NATURAL_NU[orientation](Ra), air.conductivity, L)


def h_rotating_cylinder(d, n_rpm, T_film):
    r"""Film coefficient of a cylinder (screw shaft, nut, pulley) rotating in still air.

    .. math::

        h = \frac{k}{d} \, 0.133 \, Re_\omega^{2/3} Pr^{1/3}, \quad
        Re_\omega = \frac{\omega d^2}{\nu}, \quad \omega = \frac{2\pi |n|}{60}

    Parameters
    ----------
    d : float
        Outer diameter, [m].
    n_rpm : float
        Rotational speed, [rpm]; sign ignored (screw: n_s; nut or pulley: n_n).
    T_film : float
        Film temperature, [K].

    Returns
    -------
    float
        h, [W/(m²·K)]; 0 at n = 0 (add natural convection with :func:`h_mixed`).

    Notes
    -----
    Validity as :func:`Nu_rotating_cylinder` (Re_ω < 4.3e5, 0.7 < Pr < 670).

    References
    ----------
    .. [1] Paper, Eqs. 24 and 27; AUDIT §1, Eq. 27.
    """
    air = air_properties(_temperature("T_film", T_film))
    d = float(_arr(d, "d", positive=True))
    Re = reynolds_rotating(2.0 * math.pi * float(n_rpm) / 60.0, d, air.kinematic_viscosity)
    return h_from_nusselt(Nu_rotating_cylinder(Re, air.prandtl), air.conductivity, d)


def h_flat_plate_forced(L, u, T_film):
    r"""Plate-average film coefficient of a face moving parallel to itself (Eq. 28 corrected).

    .. math:: h = \frac{k}{L} \, 0.664 \, Re_L^{1/2} Pr^{1/3}, \quad Re_L = |u| L/\nu

    Parameters
    ----------
    L : float
        Length of the face along the motion, [m].
    u : float
        Speed relative to still air, [m/s]; sign ignored.
    T_film : float
        Film temperature, [K].

    Returns
    -------
    float
        h, [W/(m²·K)].

    Notes
    -----
    Validity as :func:`Nu_flat_plate_laminar_average` (Re_L < 5e5, Pr ≥ 0.6).

    References
    ----------
    .. [1] Paper, Eqs. 24 and 28; AUDIT §1, Eq. 28.
    """
    air = air_properties(_temperature("T_film", T_film))
    L = float(_arr(L, "L", positive=True))
    Re = reynolds(u, L, air.kinematic_viscosity)
    return h_from_nusselt(Nu_flat_plate_laminar_average(Re, air.prandtl), air.conductivity, L)


def h_face_normal_to_motion(L, u, T_film):
    r"""Film coefficient of a face normal to its direction of motion (Eq. 29 form).

    .. math:: h = \frac{k}{L} \, 0.228 \, Re_L^{0.731} Pr^{1/3}, \quad Re_L = |u| L/\nu

    Parameters
    ----------
    L : float
        Height of the face across the motion, [m].
    u : float
        Speed relative to still air, [m/s]; sign ignored.
    T_film : float
        Film temperature, [K].

    Returns
    -------
    float
        h, [W/(m²·K)].

    Notes
    -----
    Valid 4e3 ≤ Re_L ≤ 1.5e4 (warns outside, i.e. at every feed speed of the paper);
    blend with natural convection through :func:`h_mixed`.

    References
    ----------
    .. [1] Paper, Eqs. 24 and 29; AUDIT §1, Eq. 29.
    """
    air = air_properties(_temperature("T_film", T_film))
    L = float(_arr(L, "L", positive=True))
    Re = reynolds(u, L, air.kinematic_viscosity)
    return h_from_nusselt(Nu_plate_normal_to_flow(Re, air.prandtl), air.conductivity, L)


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
    """
    if not n > 0:
        raise ValueError(f"n must be > 0, got {n!r}")
    F, N = _arr(h_forced, "h_forced"), _arr(h_natural, "h_natural")
    return _out((F**n + N**n) ** (1.0 / n))
