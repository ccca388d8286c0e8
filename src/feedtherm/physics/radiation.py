"""Radiative exchange of a small grey surface with large isothermal surroundings.

The paper omits radiation (docs/paper-audit.md §1, "missing"); at 20-30 °C it is comparable to
natural convection (h_r ≈ 1.8 W/(m²·K) at ε = 0.3 and ≈ 4.9 at ε = 0.8).  The
surroundings (walls of the room) are taken at the ambient air temperature.
Temperatures are in K.
"""

from __future__ import annotations

import math

import numpy as np

#: Stefan-Boltzmann constant, [W/(m²·K⁴)]: CODATA 2018, exact since the 2019 SI (it follows from
#: the defined h, c and k); scipy.constants holds the same value but takes 0.1 s to import.
SIGMA = 5.670374419e-8


def _outside(a: np.ndarray, low: float, high: float = math.inf) -> bool:
    """Whether an entry of ``a`` is not finite or lies outside (low, high]."""
    if a.ndim == 0:  # the common scalar case, without numpy's reductions
        v = float(a)
        return not (math.isfinite(v) and low < v <= high)
    return bool(np.any(~np.isfinite(a)) or np.any(a <= low) or np.any(a > high))


def _validate(emissivity, T_surface, T_ambient):
    eps = np.asarray(emissivity, dtype=float)
    if _outside(eps, 0.0, 1.0):
        raise ValueError(f"emissivity must lie in (0, 1], got {emissivity!r}")
    Ts = np.asarray(T_surface, dtype=float)
    Ta = np.asarray(T_ambient, dtype=float)
    for name, T in (("T_surface", Ts), ("T_ambient", Ta)):
        if _outside(T, 0.0):
            raise ValueError(f"{name} must be an absolute temperature in K (> 0)")
    return eps, Ts, Ta


def _validate_scalars(emissivity: float, T_surface: float, T_ambient: float) -> None:
    """:func:`_validate` for Python floats, with its messages."""
    if not (math.isfinite(emissivity) and 0.0 < emissivity <= 1.0):
        raise ValueError(f"emissivity must lie in (0, 1], got {emissivity!r}")
    for name, T in (("T_surface", T_surface), ("T_ambient", T_ambient)):
        if not (math.isfinite(T) and 0.0 < T):
            raise ValueError(f"{name} must be an absolute temperature in K (> 0)")


def _out(a):
    return float(a) if np.ndim(a) == 0 else a


def h_radiation(emissivity, T_surface, T_ambient):
    r"""Linearised radiation coefficient of a small grey surface in large surroundings.

    .. math:: h_r = \varepsilon \sigma (T_s^2 + T_{sur}^2)(T_s + T_{sur})

    so that :math:`q'' = h_r (T_s - T_{sur})` reproduces
    :func:`heat_flux_radiation` exactly.

    Parameters
    ----------
    emissivity : float or array_like
        Total hemispherical emissivity of the surface, (0, 1], [-].
    T_surface : float or array_like
        Surface temperature, [K].
    T_ambient : float or array_like
        Temperature of the surroundings, taken equal to the ambient air, [K].

    Returns
    -------
    float or ndarray
        h_r, [W/(m²·K)].

    Raises
    ------
    ValueError
        If the emissivity is outside (0, 1] or a temperature is not positive.

    Notes
    -----
    Valid for a grey, diffuse surface that is small compared with, and does not see
    itself or other warm parts of the machine in place of, isothermal surroundings.
    Near 300 K, h_r ≈ 4εσT³ ≈ 6.1 ε W/(m²·K).

    References
    ----------
    .. [1] docs/paper-audit.md §1, "missing" (radiation).
    .. [2] Incropera, DeWitt, Bergman, Lavine, *Fundamentals of Heat and Mass Transfer*,
       6th ed., Wiley, 2007, Eqs. 1.8-1.9.

    Examples
    --------
    docs/paper-audit.md §1 ("missing"): h_r ≈ 4.9 W/(m²·K) at ε = 0.8 near 300 K;
    4εσT³ = 4·0.8·5.670374e-8·300³ = 4.8992.

    >>> round(h_radiation(0.8, 300.0, 300.0), 4)
    4.8992
    """
    if type(emissivity) is float and type(T_surface) is float and type(T_ambient) is float:
        # a boundary condition's call, checked and computed without arrays: the same products (numpy
        # squares an array by multiplying it by itself, which Python's ** 2 does not always match)
        _validate_scalars(emissivity, T_surface, T_ambient)
        return emissivity * SIGMA * (T_surface * T_surface + T_ambient * T_ambient) * (T_surface + T_ambient)
    eps, Ts, Ta = _validate(emissivity, T_surface, T_ambient)
    return _out(eps * SIGMA * (Ts**2 + Ta**2) * (Ts + Ta))


def heat_flux_radiation(emissivity, T_surface, T_ambient):
    r"""Net radiative heat flux from a small grey surface to large surroundings.

    .. math:: q''_{rad} = \varepsilon \sigma (T_s^4 - T_{sur}^4)

    Parameters
    ----------
    emissivity : float or array_like
        Total hemispherical emissivity of the surface, (0, 1], [-].
    T_surface : float or array_like
        Surface temperature, [K].
    T_ambient : float or array_like
        Temperature of the surroundings, [K].

    Returns
    -------
    float or ndarray
        q'' leaving the surface, [W/m²]; negative when the surface is colder.

    Raises
    ------
    ValueError
        If the emissivity is outside (0, 1] or a temperature is not positive.

    Notes
    -----
    Same assumptions as :func:`h_radiation`.

    References
    ----------
    .. [1] Incropera, DeWitt, Bergman, Lavine, *Fundamentals of Heat and Mass Transfer*,
       6th ed., Wiley, 2007, Eq. 1.7.

    Examples
    --------
    Incropera Example 1.2: a steam pipe, D = 70 mm, T_s = 473 K, surroundings 298 K,
    ε = 0.8, loses q' = 421 W/m by radiation.

    >>> import math
    >>> round(heat_flux_radiation(0.8, 473.0, 298.0) * math.pi * 0.07)
    421
    """
    eps, Ts, Ta = _validate(emissivity, T_surface, T_ambient)
    return _out(eps * SIGMA * (Ts**4 - Ta**4))
