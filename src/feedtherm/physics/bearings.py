r"""Rolling-bearing friction torque and heat after Palmgren (paper Eqs. 15–22, corrected).

:math:`M = M_l + M_v` (load and viscous parts), :math:`H = M\omega`. Interfaces are SI
(loads [N], d_m [m], ν [m²/s], torque [N·m], heat [W], speed [rpm]); Palmgren's
N·mm/mm/mm²/s forms are converted inside. Corrections (docs/paper-audit.md §1): P₁ ≥ F_r (Eqs. 18,
20); deep-groove z = 4e-4..6e-4, not 9e-4 (Eq. 19); d_m³ in Eq. 21; 160e-7·f₀·d_m³ in
Eq. 22.

Functions of Palmgren's empirical model end in ``_Palmgren``: the SKF model (rolling,
sliding, seal and drag moments, SKF catalogue since 2004), the other one in use for the
same bearings, is in :mod:`feedtherm.physics.bearings_skf`; :func:`heat_bearing` serves both.

References
----------
.. [1] Paper, §3.1, Eqs. 15–22.
.. [2] Harris, T. A., Kotzalas, M. N., *Rolling Bearing Analysis*, 5th ed., CRC/Taylor
   & Francis, 2006, Vol. 1 *Essential Concepts of Bearing Technology*, chapter on
   friction: Palmgren's empirical torque, tables of z, y (load term) and f₀.
.. [3] Palmgren, A., *Ball and Roller Bearing Engineering*, 3rd ed., SKF Industries,
   Philadelphia, 1959.
.. [4] SKF General Catalogue (pre-2003 editions, "Frictional moment"): f₀ values;
   f₀ of a paired or double-row bearing is twice that of the single-row bearing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from feedtherm.physics._arrays import FLOATS
from feedtherm.physics._arrays import any_true as _any
from feedtherm.physics._arrays import scalar_or_array as _out
from feedtherm.physics.mechanics import heat_friction
from feedtherm.physics.validity import check_range

#: Palmgren's f₀ by bearing type and lubrication, [-]: Harris & Kotzalas 2006 (f₀ table
#: after Palmgren 1959); pairs take 2× the single-row value (SKF rule). Deep groove with
#: grease: Harris gives 0.7–2 (light to heavy series); 1.5 is docs/paper-audit.md §3's value, which
#: uses 2 per angular-contact bearing, 4 per pair. Typical values, not product data.
F0_TYPICAL: dict[str, dict[str, float]] = {
    "deep_groove": {"grease": 1.5, "oil_mist": 1.0, "oil_bath": 2.0},
    "angular_contact_single": {"grease": 2.0, "oil_mist": 1.7, "oil_bath": 3.3},
    "angular_contact_pair": {"grease": 4.0, "oil_mist": 3.4, "oil_bath": 6.6},
}

#: Range of Palmgren's load coefficient z for deep-groove ball bearings (Harris), [-].
Z_DEEP_GROOVE_RANGE = (4e-4, 6e-4)

#: Regime boundary of Palmgren's viscous torque, ν·n in [mm²/s · rpm].
VISCOUS_REGIME_LIMIT = 2000.0

# Unit-slip guards: d_m > 2 m or ν > 0.1 m²/s means mm or mm²/s was passed.
_DM_MAX = 2.0
_NU_MAX = 0.1


@dataclass(frozen=True)
class BearingTorque:
    """Palmgren friction torque of a bearing (or pair): ``load`` M_l (Eq. 16),
    ``viscous`` M_v (Eqs. 21–22 corrected) and ``total`` M_l + M_v, all [N·m]."""

    load: float
    viscous: float
    total: float


def f1_angular_contact_Palmgren(P0, C0):
    r"""Palmgren load coefficient f₁ for angular-contact ball bearings (Eq. 17).

    .. math:: f_1 = 0.001\,(P_0/C_0)^{0.33}

    Parameters
    ----------
    P0 : float or array_like
        Static equivalent load, [N]; not negative.
    C0 : float or array_like
        Basic static load rating, [N]; positive. For a pair, use the pair's P₀ and C₀.

    Returns
    -------
    float or ndarray
        f₁, [-].

    Notes
    -----
    z = 0.001, y = 0.33 are Harris's tabulated angular-contact values; Eq. 17 is
    correct as printed. Valid for 0 < P₀/C₀ ≤ 1; a warning is emitted outside.

    References
    ----------
    .. [1] Paper Eq. 17; Harris & Kotzalas 2006 (table of z, y); Palmgren 1959.

    Examples
    --------
    docs/paper-audit.md §3, front 25×62 pair, P₀ ≈ F_a = 3100 N, C₀ = 40 kN: f₁ = 4.3e-4
    (0.001·0.0775^0.33 = 0.001·e^(0.33·ln 0.0775) = 0.001·e^(−0.8440) = 4.300e-4).

    >>> round(f1_angular_contact_Palmgren(3100.0, 40e3) * 1e4, 2)
    4.3
    """
    return _f1(P0, C0, 1e-3, 0.33, "f1_angular_contact_Palmgren (Eq. 17)")


def f1_deep_groove_Palmgren(P0, C0, z=5e-4):
    r"""Palmgren load coefficient f₁ for deep-groove ball bearings (Eq. 19 corrected).

    .. math:: f_1 = z\,(P_0/C_0)^{0.55}, \qquad z = 4\times10^{-4} \ldots 6\times10^{-4}

    Parameters
    ----------
    P0 : float or array_like
        Static equivalent load, [N]; for deep-groove bearings
        P₀ = max(0.6F_r + 0.5F_a, F_r). Not negative.
    C0 : float or array_like
        Basic static load rating, [N]; positive.
    z : float, optional
        Palmgren's coefficient, [-]; default 5e-4, the middle of the tabulated range.

    Returns
    -------
    float or ndarray
        f₁, [-].

    Notes
    -----
    The paper prints z = 9e-4, which Harris does not tabulate; deep-groove bearings
    have z = 0.0004–0.0006 with y = 0.55 (docs/paper-audit.md §1, rows 19–20). A warning is emitted
    for z outside [4e-4, 6e-4] and for P₀/C₀ outside (0, 1].

    References
    ----------
    .. [1] Paper Eq. 19 (coefficient corrected); Harris & Kotzalas 2006 (table of z,
       y); Palmgren 1959.

    Examples
    --------
    P₀/C₀ = 1950/7800 = 0.25: 5e-4·0.25^0.55 = 5e-4·e^(0.55·ln 0.25) = 5e-4·e^(−0.76246)
    = 5e-4·0.46652 = 2.3326e-4.

    >>> round(f1_deep_groove_Palmgren(1950.0, 7800.0) * 1e4, 4)
    2.3326
    """
    z = _check(z, "z", "[-]", strict=True)
    check_range("f1_deep_groove_Palmgren (Eq. 19)", "z", z, *Z_DEEP_GROOVE_RANGE)
    return _f1(P0, C0, z, 0.55, "f1_deep_groove_Palmgren (Eq. 19)")


def P1_angular_contact_Palmgren(Fa, Fr):
    r"""Friction-equivalent load P₁, paired/double-row angular contact (Eq. 18).

    .. math:: P_1 = \max(1.4F_a - 0.1F_r,\; F_r)

    Parameters
    ----------
    Fa, Fr : float or array_like
        Axial load (including preload) and radial load magnitudes, [N]; not negative.

    Returns
    -------
    float or ndarray
        P₁, [N].

    Notes
    -----
    1.4F_a − 0.1F_r is Harris's form for *paired or double-row* angular-contact ball
    bearings (single-row: F_a − 0.1F_r). P₁ is the friction-equivalent load, not the
    "preload" of the paper. Harris's rule P₁ ≥ F_r, omitted by the paper, is applied:
    without it a lightly loaded bearing gets P₁ < 0.

    References
    ----------
    .. [1] Paper Eq. 18 (rule P₁ ≥ F_r added); Harris & Kotzalas 2006; Palmgren 1959.

    Examples
    --------
    docs/paper-audit.md §3, front pair: 1.4·3100 − 0.1·50 = 4335 N; without axial load the
    printed Eq. 18 gives −5 N, the rule P₁ ≥ F_r gives 50 N.

    >>> P1_angular_contact_Palmgren(3100.0, 50.0), P1_angular_contact_Palmgren(0.0, 50.0)
    (4335.0, 50.0)
    """
    Fa, Fr = _loads(Fa, Fr)
    return _out(np.maximum(1.4 * Fa - 0.1 * Fr, Fr))


def P1_deep_groove_Palmgren(Fa, Fr):
    r"""Friction-equivalent load P₁ of a deep-groove ball bearing (Eq. 20).

    .. math:: P_1 = \max(3F_a - 0.1F_r,\; F_r)

    Parameters
    ----------
    Fa, Fr : float or array_like
        Axial and radial load magnitudes, [N]; not negative.

    Returns
    -------
    float or ndarray
        P₁, [N].

    Notes
    -----
    Harris's rule P₁ ≥ F_r is applied; a floating bearing (F_a ≈ 0) gets P₁ = F_r.

    References
    ----------
    .. [1] Paper Eq. 20 (rule P₁ ≥ F_r added); Harris & Kotzalas 2006; Palmgren 1959.

    Examples
    --------
    docs/paper-audit.md §3, 6205 row: 3·2500 − 0.1·50 = 7495 N.

    >>> P1_deep_groove_Palmgren(2500.0, 50.0)
    7495.0
    """
    Fa, Fr = _loads(Fa, Fr)
    return _out(np.maximum(3.0 * Fa - 0.1 * Fr, Fr))


def torque_bearing_load_Palmgren(f1, P1, dm):
    r"""Load-dependent friction torque (Eq. 16, SI).

    .. math:: M_l = f_1 P_1 d_m

    Parameters
    ----------
    f1 : float or array_like
        Palmgren load coefficient, [-]; not negative.
    P1 : float or array_like
        Friction-equivalent load, [N]; not negative.
    dm : float or array_like
        Bearing mean diameter (d + D)/2, [m]; positive.

    Returns
    -------
    float or ndarray
        M_l, [N·m].

    References
    ----------
    .. [1] Paper Eq. 16; Harris & Kotzalas 2006; Palmgren 1959.

    Examples
    --------
    docs/paper-audit.md §3, front pair: M_l = 4.300e-4·4335 N·43.5 mm = 81.09 N·mm.

    >>> round(torque_bearing_load_Palmgren(4.300e-4, 4335.0, 0.0435) * 1e3, 2)
    81.09
    """
    return _out(_check(f1, "f1", "[-]") * _check(P1, "P1", "[N]") * _dm(dm))


def torque_bearing_viscous_Palmgren(f0, nu, n_rpm, dm):
    r"""Viscous (lubricant) friction torque after Palmgren (Eqs. 21–22 corrected).

    With ν in mm²/s, n in rpm, d_m in mm and M_v in N·mm:

    .. math::
        M_v = \begin{cases}
        10^{-7} f_0 (\nu |n|)^{2/3} d_m^3 & \nu |n| \ge 2000 \\
        160\times10^{-7} f_0 d_m^3 & \nu |n| < 2000
        \end{cases}

    Parameters
    ----------
    f0 : float or array_like
        Bearing type and lubrication factor, [-] (see :data:`F0_TYPICAL`); not negative.
    nu : float or array_like
        Kinematic viscosity of the (base) oil at operating temperature, [m²/s].
    n_rpm : float or array_like
        Rotational speed of the bearing, [rpm]; the sign is ignored.
    dm : float or array_like
        Bearing mean diameter, [m].

    Returns
    -------
    float or ndarray
        M_v, [N·m].

    Notes
    -----
    Both printed equations are wrong: Eq. 21 lacks the cube on d_m (0.02 N·mm instead
    of ~38 N·mm for a 25×62 pair at 396 rpm); Eq. 22 lacks the factor 1e-7 and the
    cube. The branches nearly meet at ν·n = 2000 (2000^{2/3} = 158.7 vs 160). With
    grease, ν is the base-oil viscosity. Values of ν above 0.1 m²/s or d_m above 2 m
    are rejected as unit slips (mm²/s, mm).

    References
    ----------
    .. [1] Paper Eqs. 21–22 (corrected); Harris & Kotzalas 2006 (viscous torque, f₀
       table); Palmgren 1959.

    Examples
    --------
    docs/paper-audit.md §3, front pair at 396 rpm with ν = 100 mm²/s, f₀ = 4: ν·n = 39600,
    39600^(2/3) = e^(2/3·10.58658) = 1161.80, d_m³ = 43.5³ = 82312.9 mm³,
    M_v = 1e-7·4·1161.80·82312.9 = 38.25 N·mm (the review: 38).

    >>> round(torque_bearing_viscous_Palmgren(4.0, 100e-6, 396.0, 0.0435) * 1e3, 2)
    38.25
    """
    f0 = _check(f0, "f0", "[-]")
    nu = _check(nu, "nu", "[m²/s]")
    if _any(nu > _NU_MAX):
        raise ValueError(
            f"nu = {np.max(nu):.4g} m²/s is not a lubricant viscosity; pass m²/s "
            "(e.g. 100 mm²/s = 1e-4 m²/s)"
        )
    dm_mm = _dm(dm) * 1e3
    nu_n = nu * 1e6 * np.abs(np.asarray(n_rpm, dtype=float))
    high = 1e-7 * f0 * nu_n ** (2.0 / 3.0) * dm_mm**3
    low = 160e-7 * f0 * dm_mm**3
    return _out(np.where(nu_n >= VISCOUS_REGIME_LIMIT, high, low) * 1e-3)


def torque_bearing_Palmgren(f1, P1, dm, f0, nu, n_rpm):
    r"""Total Palmgren friction torque of a bearing: load plus viscous part.

    .. math:: M = f_1 P_1 d_m + M_v(f_0, \nu, n, d_m)

    Parameters
    ----------
    f1, P1, dm
        As in :func:`torque_bearing_load_Palmgren`: [-], [N], [m].
    f0, nu, n_rpm
        As in :func:`torque_bearing_viscous_Palmgren`: [-], [m²/s], [rpm].

    Returns
    -------
    BearingTorque
        ``load``, ``viscous`` and ``total`` torques, [N·m].

    References
    ----------
    .. [1] Paper Eqs. 16–22 (corrected); Harris & Kotzalas 2006; Palmgren 1959.

    Examples
    --------
    docs/paper-audit.md §3, front pair at condition I: 81.09 + 38.25 = 119.34 N·mm,
    the torque that Table 1's 4.95 W at 396 rpm requires (4.95/41.469 = 119.37 N·mm).

    >>> t = torque_bearing_Palmgren(4.300e-4, 4335.0, 0.0435, 4.0, 100e-6, 396.0)
    >>> round(t.load * 1e3, 2), round(t.viscous * 1e3, 2), round(t.total * 1e3, 2)
    (81.09, 38.25, 119.34)
    """
    load = torque_bearing_load_Palmgren(f1, P1, dm)
    viscous = torque_bearing_viscous_Palmgren(f0, nu, n_rpm, dm)
    return BearingTorque(load=load, viscous=viscous, total=_out(np.add(load, viscous)))


def heat_bearing(torque, n_rpm):
    r"""Heat generated in a bearing by its friction torque (Eq. 15, SI).

    .. math:: H = |M| \, \frac{2\pi |n|}{60}

    Parameters
    ----------
    torque : float, array_like or BearingTorque
        Friction torque, [N·m]; a :class:`BearingTorque` contributes its ``total``.
    n_rpm : float or array_like
        The bearing's *own* speed, [rpm]: the front and rear screw bearings run at the
        screw speed n_s, the nut bearing at the nut speed n_n (not at n_s − n_n).

    Returns
    -------
    float or ndarray
        Heat, [W].

    Notes
    -----
    Eq. 15's 1.047e-4 is 2π/60·1e-3 for M in N·mm; here M is in N·m.

    References
    ----------
    .. [1] Paper Eq. 15; docs/paper-audit.md §3 (bearing speeds).

    Examples
    --------
    Paper Table 1, front bearings: 119.4 N·mm at 396 rpm, 0.1194·41.469 = 4.951 W (printed 4.95).

    >>> round(heat_bearing(0.1194, 396.0), 2)
    4.95
    """
    if isinstance(torque, BearingTorque):
        torque = torque.total
    return heat_friction(torque, n_rpm)


def torque_bearing_constant_friction(mu, P, d):
    r"""Friction torque of a rolling bearing from a constant coefficient of friction (catalogue estimate).

    .. math:: M = \tfrac{1}{2}\,\mu\,P\,d

    A torque that does not depend on the speed or the lubricant's viscosity: the preload drag
    of a grease-packed bearing after run-in, as the catalogues state it for support bearings.

    Parameters
    ----------
    mu : float or array_like
        Constant coefficient of friction of the bearing type, [-] (SKF's table: deep groove
        ball 0.0010, angular contact ball single row 0.0020, double row and four-point 0.0024,
        thrust ball 0.0013).
    P : float or array_like
        Equivalent dynamic bearing load, [N].
    d : float or array_like
        Bore diameter, [m].

    Returns
    -------
    float or ndarray
        Friction torque, [N·m].

    Notes
    -----
    Valid, the catalogue says, at a load of about P ≈ 0.1 C, good lubrication and normal
    operating conditions; outside them the full model (:mod:`feedtherm.physics.bearings_skf`) is
    the one to use.

    References
    ----------
    .. [1] SKF, *Rolling bearings* (catalogue PUB BU/P1 17000, 2018), "Friction": estimating the
       frictional moment with a constant coefficient of friction, M = 0.5 μ P d, and its table of
       μ for open bearings; the same form in Koyo's technical catalogue ("Friction").

    Examples
    --------
    A 25 mm bore support bearing at a 3150 N preload, μ = 0.0020:
    0.5 · 0.0020 · 3150 N · 0.025 m = 0.07875 N·m.

    >>> round(torque_bearing_constant_friction(0.0020, 3150.0, 0.025), 5)
    0.07875
    """
    mu = _check(mu, "mu", "[-]", strict=True)
    P = _check(P, "P", "[N]")
    d = _check(d, "d", "[m]", strict=True)
    if _any(mu >= 0.1):
        raise ValueError(f"mu = {np.max(mu):.4g} is not a rolling bearing's coefficient of friction (0.001-0.005)")
    if _any(d > _DM_MAX):
        raise ValueError(f"d = {np.max(d):.4g} m is not a rolling-bearing bore; pass metres (25 mm = 0.025 m)")
    return _out(0.5 * mu * P * d)


# --------------------------------------------------------------------------- helpers


def _f1(P0, C0, z, y, name):
    P0 = _check(P0, "P0", "[N]")
    C0 = _check(C0, "C0", "[N]", strict=True)
    ratio = P0 / C0
    # Valid range (0, 1]; check_range is inclusive, so low = smallest float > 0.
    check_range(name, "P0/C0", ratio, math.ulp(0.0), 1.0)
    return _out(z * ratio**y)


def _loads(Fa, Fr):
    return _check(Fa, "Fa", "[N]"), _check(Fr, "Fr", "[N]")


def _check(value, label, unit, strict=False):
    if type(value) in FLOATS:  # the usual scalar call, without numpy's reductions
        v = float(value)
        if not math.isfinite(v) or (v <= 0 if strict else v < 0):
            raise ValueError(f"{label} must be finite and {'> 0' if strict else '>= 0'} {unit}, got {value!r}")
        return v
    arr = np.asarray(value, dtype=float)
    if np.any(~np.isfinite(arr)) or np.any(arr <= 0 if strict else arr < 0):
        bound = "> 0" if strict else ">= 0"
        raise ValueError(f"{label} must be finite and {bound} {unit}, got {value!r}")
    return arr


def _dm(dm):
    arr = _check(dm, "dm", "[m]", strict=True)
    if _any(arr > _DM_MAX):
        raise ValueError(
            f"dm = {np.max(arr):.4g} m is not a rolling-bearing mean diameter; pass metres "
            "(e.g. 43.5 mm = 0.0435 m)"
        )
    return arr
