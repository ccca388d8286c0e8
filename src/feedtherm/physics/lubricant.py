r"""Lubricant kinematic viscosity against temperature: ISO VG grade and Walther's equation.

A mineral or synthetic oil (or a grease's base oil) is known by two points of its
viscosity–temperature line: ν at 40 °C and at 100 °C.  The first is the midpoint of its ISO VG
grade (ISO 3448), the second is stated on the oil's data sheet.  Between and near those
points, ASTM D341's form of Walther's equation gives ν(T):

.. math:: \log_{10}\log_{10}(\nu + 0.7) = A - B\log_{10} T

with ν in mm²/s and T in K.  Interfaces are SI (ν in m²/s, T in K); the mm²/s forms of the
standards are converted inside.

References
----------
.. [1] ISO 3448:1992, *Industrial liquid lubricants — ISO viscosity classification*, Table 1.
.. [2] ASTM D341-09, *Standard Practice for Viscosity-Temperature Charts for Liquid Petroleum
   Products*, Section 5 (equations); Walther, C., *Erdöl und Teer* 7 (1931) 382–384.
"""

from __future__ import annotations

import math
import re

import numpy as np

from feedtherm.physics._arrays import FLOATS
from feedtherm.physics._arrays import scalar_or_array as _out
from feedtherm.physics.validity import check_range

#: ISO 3448 viscosity grades: grade number -> midpoint kinematic viscosity at 40 °C [mm²/s].
#: The grade's limits are ±10 % of the midpoint.
ISO_VG_MIDPOINTS_MM2_S: dict[int, float] = {
    2: 2.2, 3: 3.2, 5: 4.6, 7: 6.8, 10: 10.0, 15: 15.0, 22: 22.0, 32: 32.0, 46: 46.0,
    68: 68.0, 100: 100.0, 150: 150.0, 220: 220.0, 320: 320.0, 460: 460.0, 680: 680.0,
    1000: 1000.0, 1500: 1500.0,
}

#: D341's Z = ν + 0.7 holds from 2.0 mm²/s up; below, the standard adds correction terms.
WALTHER_MIN_VISCOSITY_MM2_S = 2.0
_CELSIUS_40 = 313.15  # [K]
_CELSIUS_100 = 373.15  # [K]
_GRADE = re.compile(r"^\s*(?:ISO\s*)?(?:VG\s*)?(\d+)\s*$", re.IGNORECASE)
_NU_MAX = 0.1  # [m²/s]: a larger "viscosity" is a value in mm²/s passed as m²/s


def kinematic_viscosity_iso_vg(grade):
    r"""Kinematic viscosity at 40 °C of an ISO VG grade: the grade's midpoint (ISO 3448).

    Parameters
    ----------
    grade : int or str
        The grade, as its number (``100``) or written ``"ISO VG 100"`` / ``"VG 100"``.

    Returns
    -------
    float
        ν₄₀, [m²/s].

    Raises
    ------
    ValueError
        For a grade ISO 3448 does not define (the message lists those it does).

    Notes
    -----
    ISO 3448 defines 18 grades from VG 2 to VG 1500; each grade's limits are ±10 % of its
    midpoint, so a real oil of the grade may differ by that much.

    References
    ----------
    .. [1] ISO 3448:1992, Table 1.

    Examples
    --------
    ISO 3448: VG 100 has the midpoint 100 mm²/s (limits 90–110); VG 5 has 4.6 (4.14–5.06).

    >>> kinematic_viscosity_iso_vg("ISO VG 100"), kinematic_viscosity_iso_vg(5)
    (0.0001, 4.6e-06)
    """
    number = _grade_number(grade)
    if number not in ISO_VG_MIDPOINTS_MM2_S:
        known = ", ".join(str(g) for g in ISO_VG_MIDPOINTS_MM2_S)
        raise ValueError(f"ISO VG {number} is not an ISO 3448 grade; the grades are {known}")
    return ISO_VG_MIDPOINTS_MM2_S[number] / 1e6


def coefficients_viscosity_temperature_Walther(nu1, T1, nu2, T2):
    r"""Constants A, B of Walther's equation through two (ν, T) points (ASTM D341).

    With ν in mm²/s, T in K and decimal logarithms:

    .. math::
        B = \frac{\log\log(\nu_1 + 0.7) - \log\log(\nu_2 + 0.7)}{\log T_2 - \log T_1},
        \qquad A = \log\log(\nu_1 + 0.7) + B \log T_1

    Parameters
    ----------
    nu1, nu2 : float
        Kinematic viscosities, [m²/s], at
    T1, T2 : float
        the temperatures, [K]; T1 ≠ T2.

    Returns
    -------
    tuple of float
        (A, B), [-], for ν in mm²/s and T in K.

    Notes
    -----
    D341's Z = ν + 0.7 is accurate from ν = 2 mm²/s up; below it the standard adds
    correction terms, which are not implemented: a CorrelationRangeWarning is emitted.

    References
    ----------
    .. [1] ASTM D341-09, Section 5; Walther 1931.

    Examples
    --------
    An ISO VG 32 oil with ν₄₀ = 32, ν₁₀₀ = 5.4 mm²/s: log log 32.7 = log 1.514548 = 0.180283,
    log log 6.1 = log 0.785330 = −0.104948, log 313.15 = 2.495752, log 373.15 = 2.571883;
    B = (0.180283 + 0.104948)/(2.571883 − 2.495752) = 0.285231/0.076131 = 3.74658,
    A = 0.180283 + 3.74658·2.495752 = 9.53082.

    >>> A, B = coefficients_viscosity_temperature_Walther(32e-6, 313.15, 5.4e-6, 373.15)
    >>> round(A, 4), round(B, 4)
    (9.5308, 3.7466)
    """
    name = "coefficients_viscosity_temperature_Walther (ASTM D341)"
    z1 = _walther_z(_nu_mm2_s(nu1, "nu1"), name)
    z2 = _walther_z(_nu_mm2_s(nu2, "nu2"), name)
    t1, t2 = _kelvin(T1, "T1"), _kelvin(T2, "T2")
    if t1 == t2:
        raise ValueError(f"the two temperatures must differ, both are {t1:g} K")
    b = (z1 - z2) / (math.log10(t2) - math.log10(t1))
    return z1 + b * math.log10(t1), b


def kinematic_viscosity_Walther(T, A, B):
    r"""Kinematic viscosity at T from Walther's equation (ASTM D341).

    .. math:: \nu = 10^{10^{A - B\log_{10} T}} - 0.7 \quad [\mathrm{mm^2/s}]

    Parameters
    ----------
    T : float or array_like
        Temperature, [K].
    A, B : float
        Constants for ν in mm²/s and T in K (:func:`coefficients_viscosity_temperature_Walther`).

    Returns
    -------
    float or ndarray
        ν, [m²/s].

    Notes
    -----
    A result below 2 mm²/s lies where D341's Z = ν + 0.7 loses accuracy: a
    CorrelationRangeWarning is emitted.

    References
    ----------
    .. [1] ASTM D341-09, Section 5; Walther 1931.

    Examples
    --------
    The VG 32 oil of :func:`coefficients_viscosity_temperature_Walther` (A = 9.530815,
    B = 3.746578) at 80 °C: log 353.15 = 2.547959, A − B·2.547959 = 9.530815 − 9.546127
    = −0.015312, 10^−0.015312 = 0.965353, 10^0.965353 = 9.23321, ν = 9.23321 − 0.7
    = 8.533 mm²/s.

    >>> round(kinematic_viscosity_Walther(353.15, 9.530815, 3.746578) * 1e6, 3)
    8.533
    """
    if type(T) in FLOATS:  # the usual scalar call, without numpy's reductions
        T = float(T)
        bad = not math.isfinite(T) or T <= 0.0
    else:
        T = np.asarray(T, dtype=float)
        bad = np.any(~np.isfinite(T)) or np.any(T <= 0.0)
    if bad:
        raise ValueError(f"T must be an absolute temperature in K (> 0), got {T!r}")
    nu = 10.0 ** (10.0 ** (float(A) - float(B) * np.log10(T))) - 0.7
    check_range("kinematic_viscosity_Walther (ASTM D341)", "nu [mm²/s]", nu,
                WALTHER_MIN_VISCOSITY_MM2_S, math.inf)
    return _out(nu * 1e-6)


def kinematic_viscosity_lubricant(T, nu40, nu100):
    r"""Kinematic viscosity at T of an oil known at 40 °C and 100 °C (Walther, ASTM D341).

    The Walther line through (ν₄₀, 313.15 K) and (ν₁₀₀, 373.15 K), evaluated at T.

    Parameters
    ----------
    T : float or array_like
        Temperature, [K].
    nu40, nu100 : float
        Kinematic viscosities at 40 °C and 100 °C, [m²/s]; ν₁₀₀ < ν₄₀.

    Returns
    -------
    float or ndarray
        ν, [m²/s].

    Notes
    -----
    Interpolation between 40 and 100 °C is what D341's charts are built for; extrapolation
    a few tens of kelvin outside is usual practice (D341: valid between the oil's cloud point
    and its initial boiling point).  For a grease, pass the base oil's viscosities.

    References
    ----------
    .. [1] ASTM D341-09, Section 5; Walther 1931.

    Examples
    --------
    The VG 32 oil of :func:`coefficients_viscosity_temperature_Walther` at 80 °C: 8.533 mm²/s
    (hand calculation in :func:`kinematic_viscosity_Walther`); at its own points it returns
    32 and 5.4 mm²/s.

    >>> [round(kinematic_viscosity_lubricant(t, 32e-6, 5.4e-6) * 1e6, 3) for t in (313.15, 353.15, 373.15)]
    [32.0, 8.533, 5.4]
    """
    if not _nu_mm2_s(nu100, "nu100") < _nu_mm2_s(nu40, "nu40"):
        raise ValueError(f"nu100 must be smaller than nu40, got nu40 = {nu40!r}, nu100 = {nu100!r} m²/s")
    a, b = coefficients_viscosity_temperature_Walther(nu40, _CELSIUS_40, nu100, _CELSIUS_100)
    return kinematic_viscosity_Walther(T, a, b)


# --------------------------------------------------------------------------- helpers


def _grade_number(grade) -> int:
    if isinstance(grade, bool):
        raise ValueError(f"an ISO VG grade is a number such as 100 or 'ISO VG 100', got {grade!r}")
    if isinstance(grade, int):
        return grade
    match = _GRADE.match(grade) if isinstance(grade, str) else None
    if not match:
        raise ValueError(f"an ISO VG grade is written like 'ISO VG 100', got {grade!r}")
    return int(match.group(1))


def _nu_mm2_s(value, label) -> float:
    nu = float(value)
    if not math.isfinite(nu) or nu <= 0.0:
        raise ValueError(f"{label} must be a positive kinematic viscosity in m²/s, got {value!r}")
    if nu > _NU_MAX:
        raise ValueError(f"{label} = {nu:g} m²/s is not an oil viscosity; pass m²/s (e.g. 100 mm²/s = 1e-4 m²/s)")
    return nu * 1e6


def _kelvin(value, label) -> float:
    t = float(value)
    if not math.isfinite(t) or t <= 0.0:
        raise ValueError(f"{label} must be an absolute temperature in K (> 0), got {value!r}")
    return t


def _walther_z(nu_mm2_s: float, name: str) -> float:
    check_range(name, "nu [mm²/s]", nu_mm2_s, WALTHER_MIN_VISCOSITY_MM2_S, math.inf)
    return math.log10(math.log10(nu_mm2_s + 0.7))

