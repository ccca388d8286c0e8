r"""Rolling-bearing friction torque after the SKF model (rolling, sliding, seals, drag).

.. math:: M = \phi_{ish}\,\phi_{rs}\,M_{rr} + M_{sl} + M_{seal} + M_{drag}

with the rolling moment :math:`M_{rr} = G_{rr}(\nu n)^{0.6}`, the sliding moment
:math:`M_{sl} = G_{sl}\,\mu_{sl}`, the inlet-shear-heating reduction :math:`\phi_{ish}` and the
kinematic replenishment/starvation reduction :math:`\phi_{rs}`.  Unlike Palmgren's viscous
term, which grows as :math:`(\nu n)^{2/3}` without bound, the rolling moment is damped at high
speed and viscosity by the two reductions.

Interfaces are SI (loads [N], diameters [m], ν [m²/s], torque [N·m], speed [rpm]); the
catalogue's N/mm/mm²/s forms are converted inside.  The geometric constants R, S, K_Z and the
seal constants K_S1, K_S2, β are the catalogue's, for its units, and are tabulated here with
the table they come from.  Each bearing of a set is computed on its own (catalogue: "for
paired bearings calculate the frictional moment of each bearing and add them").

The model holds for grease or oil lubrication, loads at least the minimum load, constant in
magnitude and direction, and normal operating clearance (catalogue, "The new SKF model").

References
----------
.. [1] SKF General Catalogue 6000 (2006 edition; Russian edition "Общий каталог SKF",
   pp. 88–101, "Трение"): the model, Table 2a (G_rr, G_sl), Table 3 (angular contact ball
   bearings), Table 3a (deep groove ball bearings), Table 4 (seals), Table 5 (K_Z), the
   inlet-shear, replenishment/starvation and mixed-lubrication factors.
.. [2] SKF Rolling bearings catalogue (2012 and later editions), "Friction", Table 2a and
   the sliding-friction text: the same G_rr, G_sl and μ_sl = φ_bl μ_bl + (1 − φ_bl) μ_EHL.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from feedtherm.physics._arrays import any_true as _any
from feedtherm.physics._arrays import scalar_or_array as _out
from feedtherm.physics._checks import finite_array

#: Geometric constants (R1, R2, R3, S1, S2, S3) for the rolling and sliding moments, in the
#: catalogue's units; R3 = S3 = 0 where the bearing type has no F_g term.
#: Deep groove ball bearings by series: SKF General Catalogue 6000, Table 3a.
#: Angular contact ball bearings by design: Table 3 (single row: the 72 B(E), 73 B(E) and
#: 70 B series alike; the catalogue gives one row of constants per design, not per series).
GEOMETRIC_CONSTANTS_SKF: dict[str, dict[str, tuple[float, float, float, float, float, float]]] = {
    "deep_groove": {
        "2": (4.4e-7, 1.7, 0.0, 2.00e-3, 100.0, 0.0),
        "3": (4.4e-7, 1.7, 0.0, 2.00e-3, 100.0, 0.0),
        "42": (5.4e-7, 0.96, 0.0, 3.00e-3, 40.0, 0.0),
        "43": (5.4e-7, 0.96, 0.0, 3.00e-3, 40.0, 0.0),
        "60": (4.1e-7, 1.7, 0.0, 3.73e-3, 14.6, 0.0),
        "630": (4.1e-7, 1.7, 0.0, 3.73e-3, 14.6, 0.0),
        "62": (3.9e-7, 1.7, 0.0, 3.23e-3, 36.5, 0.0),
        "622": (3.9e-7, 1.7, 0.0, 3.23e-3, 36.5, 0.0),
        "63": (3.7e-7, 1.7, 0.0, 2.84e-3, 92.8, 0.0),
        "623": (3.7e-7, 1.7, 0.0, 2.84e-3, 92.8, 0.0),
        "64": (3.6e-7, 1.7, 0.0, 2.43e-3, 198.0, 0.0),
        "160": (4.3e-7, 1.7, 0.0, 4.63e-3, 4.25, 0.0),
        "161": (4.3e-7, 1.7, 0.0, 4.63e-3, 4.25, 0.0),
        "617": (4.7e-7, 1.7, 0.0, 6.50e-3, 0.78, 0.0),
        "618": (4.7e-7, 1.7, 0.0, 6.50e-3, 0.78, 0.0),
        "628": (4.7e-7, 1.7, 0.0, 6.50e-3, 0.78, 0.0),
        "637": (4.7e-7, 1.7, 0.0, 6.50e-3, 0.78, 0.0),
        "638": (4.7e-7, 1.7, 0.0, 6.50e-3, 0.78, 0.0),
        "619": (4.3e-7, 1.7, 0.0, 4.75e-3, 3.6, 0.0),
        "639": (4.3e-7, 1.7, 0.0, 4.75e-3, 3.6, 0.0),
    },
    "angular_contact": {
        "single_row": (5.03e-7, 1.97, 1.90e-12, 1.30e-2, 0.68, 1.91e-12),
        "double_row": (6.34e-7, 1.41, 7.83e-13, 7.56e-3, 1.21, 7.83e-13),
        "four_point": (4.78e-7, 2.42, 1.40e-12, 1.20e-2, 0.9, 1.40e-12),
    },
}

#: Geometric constant K_Z of the replenishment/starvation factor, Table 5.
K_Z_SKF: dict[str, dict[str, float]] = {
    "deep_groove": {series: 3.1 for series in GEOMETRIC_CONSTANTS_SKF["deep_groove"]},  # single and double row
    "angular_contact": {"single_row": 4.4, "double_row": 3.1, "four_point": 3.1},
}

#: Replenishment/starvation constant K_rs by lubrication method [-]: 3e-8 for a low-level
#: oil bath and oil jet, 6e-8 for grease and oil-air (and oil spot).  A full oil bath (level
#: above the centre of the lowest ball) replenishes the contacts: no starvation factor.
K_RS_SKF: dict[str, float | None] = {
    "grease": 6e-8, "oil_air": 6e-8, "oil_jet": 3e-8, "oil_bath_low_level": 3e-8, "oil_bath": None,
}

#: μ_bl, the boundary (mixed-film) sliding coefficient: "depends on the additive package of
#: the lubricant, approximately 0.15".
MU_BL_SKF = 0.15

#: μ_EHL, the full-film sliding coefficient of ball bearings by base oil.
MU_EHL_SKF: dict[str, float] = {"mineral": 0.05, "synthetic": 0.04, "transmission_fluid": 0.1}

#: Seal constants, Table 4: seal -> bearing type -> rows (D over [mm], D up to [mm], β, K_S1,
#: K_S2); D the bearing's outside diameter; M_seal of two seals [N·mm] with d_s in mm.
_SEAL_ROWS: dict[str, dict[str, tuple[tuple[float, float, float, float, float], ...]]] = {
    "RSL": {"deep_groove": ((0.0, 25.0, 0.0, 0.0, 0.0), (25.0, 52.0, 2.25, 0.0018, 0.0))},
    "RZ": {"deep_groove": ((0.0, 175.0, 0.0, 0.0, 0.0),)},
    "RSH": {"deep_groove": ((0.0, 52.0, 2.25, 0.028, 2.0),)},
    "RS1": {
        "deep_groove": (
            (0.0, 62.0, 2.25, 0.023, 2.0), (62.0, 80.0, 2.25, 0.018, 20.0),
            (80.0, 100.0, 2.25, 0.018, 15.0), (100.0, math.inf, 2.25, 0.018, 0.0),
        ),
        "angular_contact": ((30.0, 120.0, 2.0, 0.014, 10.0),),
    },
}
SEALS_SKF: tuple[str, ...] = tuple(_SEAL_ROWS)

# Unit-slip guards: a diameter > 2 m or ν > 0.1 m²/s means mm or mm²/s was passed.
_D_MAX = 2.0
_NU_MAX = 0.1


@dataclass(frozen=True)
class BearingTorqueSKF:
    """SKF friction torque of one bearing, [N·m]: ``rolling`` M_rr before the reductions,
    ``phi_ish`` and ``phi_rs`` [-], ``sliding`` M_sl, ``seal`` M_seal, ``drag`` M_drag and
    ``total`` = φ_ish φ_rs M_rr + M_sl + M_seal + M_drag."""

    rolling: float
    phi_ish: float
    phi_rs: float
    sliding: float
    seal: float
    drag: float
    total: float


def phi_ish(n_rpm, dm, nu):
    r"""Inlet shear heating reduction factor of the rolling moment (SKF).

    With n in r/min, d_m in mm and ν in mm²/s:

    .. math:: \phi_{ish} = \frac{1}{1 + 1.84\times10^{-9}\,(n\,d_m)^{1.28}\,\nu^{0.64}}

    Parameters
    ----------
    n_rpm : float or array_like
        Rotational speed, [rpm]; the sign is ignored.
    dm : float or array_like
        Bearing mean diameter (d + D)/2, [m].
    nu : float or array_like
        Kinematic viscosity of the oil (grease: base oil) at operating temperature, [m²/s].

    Returns
    -------
    float or ndarray
        φ_ish, [-], in (0, 1].

    Notes
    -----
    Part of the rolling lubricant is rejected at the contact inlet and flows back; its shear
    heats the inlet, lowers the viscosity and the film thickness, and so the rolling moment.

    References
    ----------
    .. [1] SKF General Catalogue 6000 (2006), "Inlet shear heating reduction factor".

    Examples
    --------
    A 7010 bearing (d_m = 65 mm) at 1080 rpm with ν = 100 mm²/s: n d_m = 70200,
    70200^1.28 = e^(1.28·11.159104) = e^14.283653 = 1.597024e6, 100^0.64 = 19.054607,
    1.84e-9·1.597024e6·19.054607 = 0.0559924, φ_ish = 1/1.0559924 = 0.946976.

    >>> round(phi_ish(1080.0, 0.065, 100e-6), 6)
    0.946976
    """
    n = np.abs(np.asarray(n_rpm, dtype=float))
    return _out(1.0 / (1.0 + 1.84e-9 * (n * _mm(dm, "dm")) ** 1.28 * _nu_mm2_s(nu) ** 0.64))


def phi_rs(K_rs, K_Z, nu, n_rpm, d, D):
    r"""Kinematic replenishment/starvation reduction factor of the rolling moment (SKF).

    With ν in mm²/s, n in r/min, d and D in mm:

    .. math:: \phi_{rs} = \exp\!\left[-K_{rs}\,\nu\,n\,(d + D)\sqrt{\frac{K_Z}{2(D - d)}}\right]

    Parameters
    ----------
    K_rs : float
        Replenishment/starvation constant, [-] (:data:`K_RS_SKF`): 3e-8 low-level oil bath
        and oil jet, 6e-8 grease and oil-air.
    K_Z : float
        Geometric constant of the bearing type, [-] (:data:`K_Z_SKF`).
    nu : float or array_like
        Kinematic viscosity at operating temperature, [m²/s].
    n_rpm : float or array_like
        Rotational speed, [rpm]; the sign is ignored.
    d, D : float
        Bore and outside diameter, [m]; D > d.

    Returns
    -------
    float or ndarray
        φ_rs, [-], in (0, 1].

    Notes
    -----
    At high speed or viscosity the rolling elements push the lubricant aside faster than it
    flows back into the track: the film thins and the rolling moment drops.  Not applied to a
    full oil bath.

    References
    ----------
    .. [1] SKF General Catalogue 6000 (2006), "Kinematic replenishment/starvation reduction
       factor", Table 5 (K_Z).

    Examples
    --------
    7010 (d = 50, D = 80 mm, K_Z = 4.4), grease (K_rs = 6e-8), ν = 100 mm²/s, 1080 rpm:
    √(4.4/60) = 0.270801, exponent 6e-8·100·1080·130·0.270801 = 0.228123,
    φ_rs = e^−0.228123 = 0.796026.

    >>> round(phi_rs(6e-8, 4.4, 100e-6, 1080.0, 0.050, 0.080), 6)
    0.796026
    """
    d_mm, D_mm = _mm(d, "d"), _mm(D, "D")
    if np.any(D_mm <= d_mm):
        raise ValueError(f"the outside diameter D must exceed the bore d, got d = {d!r}, D = {D!r} m")
    K_rs, K_Z = _nonneg(K_rs, "K_rs"), _positive(K_Z, "K_Z")
    n = np.abs(np.asarray(n_rpm, dtype=float))
    exponent = K_rs * _nu_mm2_s(nu) * n * (d_mm + D_mm) * np.sqrt(K_Z / (2.0 * (D_mm - d_mm)))
    return _out(np.exp(-exponent))


def phi_bl(n_rpm, nu, dm):
    r"""Weighting factor of boundary (mixed-film) sliding friction (SKF).

    With n in r/min, ν in mm²/s and d_m in mm:

    .. math:: \phi_{bl} = \exp\!\left[-2.6\times10^{-8}\,(n\,\nu)^{1.4}\,d_m\right]

    Parameters
    ----------
    n_rpm : float or array_like
        Rotational speed, [rpm]; the sign is ignored.
    nu : float or array_like
        Kinematic viscosity at operating temperature, [m²/s].
    dm : float or array_like
        Bearing mean diameter, [m].

    Returns
    -------
    float or ndarray
        φ_bl, [-]: 1 at standstill (boundary friction), → 0 with a full film.

    References
    ----------
    .. [1] SKF General Catalogue 6000 (2006), "Mixed lubrication for low speeds and
       viscosities"; SKF Rolling bearings (2012 and later), "Sliding frictional moment".

    Examples
    --------
    6205 (d_m = 38.5 mm) at 100 rpm with ν = 10 mm²/s: n ν = 1000, 1000^1.4 = 15848.93,
    2.6e-8·15848.93·38.5 = 0.0158648, φ_bl = e^−0.0158648 = 0.98426.

    >>> round(phi_bl(100.0, 10e-6, 0.0385), 5)
    0.98426
    """
    n = np.abs(np.asarray(n_rpm, dtype=float))
    return _out(np.exp(-2.6e-8 * (n * _nu_mm2_s(nu)) ** 1.4 * _mm(dm, "dm")))


def mu_sl(phi_bl, mu_bl=MU_BL_SKF, mu_ehl=MU_EHL_SKF["mineral"]):
    r"""Sliding friction coefficient in mixed and full-film lubrication (SKF).

    .. math:: \mu_{sl} = \phi_{bl}\,\mu_{bl} + (1 - \phi_{bl})\,\mu_{EHL}

    Parameters
    ----------
    phi_bl : float or array_like
        Weighting factor (:func:`phi_bl`), [-], in [0, 1].
    mu_bl : float, optional
        Boundary coefficient, [-]; default 0.15 ("approximately 0.15").
    mu_ehl : float, optional
        Full-film coefficient, [-]; default 0.05, ball bearings with mineral oil
        (:data:`MU_EHL_SKF`: 0.04 synthetic oil, 0.1 transmission fluid).

    Returns
    -------
    float or ndarray
        μ_sl, [-].

    References
    ----------
    .. [1] SKF General Catalogue 6000 (2006), "Mixed lubrication for low speeds and
       viscosities"; SKF Rolling bearings (2012 and later), "Sliding frictional moment".

    Examples
    --------
    φ_bl = 0.98426 (the example of :func:`phi_bl`), mineral oil:
    0.98426·0.15 + 0.01574·0.05 = 0.147639 + 0.000787 = 0.148426.

    >>> round(mu_sl(0.98426), 6)
    0.148426
    """
    p = np.asarray(phi_bl, dtype=float)
    if np.any(~np.isfinite(p)) or np.any((p < 0.0) | (p > 1.0)):
        raise ValueError(f"phi_bl must lie in [0, 1], got {phi_bl!r}")
    return _out(p * _nonneg(mu_bl, "mu_bl") + (1.0 - p) * _nonneg(mu_ehl, "mu_ehl"))


def torque_bearing_rolling_deep_groove_SKF(R1, R2, dm, Fr, Fa, C0, nu, n_rpm):
    r"""Rolling frictional moment of a deep groove ball bearing (SKF, before φ_ish φ_rs).

    With d_m in mm, loads in N, ν in mm²/s, n in r/min (M in N·mm):

    .. math::
        M_{rr} = G_{rr}(\nu n)^{0.6}, \qquad
        G_{rr} = R_1 d_m^{1.96}\left(F_r + \frac{R_2}{\sin\alpha_F}F_a\right)^{0.54},
        \qquad \alpha_F = 24.6\,(F_a/C_0)^{0.24}\ [°]

    (for F_a = 0: :math:`G_{rr} = R_1 d_m^{1.96} F_r^{0.54}`).

    Parameters
    ----------
    R1, R2 : float
        Geometric constants of the series (:data:`GEOMETRIC_CONSTANTS_SKF`, Table 3a).
    dm : float
        Bearing mean diameter, [m].
    Fr, Fa : float
        Radial and axial load of the bearing, [N]; not negative.
    C0 : float
        Basic static load rating of the bearing, [N].
    nu : float
        Kinematic viscosity at operating temperature, [m²/s].
    n_rpm : float
        Rotational speed, [rpm]; the sign is ignored.

    Returns
    -------
    float
        M_rr, [N·m].

    References
    ----------
    .. [1] SKF General Catalogue 6000 (2006), Table 2a and Table 3a.

    Examples
    --------
    6205 (series 62: R1 = 3.9e-7, R2 = 1.7; d_m = 38.5 mm, C0 = 7.8 kN), F_r = 50 N,
    F_a = 0, ν = 100 mm²/s, 1116 rpm: 38.5^1.96 = e^(1.96·3.650658) = e^7.155290 = 1280.864,
    50^0.54 = e^(0.54·3.912023) = e^2.112492 = 8.268825, G_rr = 3.9e-7·1280.864·8.268825
    = 4.130584e-3; (ν n)^0.6 = 111600^0.6 = e^(0.6·11.622676) = e^6.973606 = 1068.067;
    M_rr = 4.41174 N·mm.

    >>> round(torque_bearing_rolling_deep_groove_SKF(3.9e-7, 1.7, 0.0385, 50.0, 0.0, 7800.0, 100e-6, 1116.0) * 1e3, 5)
    4.41174
    """
    Fr, Fa, C0 = _nonneg(Fr, "Fr"), _nonneg(Fa, "Fa"), _positive(C0, "C0")
    dm_mm = _mm(dm, "dm")
    load = Fr + (_positive(R2, "R2") / _sin_alpha_F(Fa, C0)) * Fa if Fa > 0.0 else Fr
    G_rr = _positive(R1, "R1") * dm_mm**1.96 * load**0.54
    return _out(G_rr * _nu_n(nu, n_rpm) ** 0.6 * 1e-3)


def torque_bearing_sliding_deep_groove_SKF(S1, S2, dm, Fr, Fa, C0, mu):
    r"""Sliding frictional moment of a deep groove ball bearing (SKF).

    With d_m in mm and loads in N (M in N·mm):

    .. math::
        M_{sl} = G_{sl}\,\mu_{sl}, \qquad
        G_{sl} = S_1 d_m^{-0.145}\left(F_r^5 + \frac{S_2 d_m^{1.5}}{\sin\alpha_F}F_a^4\right)^{1/3}

    (for F_a = 0: :math:`G_{sl} = S_1 d_m^{-0.26} F_r^{5/3}`); α_F as in
    :func:`torque_bearing_rolling_deep_groove_SKF`.

    Parameters
    ----------
    S1, S2 : float
        Geometric constants of the series (:data:`GEOMETRIC_CONSTANTS_SKF`, Table 3a).
    dm : float
        Bearing mean diameter, [m].
    Fr, Fa : float
        Radial and axial load of the bearing, [N].
    C0 : float
        Basic static load rating of the bearing, [N].
    mu : float
        Sliding friction coefficient μ_sl (:func:`mu_sl`), [-].

    Returns
    -------
    float
        M_sl, [N·m].

    References
    ----------
    .. [1] SKF General Catalogue 6000 (2006), Table 2a and Table 3a.

    Examples
    --------
    6205 (S1 = 3.23e-3; d_m = 38.5 mm), F_r = 50 N, F_a = 0, μ_sl = 0.05:
    38.5^−0.26 = e^(−0.26·3.650658) = e^−0.949171 = 0.387062,
    50^(5/3) = e^(5/3·3.912023) = e^6.520038 = 678.604,
    G_sl = 3.23e-3·0.387062·678.604 = 0.848398 N·mm, M_sl = 0.0424199 N·mm.

    >>> round(torque_bearing_sliding_deep_groove_SKF(3.23e-3, 36.5, 0.0385, 50.0, 0.0, 7800.0, 0.05) * 1e6, 2)
    42.42
    """
    Fr, Fa, C0 = _nonneg(Fr, "Fr"), _nonneg(Fa, "Fa"), _positive(C0, "C0")
    dm_mm = _mm(dm, "dm")
    S1 = _positive(S1, "S1")
    if Fa > 0.0:
        G_sl = S1 * dm_mm**-0.145 * (Fr**5 + _positive(S2, "S2") * dm_mm**1.5 / _sin_alpha_F(Fa, C0) * Fa**4) ** (1.0 / 3.0)
    else:
        G_sl = S1 * dm_mm**-0.26 * Fr ** (5.0 / 3.0)
    return _out(G_sl * _nonneg(mu, "mu") * 1e-3)


def torque_bearing_rolling_angular_contact_SKF(R1, R2, R3, dm, Fr, Fa, nu, n_rpm):
    r"""Rolling frictional moment of an angular contact ball bearing (SKF, before φ_ish φ_rs).

    With d_m in mm, loads in N, ν in mm²/s, n in r/min (M in N·mm):

    .. math::
        M_{rr} = G_{rr}(\nu n)^{0.6}, \qquad
        G_{rr} = R_1 d_m^{1.97}\left(F_r + F_g + R_2 F_a\right)^{0.54}, \qquad
        F_g = R_3 d_m^4 n^2

    Parameters
    ----------
    R1, R2, R3 : float
        Geometric constants (:data:`GEOMETRIC_CONSTANTS_SKF`, Table 3).
    dm : float
        Bearing mean diameter, [m].
    Fr, Fa : float
        Radial and axial load of the bearing, [N]; for F_a the catalogue asks for the
        external axial load (Table 2a, footnote 1).
    nu : float
        Kinematic viscosity at operating temperature, [m²/s].
    n_rpm : float
        Rotational speed, [rpm]; the sign is ignored.

    Returns
    -------
    float
        M_rr, [N·m].

    Notes
    -----
    F_g is the balls' centrifugal load term, which grows as n².

    References
    ----------
    .. [1] SKF General Catalogue 6000 (2006), Table 2a and Table 3.

    Examples
    --------
    7010 single row (R1 = 5.03e-7, R2 = 1.97, R3 = 1.90e-12; d_m = 65 mm), F_r = 25 N,
    F_a = 300 N, 1080 rpm, ν = 100 mm²/s: F_g = 1.90e-12·65⁴·1080² = 1.90e-12·17850625
    ·1166400 = 39.5598 N; 25 + 39.5598 + 591 = 655.5598 N, 655.5598^0.54 = e^(0.54·6.485490)
    = e^3.502164 = 33.1872; 65^1.97 = e^(1.97·4.174387) = e^8.223543 = 3727.686;
    G_rr = 5.03e-7·3727.686·33.1872 = 0.0622269; 108000^0.6 = e^(0.6·11.589887)
    = e^6.953932 = 1047.259; M_rr = 65.1677 N·mm.

    >>> round(torque_bearing_rolling_angular_contact_SKF(5.03e-7, 1.97, 1.90e-12, 0.065, 25.0, 300.0, 100e-6, 1080.0) * 1e3, 3)
    65.168
    """
    Fr, Fa = _nonneg(Fr, "Fr"), _nonneg(Fa, "Fa")
    dm_mm = _mm(dm, "dm")
    n = abs(float(n_rpm))
    F_g = _nonneg(R3, "R3") * dm_mm**4 * n**2
    G_rr = _positive(R1, "R1") * dm_mm**1.97 * (Fr + F_g + _nonneg(R2, "R2") * Fa) ** 0.54
    return _out(G_rr * _nu_n(nu, n_rpm) ** 0.6 * 1e-3)


def torque_bearing_sliding_angular_contact_SKF(S1, S2, S3, dm, Fr, Fa, n_rpm, mu):
    r"""Sliding frictional moment of an angular contact ball bearing (SKF).

    With d_m in mm and loads in N (M in N·mm):

    .. math::
        M_{sl} = G_{sl}\,\mu_{sl}, \qquad
        G_{sl} = S_1 d_m^{0.26}\left[(F_r + F_g)^{4/3} + S_2 F_a^{4/3}\right], \qquad
        F_g = S_3 d_m^4 n^2

    Parameters
    ----------
    S1, S2, S3 : float
        Geometric constants (:data:`GEOMETRIC_CONSTANTS_SKF`, Table 3).
    dm : float
        Bearing mean diameter, [m].
    Fr, Fa : float
        Radial and axial load of the bearing, [N].
    n_rpm : float
        Rotational speed, [rpm]; the sign is ignored.
    mu : float
        Sliding friction coefficient μ_sl (:func:`mu_sl`), [-].

    Returns
    -------
    float
        M_sl, [N·m].

    References
    ----------
    .. [1] SKF General Catalogue 6000 (2006), Table 2a and Table 3.

    Examples
    --------
    The 7010 of :func:`torque_bearing_rolling_angular_contact_SKF` (S1 = 1.30e-2, S2 = 0.68,
    S3 = 1.91e-12): F_g = 1.91e-12·17850625·1166400 = 39.7681 N; (25 + 39.7681)^(4/3)
    = e^(4/3·4.170812) = e^5.561083 = 260.104; 300^(4/3) = e^(4/3·5.703782) = e^7.605043
    = 2008.299, ·0.68 = 1365.643; 65^0.26 = e^(0.26·4.174387) = e^1.085341 = 2.960448;
    G_sl = 1.30e-2·2.960448·1625.748 = 62.5682 N·mm; with μ_sl = 0.05: M_sl = 3.12841 N·mm.

    >>> round(torque_bearing_sliding_angular_contact_SKF(1.30e-2, 0.68, 1.91e-12, 0.065, 25.0, 300.0, 1080.0, 0.05) * 1e3, 3)
    3.128
    """
    Fr, Fa = _nonneg(Fr, "Fr"), _nonneg(Fa, "Fa")
    dm_mm = _mm(dm, "dm")
    n = abs(float(n_rpm))
    F_g = _nonneg(S3, "S3") * dm_mm**4 * n**2
    G_sl = _positive(S1, "S1") * dm_mm**0.26 * ((Fr + F_g) ** (4.0 / 3.0) + _nonneg(S2, "S2") * Fa ** (4.0 / 3.0))
    return _out(G_sl * _nonneg(mu, "mu") * 1e-3)


def seal_constants_SKF(seal, bearing_type, D):
    r"""Seal constants (β, K_S1, K_S2) of Table 4 for a seal type, bearing type and size.

    Parameters
    ----------
    seal : str
        ``"RSL"``, ``"RZ"``, ``"RSH"`` or ``"RS1"``.
    bearing_type : str
        ``"deep_groove"`` or ``"angular_contact"``.
    D : float
        Outside diameter of the bearing, [m]; selects the row of Table 4.

    Returns
    -------
    tuple of float
        (β [-], K_S1 [N·mm^(1−β)], K_S2 [N·mm]), for :func:`torque_bearing_seal_SKF`.

    Raises
    ------
    ValueError
        When Table 4 has no row for the seal, the bearing type or the size.

    References
    ----------
    .. [1] SKF General Catalogue 6000 (2006), Table 4.

    Examples
    --------
    Table 4: an RS1 seal on a deep groove ball bearing with D = 52 mm (up to 62 mm):
    β = 2.25, K_S1 = 0.023, K_S2 = 2; on an angular contact bearing of D = 80 mm
    (30 to 120 mm): β = 2, K_S1 = 0.014, K_S2 = 10.

    >>> seal_constants_SKF("RS1", "deep_groove", 0.052), seal_constants_SKF("RS1", "angular_contact", 0.080)
    ((2.25, 0.023, 2.0), (2.0, 0.014, 10.0))
    """
    rows = _SEAL_ROWS.get(seal, {}).get(bearing_type)
    if rows is None:
        raise ValueError(f"SKF Table 4 gives no constants for {seal!r} seals on {bearing_type} bearings")
    D_mm = float(_mm(D, "D"))
    for over, up_to, beta, k1, k2 in rows:
        if over < D_mm <= up_to:
            return beta, k1, k2
    sizes = ", ".join(f"{o:g} < D <= {u:g} mm" for o, u, *_ in rows)
    raise ValueError(f"SKF Table 4 gives {seal} constants on {bearing_type} bearings for {sizes}; D = {D_mm:g} mm")


def torque_bearing_seal_SKF(K_S1, beta, K_S2, ds, seals=2, *, full_value=False):
    r"""Frictional moment of a bearing's contact seals (SKF).

    With d_s in mm (M in N·mm, for two seals):

    .. math:: M_{seal} = K_{S1}\,d_s^{\beta} + K_{S2}

    Parameters
    ----------
    K_S1, beta, K_S2 : float
        Constants of Table 4 (:func:`seal_constants_SKF`).
    ds : float
        Seal counterface diameter (d₁ or d₂ of the product table, as Table 4 names), [m].
    seals : {1, 2}, optional
        Seals on the bearing; one seal makes half the moment.
    full_value : bool, optional
        True for RSL seals on bearings over 25 mm outside diameter, whose moment the
        catalogue takes whole whatever the number of seals.

    Returns
    -------
    float
        M_seal, [N·m].

    References
    ----------
    .. [1] SKF General Catalogue 6000 (2006), "Frictional moment of seals", Table 4.

    Examples
    --------
    Two RS1 seals on a deep groove ball bearing with D ≤ 62 mm and d_s = 30.2 mm:
    30.2^2.25 = e^(2.25·3.407842) = e^7.667644 = 2138.039, M = 0.023·2138.039 + 2
    = 51.1749 N·mm; one seal: 25.5874 N·mm.

    >>> round(torque_bearing_seal_SKF(0.023, 2.25, 2.0, 0.0302) * 1e3, 3), round(torque_bearing_seal_SKF(0.023, 2.25, 2.0, 0.0302, 1) * 1e3, 3)
    (51.175, 25.587)
    """
    if seals not in (1, 2):
        raise ValueError(f"seals must be 1 or 2, got {seals!r}")
    moment = _nonneg(K_S1, "K_S1") * float(_mm(ds, "ds")) ** _nonneg(beta, "beta") + _nonneg(K_S2, "K_S2")
    share = 1.0 if (seals == 2 or full_value) else 0.5
    return _out(moment * share * 1e-3)


def torque_bearing_SKF(rolling, phi_ish, phi_rs, sliding, seal=0.0, drag=0.0):
    r"""Total SKF frictional moment of a bearing from its parts.

    .. math:: M = \phi_{ish}\,\phi_{rs}\,M_{rr} + M_{sl} + M_{seal} + M_{drag}

    Parameters
    ----------
    rolling : float
        M_rr before the reductions, [N·m].
    phi_ish, phi_rs : float
        Reduction factors (:func:`phi_ish`, :func:`phi_rs`), [-], in (0, 1].
    sliding : float
        M_sl, [N·m].
    seal, drag : float, optional
        M_seal and M_drag, [N·m]; default 0 (an open bearing, no oil-bath drag).

    Returns
    -------
    BearingTorqueSKF
        The parts and the ``total``, [N·m].

    Notes
    -----
    M_drag of an oil bath depends on the variable V_M, which the catalogue gives only as a
    diagram of the oil level (Diagram 2); it is an input here, not computed.

    References
    ----------
    .. [1] SKF General Catalogue 6000 (2006), "Additional effects on frictional moments".

    Examples
    --------
    The 7010 of the examples above: 0.946976·0.796026·65.1677 + 3.12841 = 49.1246 + 3.12841
    = 52.2530 N·mm.

    >>> round(torque_bearing_SKF(0.0651677, 0.946976, 0.796026, 0.00312841).total * 1e3, 3)
    52.253
    """
    for label, value in (("phi_ish", phi_ish), ("phi_rs", phi_rs)):
        if not 0.0 < float(value) <= 1.0:
            raise ValueError(f"{label} must lie in (0, 1], got {value!r}")
    parts = {k: float(_nonneg(v, k)) for k, v in (("rolling", rolling), ("sliding", sliding), ("seal", seal), ("drag", drag))}
    total = float(phi_ish) * float(phi_rs) * parts["rolling"] + parts["sliding"] + parts["seal"] + parts["drag"]
    return BearingTorqueSKF(phi_ish=float(phi_ish), phi_rs=float(phi_rs), total=total, **parts)


# --------------------------------------------------------------------------- helpers


def _sin_alpha_F(Fa, C0):
    """sin α_F with α_F = 24.6 (F_a/C_0)^0.24 degrees (deep groove bearings, Table 2a)."""
    return math.sin(math.radians(24.6 * (Fa / C0) ** 0.24))


def _nu_n(nu, n_rpm):
    return _nu_mm2_s(nu) * np.abs(np.asarray(n_rpm, dtype=float))


def _mm(value, label):
    arr = _positive(value, label)
    if _any(arr > _D_MAX):
        raise ValueError(f"{label} = {np.max(arr):.4g} m is not a bearing diameter; pass metres (e.g. 65 mm = 0.065 m)")
    return arr * 1e3


def _nu_mm2_s(nu):
    arr = _positive(nu, "nu")
    if _any(arr > _NU_MAX):
        raise ValueError(f"nu = {np.max(arr):.4g} m²/s is not a lubricant viscosity; pass m²/s (e.g. 100 mm²/s = 1e-4 m²/s)")
    return arr * 1e6


def _positive(value, label):
    return finite_array(value, label, positive=True)


def _nonneg(value, label):
    return finite_array(value, label)

