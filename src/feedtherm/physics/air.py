"""Thermophysical properties of dry air (CoolProp's values, tabulated at one atmosphere).

All convection correlations of the paper (§3.2, Eqs. 24-29) need the properties of air
at the *qualitative temperature* ε, which the paper leaves undefined in Eq. 25; the
review (docs/paper-audit.md §1, Eq. 25) identifies it as the film temperature
:math:`T_f = (T_s + T_\\infty)/2`, the textbook choice (Incropera et al. 2007, §7.1 and
§9.6).  :func:`film_temperature` computes it and :func:`properties_air` returns the
properties there.

The properties are CoolProp's (Lemmon et al. 2000 / Lemmon & Jacobsen 2004).  At one standard
atmosphere they are read from a table of CoolProp's values every kelvin
(:mod:`.air_table`), because importing CoolProp takes seconds and a command such as
``feedtherm heat`` should answer at once; other pressures and temperatures outside the
table ask CoolProp itself.
"""

from __future__ import annotations

import bisect
import functools
import math
from dataclasses import dataclass

import numpy as np

from feedtherm.physics.air_table import P_TABLE, T_FIRST, T_LAST, coolprop_row, read_table
from feedtherm.physics.validity import check_range

#: Standard atmosphere, [Pa].
P_ATM = P_TABLE

#: Validity range of :func:`properties_air` in this package, [K].  CoolProp's equation of
#: state covers a much wider range; 200-500 K is the range in which the ideal-gas
#: expansion coefficient and the single-phase, dry-air assumptions are checked here.
T_MIN, T_MAX = 200.0, 500.0

#: Away from the table, temperatures are rounded to this many decimals of a kelvin before
#: the (cached) CoolProp call; 0.01 K changes no property by more than ~3e-5 relative.
_T_DECIMALS = 2


@dataclass(frozen=True)
class AirProperties:
    """Properties of dry air at one state point (all SI).

    Attributes
    ----------
    temperature : float
        Temperature at which the properties apply, [K].
    density : float
        Mass density, [kg/m³].
    specific_heat : float
        Isobaric specific heat capacity, [J/(kg·K)].
    conductivity : float
        Thermal conductivity, [W/(m·K)] (the paper's λ in Eq. 24).
    dynamic_viscosity : float
        Dynamic viscosity μ, [Pa·s].
    kinematic_viscosity : float
        Kinematic viscosity ν = μ/ρ, [m²/s] (the paper's v_a in Eq. 26, there wrongly
        given in mm²/s).
    prandtl : float
        Prandtl number c_p μ / k, [-].
    expansion_coefficient : float
        Volumetric thermal expansion coefficient β, [1/K], ideal-gas value 1/T.
    diffusivity : float
        Thermal diffusivity α = k/(ρ c_p), [m²/s].
    """

    temperature: float
    density: float
    specific_heat: float
    conductivity: float
    dynamic_viscosity: float
    kinematic_viscosity: float
    prandtl: float
    expansion_coefficient: float
    diffusivity: float


def film_temperature(T_surface, T_ambient):
    r"""Film temperature, the reference temperature for air properties.

    .. math:: T_f = \frac{T_s + T_\infty}{2}

    Parameters
    ----------
    T_surface : float or array_like
        Surface temperature, [K].
    T_ambient : float or array_like
        Free-stream / ambient air temperature, [K].

    Returns
    -------
    float or ndarray
        Film temperature, [K].

    Notes
    -----
    This is the paper's "qualitative temperature" ε of Eq. 25, which the printed equation
    shows as if it were an exponent (docs/paper-audit.md §1, Eq. 25).

    References
    ----------
    .. [1] Paper, Eq. 25 (ε).
    .. [2] Incropera, DeWitt, Bergman, Lavine, *Fundamentals of Heat and Mass Transfer*,
       6th ed., Wiley, 2007, §7.1 (film temperature).

    Examples
    --------
    A surface at 30 °C in air at 20 °C: T_f = (303.15 + 293.15)/2 = 596.3/2 = 298.15 K.

    >>> round(film_temperature(303.15, 293.15), 2)
    298.15
    """
    if type(T_surface) is float and type(T_ambient) is float:  # a boundary condition's call: the same sum, no arrays
        return (T_surface + T_ambient) / 2.0
    mean = (np.asarray(T_surface, dtype=float) + np.asarray(T_ambient, dtype=float)) / 2.0
    return float(mean) if mean.ndim == 0 else mean


def properties_air(T, p=P_ATM):
    r"""Properties of dry air at temperature ``T`` and pressure ``p``.

    Density, specific heat, viscosity and conductivity come from CoolProp's pseudo-pure
    fluid ``"Air"`` (Lemmon et al. 2000 equation of state, Lemmon & Jacobsen 2004
    transport): at one standard atmosphere and 110-1400 K from the table of its values
    every kelvin (:mod:`feedtherm.physics.air_table`), interpolated linearly (ρT, c_p, μ, k:
    within 5e-6 of CoolProp), elsewhere from CoolProp itself.  Derived quantities:

    .. math::

        \nu = \frac{\mu}{\rho}, \qquad
        Pr = \frac{c_p \mu}{k}, \qquad
        \alpha = \frac{k}{\rho c_p}, \qquad
        \beta = \frac{1}{T}

    Parameters
    ----------
    T : float
        Temperature, [K] (for convection: the film temperature).
    p : float, optional
        Absolute pressure, [Pa]; default one standard atmosphere, 101325 Pa.

    Returns
    -------
    AirProperties
        Frozen record of the properties, SI units.

    Raises
    ------
    ValueError
        If ``T`` or ``p`` is not a finite positive number.

    Notes
    -----
    *Validity.*  A :class:`~feedtherm.physics.validity.CorrelationRangeWarning` is
    emitted for T outside [200, 500] K, the range this package checks; CoolProp still
    returns a value there.

    *Expansion coefficient.*  β is the ideal-gas value 1/T, as in the paper's Eq. 26
    (docs/paper-audit.md §1, Eq. 26: β = 1/T_f in 1/K).  For air at 1 atm and 200-500 K the real-gas value
    :math:`-\rho^{-1}(\partial\rho/\partial T)_p` from CoolProp is larger by only
    0.04-0.9 %.

    *Comparison with Incropera Table A.4.*  The table's densities correspond to
    p = 1 bar = 10⁵ Pa, not 1 atm (1.1614 kg/m³ at 300 K is RT/M at 10⁵ Pa); at 1 atm
    CoolProp gives ρ and ν about 1.3 % different from the table, at 10⁵ Pa within 0.5 %.
    The other properties hardly depend on pressure and agree within ~1 %.

    CoolProp's results are cached on T rounded to 0.01 K (and p); the function is pure.

    References
    ----------
    .. [1] I. H. Bell, J. Wronski, S. Quoilin, V. Lemort, "Pure and Pseudo-pure Fluid
       Thermophysical Property Evaluation and the Open-Source Thermophysical Property
       Library CoolProp", Ind. Eng. Chem. Res. 53 (2014) 2498-2508.
    .. [2] E. W. Lemmon, R. T. Jacobsen, "Viscosity and Thermal Conductivity Equations
       for Nitrogen, Oxygen, Argon, and Air", Int. J. Thermophys. 25 (2004) 21-69.
    .. [3] Incropera, DeWitt, Bergman, Lavine, *Fundamentals of Heat and Mass Transfer*,
       6th ed., Wiley, 2007, Table A.4 (air at atmospheric pressure).
    .. [4] Paper, Eqs. 24-26 (λ, v_a, β).

    Examples
    --------
    Incropera Table A.4, air at 300 K (its densities are for 10⁵ Pa, see Notes):
    Pr = 0.707, ρ = 1.1614 kg/m³, k = 26.3e-3 W/(m·K); and β = 1/300 = 3.333e-3 1/K.

    >>> air = properties_air(300.0, p=1e5)
    >>> round(air.prandtl, 3), round(air.density, 2), round(air.conductivity, 3)
    (0.707, 1.16, 0.026)
    >>> round(air.expansion_coefficient * 1e3, 3)
    3.333
    """
    T = _positive_finite("T", T)
    p = _positive_finite("p", p)
    check_range("properties_air (CoolProp Air)", "T [K]", T, T_MIN, T_MAX)
    return _properties(T, p)


@functools.lru_cache(maxsize=64)
def _properties(T: float, p: float) -> AirProperties:
    """:func:`properties_air` past its checks, kept: a surface in mixed convection takes the air at
    its film temperature twice, for the forced and for the natural part."""
    if p == P_TABLE and T_FIRST <= T <= T_LAST:
        rho, cp, mu, k = _tabulated(T)
    else:
        rho, cp, mu, k = _coolprop_state(round(T, _T_DECIMALS), p)
    return AirProperties(
        temperature=T,
        density=rho,
        specific_heat=cp,
        conductivity=k,
        dynamic_viscosity=mu,
        kinematic_viscosity=mu / rho,
        prandtl=cp * mu / k,
        expansion_coefficient=1.0 / T,
        diffusivity=k / (rho * cp),
    )


@functools.lru_cache(maxsize=4096)
def _coolprop_state(T: float, p: float) -> tuple[float, float, float, float]:
    """Density, c_p, μ and k of air from CoolProp (cached; T already rounded)."""
    return coolprop_row(T, p)


@functools.lru_cache(maxsize=1)
def _table() -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The table's columns: T, ρT (nearly constant, so that a straight line between rows fits it), c_p, μ, k."""
    T, rho, cp, mu, k = read_table().T
    return T, rho * T, cp, mu, k


@functools.lru_cache(maxsize=1)
def _rows() -> tuple[list[float], list[tuple[float, float, float, float]]]:
    """The table as Python floats: its temperatures, and ρT, c_p, μ and k per row."""
    grid, rho_T, cp, mu, k = _table()
    return grid.tolist(), list(zip(rho_T.tolist(), cp.tolist(), mu.tolist(), k.tolist()))


def _tabulated(T: float) -> tuple[float, float, float, float]:
    """Density, c_p, μ and k at T [K] and one atmosphere, interpolated in the table.

    The arithmetic of ``numpy.interp`` (the same row, ``slope (T - T_j) + f_j``, the same floats)
    on Python floats: one search for all four columns, without four array calls per evaluation.
    """
    grid, rows = _rows()
    j = bisect.bisect_right(grid, T) - 1
    if j >= len(grid) - 1:  # T at the table's last temperature
        values = rows[-1]
    else:
        t0, t1, below, above = grid[j], grid[j + 1], rows[j], rows[j + 1]
        values = tuple((f1 - f0) / (t1 - t0) * (T - t0) + f0 for f0, f1 in zip(below, above))
    rho_T, cp, mu, k = values
    return rho_T / T, cp, mu, k


def _positive_finite(name: str, value) -> float:
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real number, got {value!r}") from None
    if not math.isfinite(x) or x <= 0.0:
        raise ValueError(f"{name} must be finite and > 0 (SI units: K, Pa), got {x!r}")
    return x
