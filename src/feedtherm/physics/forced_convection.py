"""Forced convection of the paper's §3.2 (Eqs. 27-29), corrected.

Nusselt correlations of rotating and translating surfaces (pure functions of Re, Pr;
scalars or arrays) and surface-level helpers returning h [W/(m²·K)] with air properties
at the film temperature.  Temperatures in K.

Corrections to the printed paper (docs/paper-audit.md §1): Eq. 24 L in m; Eq. 27 Re = ωd²/ν;
Eq. 28 plate average 0.664 (the printed local 0.332 is kept as the named variant
:func:`Nu_flat_plate_laminar_local`); Eq. 29 valid only for 4e3 < Re < 1.5e4, so at
feed speeds blend with natural convection
(:func:`~feedtherm.physics.convection.h_mixed`).

"Incropera (2007)" is F. P. Incropera, D. P. DeWitt, T. L. Bergman, A. S. Lavine,
*Fundamentals of Heat and Mass Transfer*, 6th ed., Wiley, 2007.
"""

from __future__ import annotations

import math

from feedtherm.physics._arrays import scalar_or_array as _out
from feedtherm.physics._checks import absolute_temperature as _temperature
from feedtherm.physics._checks import check_range_nonzero as _check_nonzero
from feedtherm.physics._checks import finite_array as _arr
from feedtherm.physics.air import properties_air
from feedtherm.physics.dimensionless import h_from_nusselt, reynolds, reynolds_rotating
from feedtherm.physics.validity import check_range


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
    .. [1] Paper, Eq. 27; docs/paper-audit.md §1, Eq. 27.
    .. [2] Kays & Bjorklund, Trans. ASME 80 (1958) 70-78, as quoted in Incropera
       (2007), Ch. 7.

    Examples
    --------
    0.133·1000^(2/3)·0.7^(1/3) = 0.133·100·0.887904 = 11.809.

    >>> round(Nu_rotating_cylinder(1000.0, 0.7), 3)
    11.809
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
    .. [1] Paper, Eq. 28 (prints the local 0.332); docs/paper-audit.md §1, Eq. 28.
    .. [2] Incropera (2007), Eq. 7.30.

    Examples
    --------
    Incropera Eq. 7.30: 0.664·(1e4)^(1/2)·0.7^(1/3) = 0.664·100·0.887904 = 58.957.

    >>> round(Nu_flat_plate_laminar_average(1e4, 0.7), 3)
    58.957
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
    (docs/paper-audit.md §1, Eq. 28). Valid Re_x < 5e5, Pr ≥ 0.6 (warns outside).

    References
    ----------
    .. [1] Paper, Eq. 28. Incropera (2007), Eq. 7.23.

    Examples
    --------
    Incropera Eq. 7.23: 0.332·(1e4)^(1/2)·0.7^(1/3) = 0.332·100·0.887904 = 29.478, half the
    plate average.

    >>> round(Nu_flat_plate_laminar_local(1e4, 0.7), 3)
    29.478
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
    returns 0 without warning. At feed speeds Re is 20-170 (docs/paper-audit.md §1, Eq. 29): blend
    with natural convection.

    References
    ----------
    .. [1] Paper, Eq. 29; docs/paper-audit.md §1, Eq. 29.
    .. [2] Incropera (2007), Eq. 7.52, Table 7.3 (vertical flat plate, gas).

    Examples
    --------
    Incropera Table 7.3 (C = 0.228, m = 0.731): 0.228·(1e4)^0.731·0.7^(1/3)
    = 0.228·10^2.924·0.887904 = 0.228·839.46·0.887904 = 169.94.

    >>> round(Nu_plate_normal_to_flow(1e4, 0.7), 2)
    169.94
    """
    Re, Pr = _arr(Re, "Re"), _arr(Pr, "Pr", positive=True)
    _check_nonzero("Nu_plate_normal_to_flow (Eq. 29)", "Re", Re, 4e3, 1.5e4)
    check_range("Nu_plate_normal_to_flow (Eq. 29)", "Pr", Pr, 0.7, math.inf)
    return _out(0.228 * Re**0.731 * Pr ** (1.0 / 3.0))


def Nu_cylinder_crossflow_Churchill_Bernstein(Re, Pr):
    r"""Mean Nusselt number of a cylinder in cross flow (Churchill and Bernstein).

    .. math::

        Nu_D = 0.3 + \frac{0.62\, Re_D^{1/2} Pr^{1/3}}{[1 + (0.4/Pr)^{2/3}]^{1/4}}
               \left[1 + \left(\frac{Re_D}{282\,000}\right)^{5/8}\right]^{4/5}

    Parameters
    ----------
    Re : float or array_like
        Reynolds number on the diameter, u D/ν, [-].
    Pr : float or array_like
        Prandtl number, [-].

    Returns
    -------
    float or ndarray
        Nu_D, [-].

    Notes
    -----
    Valid for Re·Pr ≥ 0.2 (warns below; every Re of a room's air, 0.05-1 m/s past a 20-200 mm
    part, lies far above). Re = 0 returns 0 without warning: in still air the transfer is
    natural convection's, which the surface model adds (mixed convection), not the
    correlation's conduction limit 0.3.

    References
    ----------
    .. [1] S. W. Churchill and M. Bernstein, J. Heat Transfer 99, 300-306 (1977).
    .. [2] Incropera (2007), Eq. 7.54.

    Examples
    --------
    Re = 1000, Pr = 0.7 by hand: Re^(1/2) = 31.6228, Pr^(1/3) = 0.887904,
    [1 + (0.4/0.7)^(2/3)]^(1/4) = 1.688598^(1/4) = 1.139943, so the middle term is
    0.62·31.6228·0.887904/1.139943 = 15.27124; [1 + (1000/282000)^(5/8)]^(4/5) =
    1.029413^(4/5) = 1.023462; Nu = 0.3 + 15.27124·1.023462 = 15.9296.

    >>> round(Nu_cylinder_crossflow_Churchill_Bernstein(1000.0, 0.7), 3)
    15.93
    """
    Re, Pr = _arr(Re, "Re"), _arr(Pr, "Pr", positive=True)
    _check_nonzero("Nu_cylinder_crossflow_Churchill_Bernstein", "Re*Pr", Re * Pr, 0.2, math.inf)
    nu = 0.3 + 0.62 * Re**0.5 * Pr ** (1.0 / 3.0) / (1.0 + (0.4 / Pr) ** (2.0 / 3.0)) ** 0.25 \
        * (1.0 + (Re / 282_000.0) ** 0.625) ** 0.8
    return _out(nu * (Re > 0.0))


def h_cylinder_crossflow(d, u, T_film):
    r"""Film coefficient of a cylinder in a cross flow of air (Churchill and Bernstein).

    .. math:: h = \frac{k}{d} Nu_D(Re_D, Pr), \quad Re_D = |u| d/\nu

    Parameters
    ----------
    d : float
        Diameter, [m].
    u : float
        Air speed across the axis, [m/s]; sign ignored.
    T_film : float
        Film temperature, [K].

    Returns
    -------
    float
        h, [W/(m²·K)].

    Notes
    -----
    Validity as :func:`Nu_cylinder_crossflow_Churchill_Bernstein` (Re·Pr ≥ 0.2).

    References
    ----------
    .. [1] Incropera (2007), Eq. 7.54.

    Examples
    --------
    A 32 mm screw in a 0.2 m/s draught, air at 300 K (CoolProp: k = 0.0263845 W/(m·K),
    ν = 1.57497e-5 m²/s, Pr = 0.707064): Re = 0.2·0.032/1.57497e-5 = 406.357, Re^(1/2) = 20.15829,
    Pr^(1/3) = 0.890881, [1 + (0.4/Pr)^(2/3)]^(1/4) = 1.684018^(1/4) = 1.139165, middle term
    0.62·20.15829·0.890881/1.139165 = 9.774132; [1 + (406.357/282000)^(5/8)]^(4/5) =
    1.016756^(4/5) = 1.013382; Nu = 0.3 + 9.774132·1.013382 = 10.20493,
    h = 10.20493·0.0263845/0.032 = 8.414 W/(m²·K).

    >>> round(h_cylinder_crossflow(0.032, 0.2, 300.0), 3)
    8.414
    """
    air = properties_air(_temperature("T_film", T_film))
    d = float(_arr(d, "d", positive=True))
    Re = reynolds(u, d, air.kinematic_viscosity)
    return h_from_nusselt(Nu_cylinder_crossflow_Churchill_Bernstein(Re, air.prandtl), air.conductivity, d)


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
    .. [1] Paper, Eqs. 24 and 27; docs/paper-audit.md §1, Eq. 27.

    Examples
    --------
    docs/paper-audit.md §4, screw shaft Ø32 at 396 rpm: 18.8 W/(m²·K) with Incropera's air at
    300 K. With CoolProp air at the film temperature 298.15 K (k = 0.026247 W/(m·K),
    ν = 1.55770e-5 m²/s, Pr = 0.70730): ω = 41.4690 rad/s, Re = 41.4690·0.032²/1.55770e-5
    = 2726.1, Re^(2/3) = 195.146, Pr^(1/3) = 0.89098, Nu = 0.133·195.146·0.89098 = 23.125,
    h = 23.125·0.026247/0.032 = 18.97 W/(m²·K).

    >>> round(h_rotating_cylinder(0.032, 396.0, 298.15), 2)
    18.97
    """
    air = properties_air(_temperature("T_film", T_film))
    d = float(_arr(d, "d", positive=True))
    Re = reynolds_rotating(2.0 * math.pi * float(n_rpm) / 60.0, d, air.kinematic_viscosity)
    return h_from_nusselt(Nu_rotating_cylinder(Re, air.prandtl), air.conductivity, d)


def h_flat_plate_laminar_average(L, u, T_film):
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
    .. [1] Paper, Eqs. 24 and 28; docs/paper-audit.md §1, Eq. 28.

    Examples
    --------
    docs/paper-audit.md §4: a 0.3 m table at 3 mm/s has h = 0.39 W/(m²·K) (Incropera's air).
    With CoolProp air at 300 K (k = 0.026384 W/(m·K), ν = 1.57497e-5 m²/s, Pr = 0.70706):
    Re = 0.003·0.3/1.57497e-5 = 57.144, Re^(1/2) = 7.5594, Pr^(1/3) = 0.89088,
    Nu = 0.664·7.5594·0.89088 = 4.4717, h = 4.4717·0.026384/0.3 = 0.3933 W/(m²·K).

    >>> round(h_flat_plate_laminar_average(0.3, 0.003, 300.0), 4)
    0.3933
    """
    air = properties_air(_temperature("T_film", T_film))
    L = float(_arr(L, "L", positive=True))
    Re = reynolds(u, L, air.kinematic_viscosity)
    return h_from_nusselt(Nu_flat_plate_laminar_average(Re, air.prandtl), air.conductivity, L)


def h_plate_normal_to_flow(L, u, T_film):
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
    .. [1] Paper, Eqs. 24 and 29; docs/paper-audit.md §1, Eq. 29.

    Examples
    --------
    A 0.1 m face at 1.589 m/s, air at 300 K as above (CoolProp): Re = 1.589·0.1/1.57497e-5
    = 10089, Re^0.731 = 844.92, Nu = 0.228·844.92·0.89088 = 171.62,
    h = 171.62·0.026384/0.1 = 45.28 W/(m²·K).

    >>> round(h_plate_normal_to_flow(0.1, 1.589, 300.0), 2)
    45.28
    """
    air = properties_air(_temperature("T_film", T_film))
    L = float(_arr(L, "L", positive=True))
    Re = reynolds(u, L, air.kinematic_viscosity)
    return h_from_nusselt(Nu_plate_normal_to_flow(Re, air.prandtl), air.conductivity, L)
