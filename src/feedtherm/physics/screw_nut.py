r"""Friction torque and heat of the sliding screw–nut pair (paper Eq. 23; docs/paper-audit.md §5).

The *sliding* model of a trapezoidal thread (docs/paper-audit.md §5): Shigley's power-screw torque
with the flank angle, a split-nut preload and Couette grease shear.  Tr flanks are
conformal helicoids (no Hertz radius R), so this is the model for the real nut; the
rolling terms of the paper's three-part *rolling-analogy* model (Eqs. 1–12, corrected,
in :mod:`feedtherm.physics.screw_nut_rolling`) come out ~10³× too small.  SI units
throughout; rpm only where named.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from feedtherm.physics._arrays import scalar_or_array as _out
from feedtherm.physics._checks import coulomb_mu as _mu
from feedtherm.physics._checks import nonnegative as _nonnegative
from feedtherm.physics._checks import positive as _positive
from feedtherm.physics.mechanics import angular_speed, heat_friction
from feedtherm.physics.validity import check_range

_MAX_FLANK = float(np.nextafter(math.pi / 4.0, 0.0))  # 45°, exclusive


def helix_angle(lead, d2):
    r"""Helix (lead) angle at the pitch diameter.

    .. math:: \varphi = \arctan\frac{P_h}{\pi d_2}

    Parameters
    ----------
    lead, d2 : float or array_like
        Lead P_h (starts × pitch) and pitch diameter, [m].

    Returns
    -------
    float or ndarray
        φ, [rad]; 6.16° for Tr32×10.

    Notes
    -----
    Non-positive lengths raise ValueError.

    References
    ----------
    .. [1] Shigley's *Mechanical Engineering Design*, §8-2 (power screws); docs/paper-audit.md §5.

    Examples
    --------
    docs/paper-audit.md §4, Tr32×10: atan(10/(π·29.5)) = atan(0.10790) = 6.16°.

    >>> import math
    >>> round(math.degrees(helix_angle(0.010, 0.0295)), 2)
    6.16
    """
    return _out(np.arctan(_positive("lead", lead) / (math.pi * _positive("d2", d2))))


def friction_angle_thread(mu, flank_half_angle):
    r"""Virtual friction angle of an inclined-flank thread.

    .. math:: \rho' = \arctan\frac{\mu}{\cos\beta}

    Parameters
    ----------
    mu : float or array_like
        Flank Coulomb coefficient, [-]; validity (0, 0.5], negative raises.
    flank_half_angle : float or array_like
        Flank half angle β, axial plane, [rad]; 15° Tr, 0 square; validity [0, 45°).

    Returns
    -------
    float or ndarray
        ρ′, [rad].

    Notes
    -----
    The flank wedge raises the normal force by sec β (Shigley's f sec α).

    References
    ----------
    .. [1] Shigley's *Mechanical Engineering Design*, §8-2, Eq. (8-5); docs/paper-audit.md §5.

    Examples
    --------
    μ = 0.1 on a Tr flank (β = 15°): atan(0.1/cos 15°) = atan(0.1/0.965926) = atan(0.103528)
    = 0.10316 rad.

    >>> import math
    >>> round(friction_angle_thread(0.1, math.radians(15.0)), 5)
    0.10316
    """
    mu = _mu("friction_angle_thread (power screw)", mu)
    beta = np.asarray(flank_half_angle, dtype=float)
    check_range("friction_angle_thread (power screw)", "flank_half_angle", beta, 0.0,
                _MAX_FLANK)
    return _out(np.arctan(mu / np.cos(beta)))


def torque_thread_load(F_axial, d2, lead, mu, flank_half_angle):
    r"""Dissipated part of the thread torque under an axial load.

    .. math:: M_F = |F|\,\frac{d_2}{2}\left[\tan(\varphi+\rho') - \tan\varphi\right]

    Parameters
    ----------
    F_axial : float or array_like
        Axial load on the nut, [N]; the sign is ignored.
    d2, lead : float or array_like
        Pitch diameter and lead, [m].
    mu : float or array_like
        Flank Coulomb coefficient, [-]; validity (0, 0.5].
    flank_half_angle : float or array_like
        β, [rad]; validity [0, 45°).

    Returns
    -------
    float or ndarray
        M_F, [N·m]: Shigley's raising torque minus the useful part F r₂ tan φ = F P_h/2π.

    Notes
    -----
    The raising form is used for either load direction; an overhauling load dissipates
    F r₂[tan φ − tan(φ−ρ′)], slightly less (tan is convex), so this is an upper bound.
    No collar friction (the nut runs in its own bearing).

    References
    ----------
    .. [1] Shigley's *Mechanical Engineering Design*, §8-2, Eq. (8-1), (8-5); docs/paper-audit.md §5.

    Examples
    --------
    Shigley Example 8-1 (square thread, d_m = 30 mm, l = 8 mm, f = 0.08, F = 6.4 kN): raising
    torque T_R = 15.94 N·m, of which F·l/(2π) = 8.149 N·m is useful work.

    >>> import math
    >>> F, d_m, lead = 6400.0, 0.030, 0.008
    >>> round(torque_thread_load(F, d_m, lead, 0.08, 0.0) + F * lead / (2 * math.pi), 2)
    15.94
    """
    phi, rho = helix_angle(lead, d2), friction_angle_thread(mu, flank_half_angle)
    F = np.abs(np.asarray(F_axial, dtype=float))
    return _out(F * np.asarray(d2, float) / 2.0 * (np.tan(phi + rho) - np.tan(phi)))


def torque_thread_preload(F_preload, d2, lead, mu, flank_half_angle):
    r"""Friction torque of a split nut whose halves are preloaded against each other.

    .. math:: M_p = F_p\,\frac{d_2}{2}\left[\tan(\varphi+\rho') - \tan(\varphi-\rho')\right]

    Parameters
    ----------
    F_preload : float or array_like
        Preload between the nut halves, [N]; ≥ 0.
    d2, lead : float or array_like
        Pitch diameter and lead, [m].
    mu : float or array_like
        Flank Coulomb coefficient, [-]; validity (0, 0.5].
    flank_half_angle : float or array_like
        β, [rad]; validity [0, 45°).

    Returns
    -------
    float or ndarray
        M_p, [N·m]; all of it is dissipated.

    Notes
    -----
    One half "raises" F_p (T_R = F_p r₂ tan(φ+ρ′)), the other "lowers" it (T_L =
    F_p r₂ tan(ρ′−φ)); M_p = T_R + T_L. With an external load on one (rigid) half,
    M_T = M_p + :func:`torque_thread_load` exactly. Tr32×10, μ 0.1, 500 N: 1.545 N·m.

    References
    ----------
    .. [1] Shigley's *Mechanical Engineering Design*, §8-2, Eqs. (8-1), (8-2), (8-5);
       docs/paper-audit.md §5.

    Examples
    --------
    Shigley Example 8-1 as a split nut preloaded with F = 6.4 kN: T_R + T_L = 15.94 − 0.466
    = 15.47 N·m.

    >>> round(torque_thread_preload(6400.0, 0.030, 0.008, 0.08, 0.0), 2)
    15.47
    """
    F_p = _nonnegative("F_preload", F_preload)
    phi, rho = helix_angle(lead, d2), friction_angle_thread(mu, flank_half_angle)
    return _out(F_p * np.asarray(d2, float) / 2.0 * (np.tan(phi + rho) - np.tan(phi - rho)))


def torque_grease_shear(eta, omega, r2, area, gap):
    r"""Couette (Petroff) shear torque of the grease film between screw and nut.

    .. math:: M_\eta = \eta\,|\omega|\,r_2^2\,A/h

    Parameters
    ----------
    eta : float or array_like
        Apparent dynamic viscosity of the grease, [Pa·s].
    omega : float or array_like
        Relative angular speed, [rad/s]; the sign is ignored.
    r2, area, gap : float or array_like
        Pitch radius [m], sheared area [m²] and film thickness h [m].

    Returns
    -------
    float or ndarray
        M_η, [N·m].

    Notes
    -----
    Newtonian, shear rate ω r₂/h; the helix (1/cos φ ≈ 1.006) is ignored and grease
    shear thinning must be folded into an apparent η at that rate.

    References
    ----------
    .. [1] Petroff (1883); Shigley's *Mechanical Engineering Design*, §12 (Petroff's
       equation); docs/paper-audit.md §5.

    Examples
    --------
    η = 1 Pa·s, 36 rpm (3.76991 rad/s), r₂ = 14.75 mm, A = π·0.0295·0.060 = 5.5606e-3 m²,
    h = 0.3 mm: 1·3.76991·2.175625e-4·5.5606e-3/3e-4 = 0.015203 N·m.

    >>> import math
    >>> round(torque_grease_shear(1.0, 2 * math.pi * 36 / 60, 0.01475, 5.5606e-3, 3e-4), 6)
    0.015203
    """
    eta = _nonnegative("eta", eta)
    r2, area, gap = _positive("r2", r2), _positive("area", area), _positive("gap", gap)
    return _out(eta * np.abs(np.asarray(omega, dtype=float)) * r2**2 * area / gap)


def normal_load_flank(F_axial, n_flanks, flank_half_angle, helix_angle):
    r"""Normal load per engaged flank, equal sharing.

    .. math:: Q_j = \frac{|F|}{\sigma\cos\beta\cos\varphi}

    Parameters
    ----------
    F_axial : float or array_like
        Axial load, [N]; the sign is ignored.
    n_flanks : int or array_like
        Engaged (loaded) flanks σ, [-].
    flank_half_angle, helix_angle : float or array_like
        β and φ, [rad].

    Returns
    -------
    float or ndarray
        Q_j, [N].

    Notes
    -----
    Equal sharing is an idealisation (the first threads carry most); friction and the
    normal-plane angle (tan α_n = tan β cos φ; 0.04 % for Tr32×10) are neglected.

    References
    ----------
    .. [1] Paper, Eqs. 3, 8 (Q_j); Shigley §8-2; docs/paper-audit.md §5.

    Examples
    --------
    500 N over 12 Tr flanks (β = 15°, φ = 6.158° = 0.107486 rad): 500/(12·0.965926·0.994229)
    = 500/11.5242 = 43.387 N.

    >>> import math
    >>> round(normal_load_flank(500.0, 12, math.radians(15.0), 0.107486), 3)
    43.387
    """
    sigma, F = _positive("n_flanks", n_flanks), np.abs(np.asarray(F_axial, dtype=float))
    return _out(F / (sigma * np.cos(flank_half_angle) * np.cos(helix_angle)))


@dataclass(frozen=True)
class SlidingScrewTorque:
    """Friction torque of a sliding screw–nut pair by cause, all [N·m]."""

    load: float
    preload: float
    grease: float
    total: float


def torque_screw_nut_sliding(F_axial, F_preload, d2, lead, mu, flank_half_angle, eta, gap,
                         engaged_length, n_rel_rpm) -> SlidingScrewTorque:
    r"""Friction torque of a (split, preloaded) trapezoidal screw–nut pair.

    .. math:: M_T = |F| r_2[\tan(\varphi+\rho')-\tan\varphi]
              + F_p r_2[\tan(\varphi+\rho')-\tan(\varphi-\rho')]
              + \eta|\omega| r_2^2\,\pi d_2 L_e/h

    Parameters
    ----------
    F_axial, F_preload : float
        External axial load (sign ignored) and split-nut preload, [N].
    d2, lead : float
        Pitch diameter and lead, [m].
    mu : float
        Flank Coulomb coefficient, [-]; validity (0, 0.5].
    flank_half_angle : float
        β, [rad]; validity [0, 45°).
    eta, gap : float
        Apparent grease viscosity [Pa·s] and film thickness [m].
    engaged_length : float
        Engaged nut length L_e, [m].
    n_rel_rpm : float
        Relative speed n_screw − n_nut, [rpm]; only the grease term depends on it.

    Returns
    -------
    SlidingScrewTorque
        ``load``, ``preload``, ``grease`` and ``total``, [N·m].

    Notes
    -----
    The wetted area A = π d₂ L_e (pitch cylinder over the engaged length) is an estimate;
    the real flank area differs, so treat η·A/h as one calibrated group.

    References
    ----------
    .. [1] Shigley's *Mechanical Engineering Design*, §8-2; Petroff (1883); docs/paper-audit.md §5.

    Examples
    --------
    docs/paper-audit.md §5, Tr32×10 (d₂ = 29.5 mm), μ = 0.10, F_p = 500 N, 25 N of guideway
    friction, no grease term: M_T = 0.039 + 1.545 = 1.58 N·m.

    >>> import math
    >>> t = torque_screw_nut_sliding(25.0, 500.0, 0.0295, 0.010, 0.10, math.radians(15.0),
    ...                              0.0, 3e-4, 0.060, 36.0)
    >>> round(t.load, 3), round(t.preload, 3), round(t.total, 2)
    (0.039, 1.545, 1.58)
    """
    M_load = torque_thread_load(F_axial, d2, lead, mu, flank_half_angle)
    M_pre = torque_thread_preload(F_preload, d2, lead, mu, flank_half_angle)
    area = math.pi * _positive("d2", d2) * _positive("engaged_length", engaged_length)
    r2 = np.asarray(d2, dtype=float) / 2.0
    M_grease = torque_grease_shear(eta, angular_speed(n_rel_rpm), r2, area, gap)
    return SlidingScrewTorque(M_load, M_pre, M_grease, _out(M_load + M_pre + M_grease))


def heat_screw_nut(torque, n_screw_rpm, n_nut_rpm):
    r"""Heat of the screw–nut pair at the relative speed (paper Eq. 23).

    .. math:: H_T = |M_T|\,2\pi|n_s - n_n|/60

    Parameters
    ----------
    torque : float or array_like
        Friction torque M_T, [N·m].
    n_screw_rpm, n_nut_rpm : float or array_like
        Signed speeds of screw and nut, same sense = same sign, [rpm].

    Returns
    -------
    float or ndarray
        H_T, [W].

    Notes
    -----
    Eq. 23 (H = M n_T/9550, M in N·mm) in SI, with n_T = |n_s − n_n| (36 rpm in
    condition I, not 396 rpm).

    References
    ----------
    .. [1] Paper, Eq. 23 (docs/paper-audit.md §1, §2).

    Examples
    --------
    docs/paper-audit.md §5: 1.584 N·m at |396 − 360| = 36 rpm gives 1.584·3.7699 = 6.0 W.

    >>> round(heat_screw_nut(1.584, 396.0, 360.0), 1)
    6.0
    """
    n_rel = np.asarray(n_screw_rpm, dtype=float) - np.asarray(n_nut_rpm, dtype=float)
    return heat_friction(torque, n_rel)
