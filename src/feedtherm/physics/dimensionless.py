"""Dimensionless groups of convection (Gr, Ra, Re, Re_ω) and Eq. 24's h = Nu k/L.

Shared by :mod:`~feedtherm.physics.natural_convection` and
:mod:`~feedtherm.physics.forced_convection`, and re-exported by
:mod:`feedtherm.physics.convection`.  They live in a module of their own so that the
natural and forced modules can use them without importing the module that re-exports
them (which would be an import cycle).

Corrections to the printed paper (docs/paper-audit.md §1): Eq. 24 L in m; Eq. 26 ν in m²/s,
β = 1/T_f; Eq. 27 Re = ωd²/ν.

"Incropera (2007)" is F. P. Incropera, D. P. DeWitt, T. L. Bergman, A. S. Lavine,
*Fundamentals of Heat and Mass Transfer*, 6th ed., Wiley, 2007.
"""

from __future__ import annotations

import numpy as np

from feedtherm.physics._arrays import scalar_or_array as _out
from feedtherm.physics._checks import finite_array as _arr

#: Standard gravity, [m/s²].
G_STANDARD = 9.80665


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
    .. [1] Paper, Eq. 26; docs/paper-audit.md §1, Eq. 26. Incropera (2007), Eq. 9.12.

    Examples
    --------
    L = 0.1 m, ΔT = 10 K, air at 300 K (Incropera Table A.4: ν = 15.89e-6 m²/s), β = 1/300:
    Gr = 9.80665/300·10·0.1³/(15.89e-6)² = 3.26888e-4/2.52492e-10 = 1.2946e6.

    >>> round(grashof(0.1, 310.0, 300.0, 15.89e-6, 1 / 300) / 1e6, 4)
    1.2946
    """
    L, nu = _arr(L, "L", positive=True), _arr(nu, "nu", positive=True)
    if type(T_surface) is float and type(T_ambient) is float:  # a boundary condition's call: the same difference
        dT = abs(T_surface - T_ambient)
    else:
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

    Examples
    --------
    Ra = 1.2946e6·0.707 = 9.153e5.

    >>> round(rayleigh(1.2946e6, 0.707) / 1e5, 3)
    9.153
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

    Examples
    --------
    A 0.3 m table at 3 mm/s in air (ν = 15.89e-6 m²/s): Re = 0.003·0.3/15.89e-6 = 56.64
    (docs/paper-audit.md §4: 56.6).

    >>> round(reynolds(0.003, 0.3, 15.89e-6), 2)
    56.64
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
    The Re of Eq. 27, which the paper does not state (docs/paper-audit.md §1, Eq. 27).

    References
    ----------
    .. [1] W. M. Kays, I. S. Bjorklund, "Heat transfer from a rotating cylinder with and
       without crossflow", Trans. ASME 80 (1958) 70-78.

    Examples
    --------
    docs/paper-audit.md §4, screw shaft Ø32 at 396 rpm (41.469 rad/s):
    Re = 41.469·0.032²/15.89e-6 = 0.042464/15.89e-6 = 2672.4 (the review: 2672).

    >>> round(reynolds_rotating(41.469, 0.032, 15.89e-6), 1)
    2672.4
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
    .. [1] Paper, Eq. 24; docs/paper-audit.md §1, Eq. 24.

    Examples
    --------
    docs/paper-audit.md §4, screw shaft: h = 22.817·0.0263/0.032 = 18.753 W/(m²·K) (the
    review: 18.8); L in mm, as printed, would give 1000× less.

    >>> round(h_from_nusselt(22.817, 0.0263, 0.032), 3)
    18.753
    """
    return _out(_arr(Nu, "Nu") * _arr(k, "k", positive=True) / _arr(L, "L", positive=True))
