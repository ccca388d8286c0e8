r"""The paper's three-part rolling-analogy friction torque of the screw–nut pair (Eqs. 1–12).

Differential sliding, elastic hysteresis and EHL rolling resistance, with the paper's
printed errors corrected (docs/paper-audit.md §1).  Tr flanks are conformal helicoids (no Hertz radius
R), so the sliding model of :mod:`feedtherm.physics.screw_nut` is the model for the real
nut; the rolling terms here come out ~10³× too small.  For a ball screw, where balls do roll
in their grooves, the source model ``ball_screw`` (:mod:`feedtherm.physics.ball_screw`,
boundary/heat.py) builds on these terms.  SI units throughout.

Names end in the source where two conventions or approximations exist for the same
quantity: E* (``effective_modulus_Hertz``) vs. E′ = 2E* (``..._Hamrock_Dowson``); the
exact Hertz semi-axis vs. Hamrock & Brewe's fitted ellipticity.
"""

from __future__ import annotations

import numpy as np

from feedtherm.physics._arrays import scalar_or_array as _out
from feedtherm.physics._checks import coulomb_mu as _mu
from feedtherm.physics._checks import nonnegative as _nonnegative
from feedtherm.physics._checks import positive as _positive
from feedtherm.physics.validity import check_range

#: Tabor/Johnson hysteresis coefficient of a sphere, F = (3/16) α W a/R (Johnson §9.2).
KAPPA_SPHERE = 3.0 / 16.0


def effective_modulus_Hertz(E1, nu1, E2, nu2):
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
    Use E* in Hertz's formulae (:func:`semi_minor_axis_Hertz`); Eq. 9 needs E′ = 2E*.
    ν outside [−1, 0.5] warns.

    References
    ----------
    .. [1] Paper, Eq. 10. Johnson, *Contact Mechanics* (1985), Eq. (4.22).

    Examples
    --------
    Steel on steel, E = 210 GPa, ν = 0.3: E* = E/(2(1 − ν²)) = 2.1e11/1.82 = 1.1538e11 Pa.

    >>> round(effective_modulus_Hertz(2.1e11, 0.3, 2.1e11, 0.3) / 1e11, 4)
    1.1538
    """
    _positive("E1", E1), _positive("E2", E2)
    check_range("effective_modulus_Hertz (Eq. 10)", "nu", [nu1, nu2], -1.0, 0.5)
    return _out(1.0 / ((1.0 - np.square(nu1)) / E1 + (1.0 - np.square(nu2)) / E2))


def effective_modulus_Hamrock_Dowson(E1, nu1, E2, nu2):
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
    .. [1] Paper, Eqs. 9–10 (docs/paper-audit.md §1). Hamrock & Dowson, *Ball Bearing Lubrication* (1981).

    Examples
    --------
    Hamrock & Dowson's bearing steel (E = 207.5 GPa, ν = 0.3): E′ = 2.075e11/0.91 = 2.28e11 Pa.

    >>> round(effective_modulus_Hamrock_Dowson(2.075e11, 0.3, 2.075e11, 0.3) / 1e11, 2)
    2.28
    """
    return _out(2.0 * effective_modulus_Hertz(E1, nu1, E2, nu2))


def bracket_differential_sliding(X1, X2):
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

    Examples
    --------
    docs/paper-audit.md §1, Eq. 3: Heathcote's rolling lines ±c, c = 2 cos 80° = 0.347296:
    4/15 − 4(c³/3 − c⁵/5) = 0.26667 − 0.05181 = 0.21486.

    >>> import math
    >>> c = 2 * math.cos(math.radians(80.0))
    >>> round(bracket_differential_sliding(-c, c), 5)
    0.21486
    """
    X1, X2 = np.asarray(X1, dtype=float), np.asarray(X2, dtype=float)
    if np.any(X1 < -1.0) or np.any(X2 > 1.0) or np.any(X1 > X2):
        raise ValueError(f"need -1 <= X1 <= X2 <= 1 (got X1={X1}, X2={X2})")
    def primitive(X):
        return X**3 / 3.0 - X**5 / 5.0

    return _out(4.0 / 15.0 - 2.0 * (primitive(X2) - primitive(X1)))


def torque_differential_sliding_contact(mu, Q, a, R, X1, X2):
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
        Pure-rolling lines, [-] (:func:`bracket_differential_sliding`).

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
    .. [1] Paper, Eq. 3 (docs/paper-audit.md §1). Heathcote (1921); Johnson, *Contact Mechanics* (1985)
       §8; Harris & Kotzalas, *Rolling Bearing Analysis* 5th ed.

    Examples
    --------
    docs/paper-audit.md §1, Eq. 3: with the rolling lines at ±0.347, M_dj = 0.75·0.2150/2
    ·μQa²/R = 0.0806·μQa²/R (Heathcote). μ = 0.1, Q = 100 N, a = 1 mm, R = 15 mm:

    >>> M = torque_differential_sliding_contact(0.1, 100.0, 1e-3, 0.015, -0.347, 0.347)
    >>> round(M / (0.1 * 100.0 * 1e-3**2 / 0.015), 4)
    0.0806
    """
    mu = _mu("torque_differential_sliding_contact (Eq. 3)", mu)
    Q, a, R = _nonnegative("Q", Q), _positive("a", a), _positive("R", R)
    return _out(0.75 * mu * Q * a**2 / (2.0 * R) * bracket_differential_sliding(X1, X2))


def torque_differential_sliding(contact_torques, contact_angle):
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
    .. [1] Paper, Eq. 5 (docs/paper-audit.md §1).

    Examples
    --------
    (1e-4 + 2e-4 + 3e-4)·cos 15° = 6e-4·0.965926 = 5.7956e-4 N·m.

    >>> import math
    >>> round(torque_differential_sliding([1e-4, 2e-4, 3e-4], math.radians(15.0)) * 1e4, 4)
    5.7956
    """
    torques = np.asarray(contact_torques, dtype=float)
    return float(np.sum(torques * np.cos(np.asarray(contact_angle, dtype=float))))


def semi_minor_axis_Hertz(gamma, Q, E_star, sum_rho):
    r"""Hertz semi-minor axis of an elliptical contact.

    .. math:: b = \gamma\left[\frac{3Q}{2E^*\sum\rho}\right]^{1/3}

    Parameters
    ----------
    gamma : float or array_like
        Dimensionless semi-minor-axis coefficient b* (1 for a circle), [-].
    Q : float or array_like
        Normal load, [N].
    E_star : float or array_like
        Reduced modulus E* (:func:`effective_modulus_Hertz`), [Pa].
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
    .. [1] Paper, Eq. 8 (docs/paper-audit.md §1). Johnson, *Contact Mechanics* (1985) §4.2; Harris &
       Kotzalas, *Rolling Bearing Analysis* 5th ed.

    Examples
    --------
    Sphere on a plane (Johnson Eq. 4.22), Q = 100 N, R = 10 mm, E* = 2.1e11/1.82 Pa:
    a = (3QR/(4E*))^(1/3) = (3/4.61538e11)^(1/3) = (6.5e-12)^(1/3) = 1.8663e-4 m
    (γ = 1, Σρ = 2/R = 200 1/m).

    >>> round(semi_minor_axis_Hertz(1.0, 100.0, 2.1e11 / 1.82, 200.0) * 1e4, 4)
    1.8663
    """
    gamma, E_star = _positive("gamma", gamma), _positive("E_star", E_star)
    Q, sum_rho = _nonnegative("Q", Q), _positive("sum_rho", sum_rho)
    return _out(gamma * np.cbrt(3.0 * Q / (2.0 * E_star * sum_rho)))


def torque_hysteresis_contact(alpha_h, Q, b, R, r_m, kappa=KAPPA_SPHERE):
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
    Combined with :func:`semi_minor_axis_Hertz`: M ∝ γ(3/(2E*Σρ))^(1/3) Q^(4/3) r_m/R.

    References
    ----------
    .. [1] Paper, Eqs. 6–8 (docs/paper-audit.md §1). Johnson, *Contact Mechanics* (1985) §9.2; Tabor
       (1955).

    Examples
    --------
    κ = 3/16, α_h = 0.01, Q = 100 N, b = 1.8663e-4 m, R = 10 mm, r_m = 15 mm:
    0.1875·0.01·100·0.018663·0.015 = 5.2488e-5 N·m.

    >>> round(torque_hysteresis_contact(0.01, 100.0, 1.8662556e-4, 0.01, 0.015) * 1e5, 4)
    5.2488
    """
    check_range("torque_hysteresis_contact (Eqs. 6-8)", "alpha_h", alpha_h, 0.0, 1.0)
    Q, b, R = _nonnegative("Q", Q), _positive("b", b), _positive("R", R)
    return _out(kappa * np.asarray(alpha_h, float) * Q * b / R * _positive("r_m", r_m))


def ellipticity_Hamrock_Brewe(Ry, Rx):
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

    Examples
    --------
    R_y/R_x = 10: 1.0339·10^0.636 = 1.0339·4.32514 = 4.4718.

    >>> round(ellipticity_Hamrock_Brewe(0.05, 0.005), 4)
    4.4718
    """
    ratio = _positive("Ry", Ry) / _positive("Rx", Rx)
    check_range("ellipticity_Hamrock_Brewe", "Ry/Rx", ratio, 1.0, 100.0)
    return _out(1.0339 * ratio**0.636)


def dimensionless_groups_ehl(eta0, alpha_p, u, Q, E_prime, Rx):
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
    Definitions require E′ (:func:`effective_modulus_Hamrock_Dowson`), not the paper's E*.

    References
    ----------
    .. [1] Paper, Eq. 9. Hamrock & Dowson, *Ball Bearing Lubrication* (1981).

    Examples
    --------
    η₀ = 0.1 Pa·s, α_p = 2e-8 1/Pa, u = 0.5 m/s, Q = 100 N, E′ = 2.28e11 Pa, R_x = 5 mm:
    U = 0.05/(2.28e11·0.005) = 4.3860e-11, G = 2e-8·2.28e11 = 4560,
    W = 100/(2.28e11·2.5e-5) = 1.7544e-5.

    >>> U, G, W = dimensionless_groups_ehl(0.1, 2e-8, 0.5, 100.0, 2.28e11, 0.005)
    >>> round(U * 1e11, 4), round(G), round(W * 1e5, 4)
    (4.386, 4560, 1.7544)
    """
    eta0, alpha_p = _nonnegative("eta0", eta0), _nonnegative("alpha_p", alpha_p)
    Q = _nonnegative("Q", Q)
    E_prime, Rx = _positive("E_prime", E_prime), _positive("Rx", Rx)
    U = eta0 * np.abs(np.asarray(u, dtype=float)) / (E_prime * Rx)
    return _out(U), _out(alpha_p * E_prime), _out(Q / (E_prime * Rx**2))


def rolling_resistance_ehl(E_prime, Rx, k, G, U, W, f_t=1.0):
    r"""EHL rolling-resistance force of one rolling contact (paper Eq. 9).

    .. math:: F_l = 2.86\,E'R_x^2\,k^{0.348}G^{0.022}U^{0.66}W^{0.47}f_t

    Parameters
    ----------
    E_prime, Rx : float or array_like
        E′ = 2E* [Pa] and effective radius along the rolling direction [m].
    k : float or array_like
        Ellipticity (:func:`ellipticity_Hamrock_Brewe`), [-].
    G, U, W : float or array_like
        Dimensionless groups (:func:`dimensionless_groups_ehl`), [-].
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
    .. [1] Paper, Eq. 9 (docs/paper-audit.md §1). Houpert, *Tribol. Trans.* (1999); Harris & Kotzalas,
       *Rolling Bearing Analysis* 5th ed.

    Examples
    --------
    With the groups above and k = 4.4718: k^0.348 = 1.68409, G^0.022 = 1.20364,
    U^0.66 = 1.45802e-7, W^0.47 = 5.81753e-3, E′R_x² = 5.7e6 N;
    F = 2.86·5.7e6·1.68409·1.20364·1.45802e-7·5.81753e-3 = 2.8029e-2 N.

    >>> round(rolling_resistance_ehl(2.28e11, 0.005, 4.4717605, 4560.0, 4.3859649e-11,
    ...                              1.7543860e-5) * 1e2, 3)
    2.803
    """
    E_prime, Rx, k = _positive("E_prime", E_prime), _positive("Rx", Rx), _positive("k", k)
    G, U, W = _nonnegative("G", G), _nonnegative("U", U), _nonnegative("W", W)
    F = 2.86 * E_prime * Rx**2 * k**0.348 * G**0.022 * U**0.66 * W**0.47
    return _out(F * np.asarray(f_t, dtype=float))


def torque_viscous_contact(F_l, d2):
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
    .. [1] Paper, Eqs. 11–12 (docs/paper-audit.md §1).

    Examples
    --------
    F_l = 2 N at the pitch radius of Tr32 (d₂/2 = 14.75 mm): 0.0295 N·m (at the printed d/2
    = 16 mm: 0.032 N·m, 8.5 % more).

    >>> round(torque_viscous_contact(2.0, 0.0295), 6)
    0.0295
    """
    return _out(np.asarray(F_l, dtype=float) * _positive("d2", d2) / 2.0)


def torque_screw_nut_rolling(M_d, M_f, M_l):
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
    .. [1] Paper, Eq. 1 (docs/paper-audit.md §1).

    Examples
    --------
    12 contacts of 1e-5, 2e-5 and 3e-5 N·m: 12e-5 + 24e-5 + 36e-5 = 72e-5 N·m (the printed
    double sum would count each contact 12 times).

    >>> round(torque_screw_nut_rolling(12e-5, 24e-5, 36e-5) * 1e5, 9)
    72.0
    """
    return _out(np.asarray(M_d, float) + np.asarray(M_f, float) + np.asarray(M_l, float))
