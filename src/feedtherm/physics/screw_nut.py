r"""Friction torque and heat of the sliding screw–nut pair (paper Eqs. 1–12, 23).

Two models. (1) The paper's three-part *rolling-analogy* model — differential sliding,
elastic hysteresis, EHL rolling resistance — with its printed errors corrected (AUDIT §1).
(2) The *sliding* model of a trapezoidal thread (AUDIT §5): Shigley's power-screw torque
with the flank angle, a split-nut preload and Couette grease shear.  Tr flanks are
conformal helicoids (no Hertz radius R), so (2) is the model for the real nut; the
rolling terms of (1) come out ~10³× too small.  SI units throughout; rpm only where named.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from feedtherm.physics.mechanics import angular_speed, frictional_power
from feedtherm.physics.validity import check_range

#: Tabor/Johnson hysteresis coefficient of a sphere, F = (3/16) α W a/R (Johnson §9.2).
KAPPA_SPHERE = 3.0 / 16.0
_MAX_FLANK = float(np.nextafter(math.pi / 4.0, 0.0))  # 45°, exclusive
_MIN_MU = float(np.nextafter(0.0, 1.0))  # 0, exclusive


def _out(value):
    """Return a Python float for 0-d results so scalars stay scalars."""
    value = np.asarray(value, dtype=float)
    return float(value) if value.ndim == 0 else value


def _positive(name: str, value) -> np.ndarray:
    arr = np.asarray(value, dtype=float)
    if not np.all(arr > 0.0):
        raise ValueError(f"{name} must be positive (got {value!r})")
    return arr


def _nonnegative(name: str, value) -> np.ndarray:
    arr = np.asarray(value, dtype=float)
    if not np.all(arr >= 0.0):
        raise ValueError(f"{name} must not be negative (got {value!r})")
    return arr


def _mu(correlation: str, mu) -> np.ndarray:
    """Coulomb coefficient: negative raises, outside (0, 0.5] warns."""
    mu = _nonnegative("mu", mu)
    check_range(correlation, "mu", mu, _MIN_MU, 0.5)
    return mu


def effective_modulus(E1, nu1, E2, nu2):
    r"""Hertz reduced modulus E* of screw and nut (paper Eq. 10, correct as printed).

    .. math:: E^* = \left[(1-\nu_1^2)/E_1 + (1-\nu_2^2)/E_2\right]^{-1}

    Parameters
    ----------
    E1, nu1, E2, nu2 : float or array_like
        Young's moduli [Pa] and Poisson's ratios [-] of the two bodies.

    Returns
    -------
    float or ndarray
        E*, [Pa].

    Notes
    -----
    Use E* in Hertz's formulae (:func:`hertz_semi_minor_axis`); Eq. 9 needs E′ = 2E*.
    ν outside [−1, 0.5] warns.

    References
    ----------
    .. [1] Paper, Eq. 10. Johnson, *Contact Mechanics* (1985), Eq. (4.22).
    """
    _positive("E1", E1), _positive("E2", E2)
    check_range("effective_modulus (Eq. 10)", "nu", [nu1, nu2], -1.0, 0.5)
    return _out(1.0 / ((1.0 - np.square(nu1)) / E1 + (1.0 - np.square(nu2)) / E2))


def hamrock_modulus(E1, nu1, E2, nu2):
    r"""Hamrock–Dowson effective modulus E′ = 2E*, as needed by Eq. 9.

    .. math:: E' = 2\left[(1-\nu_1^2)/E_1 + (1-\nu_2^2)/E_2\right]^{-1}

    Parameters
    ----------
    E1, nu1, E2, nu2 : float or array_like
        Young's moduli [Pa] and Poisson's ratios [-] of the two bodies.

    Returns
    -------
    float or ndarray
        E′, [Pa].

    Notes
    -----
    The paper feeds Eq. 10 (E*) to Eq. 9. As F ∝ E′^(1−0.66+0.022−0.47) = E′^−0.108, E*
    overestimates F_l by 2^0.108 = 1.078. Steel–steel (E = 207.5 GPa, ν = 0.3): 2.28e11 Pa.

    References
    ----------
    .. [1] Paper, Eqs. 9–10 (AUDIT §1). Hamrock & Dowson, *Ball Bearing Lubrication* (1981).
    """
    return _out(2.0 * effective_modulus(E1, nu1, E2, nu2))


def heathcote_bracket(X1, X2):
    r"""Bracket of Eq. 3, the signed integral of (X² − X⁴) over the contact, closed form.

    .. math:: \int_{-1}^{1}(X^2-X^4)dX - 2\int_{X_1}^{X_2}(X^2-X^4)dX
              = \frac{4}{15} - 2\left[\frac{X^3}{3}-\frac{X^5}{5}\right]_{X_1}^{X_2}

    Parameters
    ----------
    X1, X2 : float or array_like
        Pure-rolling lines on the major axis, X = x/a, [-]; −1 ≤ X1 ≤ X2 ≤ 1.

    Returns
    -------
    float or ndarray
        Bracket, [-].

    Notes
    -----
    Zero net tangential force puts the rolling lines at ±2 cos 80° = ±0.3473 (roots of
    X³ − 3X + 1 = 0): bracket 0.2149 (Heathcote).

    References
    ----------
    .. [1] Paper, Eqs. 3–4. Heathcote (1921); Johnson, *Contact Mechanics* (1985) §8.
    """
    X1, X2 = np.asarray(X1, dtype=float), np.asarray(X2, dtype=float)
    if np.any(X1 < -1.0) or np.any(X2 > 1.0) or np.any(X1 > X2):
        raise ValueError(f"need -1 <= X1 <= X2 <= 1 (got X1={X1}, X2={X2})")
    def primitive(X):
        return X**3 / 3.0 - X**5 / 5.0

    return _out(4.0 / 15.0 - 2.0 * (primitive(X2) - primitive(X1)))


def differential_sliding_torque_contact(mu, Q, a, R, X1, X2):
    r"""Differential-sliding torque of one rolling contact (paper Eq. 3, corrected).

    .. math:: M_{dj} = \frac{3}{4}\mu Q_j\frac{a^2}{2R}\left[\int_{-1}^{1}(X^2-X^4)dX
              - 2\int_{X_1}^{X_2}(X^2-X^4)dX\right]

    Parameters
    ----------
    mu : float or array_like
        Coulomb coefficient in the slip zones, [-]; validity (0, 0.5].
    Q : float or array_like
        Normal load of the contact, [N].
    a, R : float or array_like
        Semi-major axis of the contact ellipse and effective ball radius, [m].
    X1, X2 : float or array_like
        Pure-rolling lines, [-] (:func:`heathcote_bracket`).

    Returns
    -------
    float or ndarray
        M_dj, [N·m].

    Notes
    -----
    Hertz line load q = (3Q/4a)(1 − X²) and lever arm z = x²/2R give the prefactor 3/4;
    the printed 0.1 is 7.5× smaller. X = ±0.347: M = 0.0806 μQa²/R. Ball/roller contacts
    only — a conformal Tr flank has R → ∞.

    References
    ----------
    .. [1] Paper, Eq. 3 (AUDIT §1). Heathcote (1921); Johnson, *Contact Mechanics* (1985)
       §8; Harris & Kotzalas, *Rolling Bearing Analysis* 5th ed.
    """
    mu = _mu("differential_sliding_torque_contact (Eq. 3)", mu)
    Q, a, R = _nonnegative("Q", Q), _positive("a", a), _positive("R", R)
    return _out(0.75 * mu * Q * a**2 / (2.0 * R) * heathcote_bracket(X1, X2))


def differential_sliding_torque(contact_torques, contact_angle):
    r"""Differential-sliding torque of all engaged contacts (paper Eq. 5).

    .. math:: M_d = \sum_{j=1}^{\sigma} M_{dj}\cos\alpha

    Parameters
    ----------
    contact_torques : array_like
        M_dj of each engaged contact, [N·m].
    contact_angle : float or array_like
        Contact angle α, scalar or per contact, [rad]; flank half angle β = 15° for Tr.

    Returns
    -------
    float
        M_d, [N·m].

    Notes
    -----
    The paper leaves α undefined (and reuses α for thermal expansion).

    References
    ----------
    .. [1] Paper, Eq. 5 (AUDIT §1).
    """
    torques = np.asarray(contact_torques, dtype=float)
    return float(np.sum(torques * np.cos(np.asarray(contact_angle, dtype=float))))


def hertz_semi_minor_axis(gamma, Q, E_star, sum_rho):
    r"""Hertz semi-minor axis of an elliptical contact.

    .. math:: b = \gamma\left[\frac{3Q}{2E^*\sum\rho}\right]^{1/3}

    Parameters
    ----------
    gamma : float or array_like
        Dimensionless semi-minor-axis coefficient b* (1 for a circle), [-].
    Q : float or array_like
        Normal load, [N].
    E_star : float or array_like
        Reduced modulus E* (:func:`effective_modulus`), [Pa].
    sum_rho : float or array_like
        Curvature sum Σρ, [1/m].

    Returns
    -------
    float or ndarray
        b, [m].

    Notes
    -----
    Sphere on a plane (γ = 1, Σρ = 2/R) reduces to a = (3QR/4E*)^(1/3). Eq. 8 as printed
    puts E in the numerator, which is dimensionally wrong.

    References
    ----------
    .. [1] Paper, Eq. 8 (AUDIT §1). Johnson, *Contact Mechanics* (1985) §4.2; Harris &
       Kotzalas, *Rolling Bearing Analysis* 5th ed.
    """
    gamma, E_star = _positive("gamma", gamma), _positive("E_star", E_star)
    Q, sum_rho = _nonnegative("Q", Q), _positive("sum_rho", sum_rho)
    return _out(gamma * np.cbrt(3.0 * Q / (2.0 * E_star * sum_rho)))


def hysteresis_torque_contact(alpha_h, Q, b, R, r_m, kappa=KAPPA_SPHERE):
    r"""Elastic-hysteresis torque of one rolling contact (paper Eqs. 6–8, corrected).

    .. math:: M_{fj} = \kappa\,\alpha_h\,Q_j\,\frac{b}{R}\,r_m

    Parameters
    ----------
    alpha_h : float or array_like
        Hysteresis loss fraction, [-]; validity [0, 1].
    Q : float or array_like
        Normal load, [N].
    b, R : float or array_like
        Contact semi-axis in the rolling direction and rolling radius, [m].
    r_m : float or array_like
        Lever arm of the resistance about the screw axis, [m].
    kappa : float, optional
        Geometric coefficient, [-]; default 3/16.

    Returns
    -------
    float or ndarray
        M_fj, [N·m].

    Notes
    -----
    Tabor: the leading-half pressure of a circular contact has a moment 3Qb/16, so the
    work per unit rolled distance is (3/16)Qb/R and F_h = (3/16)α_h Qb/R (κ = 3/16).  The
    paper's 3/32 (also in some bearing texts) goes with a loss factor α′ = 2α_h on another
    reference energy: pass ``kappa=3/32`` only with such an α′.  As printed, Eq. 6
    multiplies by B = 2R where R must divide, Eq. 7 yields a force, Eq. 8 has E for 1/E*.
    Combined with :func:`hertz_semi_minor_axis`: M ∝ γ(3/(2E*Σρ))^(1/3) Q^(4/3) r_m/R.

    References
    ----------
    .. [1] Paper, Eqs. 6–8 (AUDIT §1). Johnson, *Contact Mechanics* (1985) §9.2; Tabor
       (1955).
    """
    check_range("hysteresis_torque_contact (Eqs. 6-8)", "alpha_h", alpha_h, 0.0, 1.0)
    Q, b, R = _nonnegative("Q", Q), _positive("b", b), _positive("R", R)
    return _out(kappa * np.asarray(alpha_h, float) * Q * b / R * _positive("r_m", r_m))


def ellipticity(Ry, Rx):
    r"""Contact ellipticity k = a/b from the radius ratio (Hamrock–Brewe fit).

    .. math:: k \approx 1.0339\,(R_y/R_x)^{0.636}

    Parameters
    ----------
    Ry, Rx : float or array_like
        Effective radii across and along the rolling direction, [m].

    Returns
    -------
    float or ndarray
        k, [-].

    Notes
    -----
    Fit within ~3 % for 1 ≤ R_y/R_x ≤ 100 (warns outside); k(1) = 1.0339, not 1.

    References
    ----------
    .. [1] Paper, Eq. 9. Hamrock & Brewe, *J. Lubr. Technol.* 105 (1983) 171–177.
    """
    ratio = _positive("Ry", Ry) / _positive("Rx", Rx)
    check_range("ellipticity (Hamrock-Brewe)", "Ry/Rx", ratio, 1.0, 100.0)
    return _out(1.0339 * ratio**0.636)


def ehl_dimensionless_groups(eta0, alpha_p, u, Q, E_prime, Rx):
    r"""Hamrock–Dowson speed, material and load parameters.

    .. math:: U = \frac{\eta_0 u}{E'R_x},\quad G = \alpha_p E',\quad W = \frac{Q}{E'R_x^2}

    Parameters
    ----------
    eta0 : float or array_like
        Viscosity at ambient pressure, [Pa·s].
    alpha_p : float or array_like
        Pressure-viscosity coefficient, [1/Pa].
    u : float or array_like
        Mean entraining speed, [m/s]; the sign is ignored.
    Q : float or array_like
        Normal load, [N].
    E_prime, Rx : float or array_like
        E′ = 2E* [Pa] and effective radius along the rolling direction [m].

    Returns
    -------
    tuple
        (U, G, W), each [-].

    Notes
    -----
    Definitions require E′ (:func:`hamrock_modulus`), not the paper's E*.

    References
    ----------
    .. [1] Paper, Eq. 9. Hamrock & Dowson, *Ball Bearing Lubrication* (1981).
    """
    eta0, alpha_p = _nonnegative("eta0", eta0), _nonnegative("alpha_p", alpha_p)
    Q = _nonnegative("Q", Q)
    E_prime, Rx = _positive("E_prime", E_prime), _positive("Rx", Rx)
    U = eta0 * np.abs(np.asarray(u, dtype=float)) / (E_prime * Rx)
    return _out(U), _out(alpha_p * E_prime), _out(Q / (E_prime * Rx**2))


def ehl_rolling_resistance(E_prime, Rx, k, G, U, W, f_t=1.0):
    r"""EHL rolling-resistance force of one rolling contact (paper Eq. 9).

    .. math:: F_l = 2.86\,E'R_x^2\,k^{0.348}G^{0.022}U^{0.66}W^{0.47}f_t

    Parameters
    ----------
    E_prime, Rx : float or array_like
        E′ = 2E* [Pa] and effective radius along the rolling direction [m].
    k : float or array_like
        Ellipticity (:func:`ellipticity`), [-].
    G, U, W : float or array_like
        Dimensionless groups (:func:`ehl_dimensionless_groups`), [-].
    f_t : float or array_like, optional
        Thermal reduction factor, [-]; 1 = isothermal.

    Returns
    -------
    float or ndarray
        F_l, [N].

    Notes
    -----
    Fully flooded rolling point contacts only; no model for sliding flanks.

    References
    ----------
    .. [1] Paper, Eq. 9 (AUDIT §1). Houpert, *Tribol. Trans.* (1999); Harris & Kotzalas,
       *Rolling Bearing Analysis* 5th ed.
    """
    E_prime, Rx, k = _positive("E_prime", E_prime), _positive("Rx", Rx), _positive("k", k)
    G, U, W = _nonnegative("G", G), _nonnegative("U", U), _nonnegative("W", W)
    F = 2.86 * E_prime * Rx**2 * k**0.348 * G**0.022 * U**0.66 * W**0.47
    return _out(F * np.asarray(f_t, dtype=float))


def viscous_torque_contact(F_l, d2):
    r"""Lubrication torque of one contact (paper Eq. 11, corrected lever arm).

    .. math:: M_{lj} = F_{lj}\,d_2/2

    Parameters
    ----------
    F_l : float or array_like
        Viscous resistance of the contact (Eq. 9), [N].
    d2 : float or array_like
        Pitch diameter, [m].

    Returns
    -------
    float or ndarray
        M_lj, [N·m].

    Notes
    -----
    The force acts at the pitch radius, not at the printed nominal radius d/2 (which
    overestimates by d/d₂, 8.5 % for Tr32).

    References
    ----------
    .. [1] Paper, Eqs. 11–12 (AUDIT §1).
    """
    return _out(np.asarray(F_l, dtype=float) * _positive("d2", d2) / 2.0)


def paper_friction_torque(M_d, M_f, M_l):
    r"""Total torque of the three-part model (paper Eq. 1, corrected).

    .. math:: M_T = M_d + M_f + M_l

    Parameters
    ----------
    M_d, M_f, M_l : float or array_like
        Sliding (Eq. 5), hysteresis (Eq. 8) and lubrication (Eq. 12) torques, each
        already summed over the σ engaged threads, [N·m].

    Returns
    -------
    float or ndarray
        M_T, [N·m].

    Notes
    -----
    The printed outer Σ would count each contact σ times. Eq. 7 calls M_f "M_e".

    References
    ----------
    .. [1] Paper, Eq. 1 (AUDIT §1).
    """
    return _out(np.asarray(M_d, float) + np.asarray(M_f, float) + np.asarray(M_l, float))


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
    .. [1] Shigley's *Mechanical Engineering Design*, §8-2 (power screws); AUDIT §5.
    """
    return _out(np.arctan(_positive("lead", lead) / (math.pi * _positive("d2", d2))))


def thread_friction_angle(mu, flank_half_angle):
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
    .. [1] Shigley's *Mechanical Engineering Design*, §8-2, Eq. (8-5); AUDIT §5.
    """
    mu = _mu("thread_friction_angle (power screw)", mu)
    beta = np.asarray(flank_half_angle, dtype=float)
    check_range("thread_friction_angle (power screw)", "flank_half_angle", beta, 0.0,
                _MAX_FLANK)
    return _out(np.arctan(mu / np.cos(beta)))


def load_friction_torque(F_axial, d2, lead, mu, flank_half_angle):
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
    .. [1] Shigley's *Mechanical Engineering Design*, §8-2, Eq. (8-1), (8-5); AUDIT §5.
    """
    phi, rho = helix_angle(lead, d2), thread_friction_angle(mu, flank_half_angle)
    F = np.abs(np.asarray(F_axial, dtype=float))
    return _out(F * np.asarray(d2, float) / 2.0 * (np.tan(phi + rho) - np.tan(phi)))


def preload_friction_torque(F_preload, d2, lead, mu, flank_half_angle):
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
    M_T = M_p + :func:`load_friction_torque` exactly. Tr32×10, μ 0.1, 500 N: 1.545 N·m.

    References
    ----------
    .. [1] Shigley's *Mechanical Engineering Design*, §8-2, Eqs. (8-1), (8-2), (8-5);
       AUDIT §5.
    """
    F_p = _nonnegative("F_preload", F_preload)
    phi, rho = helix_angle(lead, d2), thread_friction_angle(mu, flank_half_angle)
    return _out(F_p * np.asarray(d2, float) / 2.0 * (np.tan(phi + rho) - np.tan(phi - rho)))


def grease_shear_torque(eta, omega, r2, area, gap):
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
       equation); AUDIT §5.
    """
    eta = _nonnegative("eta", eta)
    r2, area, gap = _positive("r2", r2), _positive("area", area), _positive("gap", gap)
    return _out(eta * np.abs(np.asarray(omega, dtype=float)) * r2**2 * area / gap)


def flank_normal_load(F_axial, n_flanks, flank_half_angle, helix_angle):
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
    .. [1] Paper, Eqs. 3, 8 (Q_j); Shigley §8-2; AUDIT §5.
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


def sliding_screw_torque(F_axial, F_preload, d2, lead, mu, flank_half_angle, eta, gap,
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
    .. [1] Shigley's *Mechanical Engineering Design*, §8-2; Petroff (1883); AUDIT §5.
    """
    M_load = load_friction_torque(F_axial, d2, lead, mu, flank_half_angle)
    M_pre = preload_friction_torque(F_preload, d2, lead, mu, flank_half_angle)
    area = math.pi * _positive("d2", d2) * _positive("engaged_length", engaged_length)
    r2 = np.asarray(d2, dtype=float) / 2.0
    M_grease = grease_shear_torque(eta, angular_speed(n_rel_rpm), r2, area, gap)
    return SlidingScrewTorque(M_load, M_pre, M_grease, _out(M_load + M_pre + M_grease))


def screw_nut_heat(torque, n_screw_rpm, n_nut_rpm):
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
    .. [1] Paper, Eq. 23 (AUDIT §1, §2).
    """
    n_rel = np.asarray(n_screw_rpm, dtype=float) - np.asarray(n_nut_rpm, dtype=float)
    return frictional_power(torque, n_rel)
