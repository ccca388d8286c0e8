r"""Geometry, loads and kinematics of the ball contacts of a ball screw–nut pair.

What the rolling-contact terms of :mod:`feedtherm.physics.screw_nut_rolling` (paper Eqs.
1–12, corrected; docs/paper-audit.md §1) need to be applied to a ball screw: the normal load
per ball, the load sharing of a preloaded nut, the effective radii and the Hertz semi-axis
coefficient of a ball in a circular-arc (gothic-arch) groove, the radius of the deformed
contact surface (Heathcote slip) and the lever that turns a rolling resistance at a ball
contact into a torque about the screw axis.  The screw groove plays the inner race of an
angular-contact ball bearing, the nut groove the outer race.  SI units throughout.
"""

from __future__ import annotations

import math

import numpy as np

from feedtherm.physics._arrays import scalar_or_array as _out
from feedtherm.physics._checks import nonnegative as _nonnegative
from feedtherm.physics._checks import positive as _positive
from feedtherm.physics.validity import check_range

#: Axial load, in preloads, at which the unloaded ball set of a preloaded nut lifts off: 2^(3/2).
LIFT_OFF_RATIO = 2.0**1.5


def _contact_angle(contact_angle) -> np.ndarray:
    alpha = np.asarray(contact_angle, dtype=float)
    if not np.all((alpha > 0.0) & (alpha < math.pi / 2.0)):
        raise ValueError(f"contact_angle must lie between 0 and pi/2 rad (got {contact_angle!r})")
    return alpha


def _conformity(conformity) -> np.ndarray:
    f = np.asarray(conformity, dtype=float)
    if not np.all(f > 0.5):
        raise ValueError(f"conformity (groove radius / ball diameter) must exceed 0.5 (got {conformity!r})")
    return f


def normal_load_ball(F_axial, n_balls, contact_angle, helix_angle):
    r"""Normal load per ball of one ball set carrying an axial load, equal sharing.

    .. math:: Q = \frac{|F|}{z\,\sin\alpha\,\cos\lambda}

    Parameters
    ----------
    F_axial : float or array_like
        Axial load on the ball set, [N]; the sign is ignored.
    n_balls : int or array_like
        Loaded balls z of the set, [-].
    contact_angle : float or array_like
        Contact angle α between the contact normal and a plane normal to the screw axis,
        [rad]; validity (0, π/2).
    helix_angle : float or array_like
        Helix angle λ at the pitch diameter (:func:`feedtherm.physics.screw_nut.helix_angle`),
        [rad].

    Returns
    -------
    float or ndarray
        Q, [N].

    Notes
    -----
    The normal force lies in the groove's normal section, tilted by α from the radial
    direction and by λ from the axial plane, so its axial part is Q sin α cos λ. Equal
    sharing is an idealisation (the first turns carry more).

    References
    ----------
    .. [1] Harris & Kotzalas, *Rolling Bearing Analysis* 5th ed. (thrust load on an
       angular-contact set, Q = F/(z sin α)); Lin, Velinsky & Ravani, *J. Mech. Des.* 116
       (1994) 188–196 (the helix's cos λ).

    Examples
    --------
    1000 N on 20 balls at α = 45°, λ = 0: 1000/(20·0.7071068) = 70.711 N; a lead-10 screw
    at d_m = 26 mm (λ = atan(10/(π·26)) = 6.98°, cos λ = 0.992589) gives 71.239 N.

    >>> import math
    >>> round(normal_load_ball(1000.0, 20, math.radians(45.0), 0.0), 3)
    70.711
    >>> round(normal_load_ball(1000.0, 20, math.radians(45.0), math.atan(10 / (math.pi * 26))), 3)
    71.239
    """
    z, alpha = _positive("n_balls", n_balls), _contact_angle(contact_angle)
    F = np.abs(np.asarray(F_axial, dtype=float))
    return _out(F / (z * np.sin(alpha) * np.cos(np.asarray(helix_angle, dtype=float))))


def axial_loads_preloaded_nut(F_axial, F_preload):
    r"""Axial loads of the two ball sets of a preloaded nut under an external axial load.

    .. math:: F_1 - F_2 = |F|,\qquad F_1^{2/3} + F_2^{2/3} = 2F_p^{2/3}
              \quad(|F| < 2^{3/2}F_p);\qquad F_1 = |F|,\ F_2 = 0 \ \text{beyond}

    Parameters
    ----------
    F_axial : float
        External axial load on the nut, [N]; the sign is ignored.
    F_preload : float
        Axial preload between the two ball sets (double nut or offset lead), [N]; ≥ 0.

    Returns
    -------
    tuple of float
        (F₁, F₂): the set the load presses harder and the set it relieves, [N].

    Notes
    -----
    Each set deflects as a Hertz point contact, δ ∝ F^{2/3}; the sets are stacked against
    each other, so the load adds to one deflection what it takes from the other
    (δ₁ + δ₂ = 2δ_p). The relieved set lifts off at |F| = 2^{3/2}F_p = 2.83F_p, the
    "about three times the preload" of ball-screw catalogues. Without preload one set
    carries |F|. Scalars only (a root is solved).

    References
    ----------
    .. [1] Harris & Kotzalas, *Rolling Bearing Analysis* 5th ed. (preloaded duplex pairs);
       Johnson, *Contact Mechanics* (1985) §4.2 (δ ∝ Q^{2/3}).

    Examples
    --------
    Hand calculation: F₁ = 1728 N = 12³ and F₂ = 216 N = 6³ give F₁^{2/3} + F₂^{2/3} = 144 +
    36 = 180 = 2F_p^{2/3}, so F_p = 90^{3/2} = 853.815 N and |F| = 1728 − 216 = 1512 N.

    >>> F1, F2 = axial_loads_preloaded_nut(1512.0, 90.0**1.5)
    >>> round(F1, 6), round(F2, 6)
    (1728.0, 216.0)
    >>> axial_loads_preloaded_nut(0.0, 500.0), axial_loads_preloaded_nut(3000.0, 1000.0)
    ((500.0, 500.0), (3000.0, 0.0))
    """
    F, F_p = abs(float(F_axial)), float(_nonnegative("F_preload", F_preload))
    if F >= LIFT_OFF_RATIO * F_p:
        return F, 0.0
    if F == 0.0:
        return F_p, F_p
    from scipy.optimize import brentq  # 0.3 s to import: only where a preloaded nut is loaded

    budget = 2.0 * F_p ** (2.0 / 3.0)
    F2 = brentq(lambda x: (x + F) ** (2.0 / 3.0) + x ** (2.0 / 3.0) - budget, 0.0, F_p,
                xtol=1e-12 * F_p, rtol=1e-14)
    return F2 + F, F2


def radii_effective_ball_groove(ball_diameter, pitch_diameter, contact_angle, conformity, race):
    r"""Effective radii R_x (rolling direction) and R_y (across it) of a ball in a groove.

    .. math:: R_x = \frac{D}{2}\left(1 \mp \gamma\right),\quad \gamma = \frac{D\cos\alpha}{d_m},
              \qquad R_y = \frac{fD}{2f-1}

    (− for the screw, the convex inner race; + for the nut, the concave outer race.)

    Parameters
    ----------
    ball_diameter, pitch_diameter : float or array_like
        Ball diameter D and ball-centre (pitch) diameter d_m, [m].
    contact_angle : float or array_like
        α, [rad]; validity (0, π/2).
    conformity : float or array_like
        Groove radius over ball diameter f, [-]; > 0.5 (0.52–0.56 in ball screws).
    race : {"screw", "nut"}
        Which groove the ball touches.

    Returns
    -------
    tuple
        (R_x, R_y), [m].

    Notes
    -----
    The helix (λ of a few degrees) is ignored in the curvatures: it changes R_x by
    O(λ²). R_y/R_x lies between 10 and 60 for usual conformities, inside the range of
    :func:`feedtherm.physics.screw_nut_rolling.ellipticity_Hamrock_Brewe`.

    References
    ----------
    .. [1] Hamrock & Dowson, *Ball Bearing Lubrication* (1981), ch. 2–3 (inner and outer
       race of a ball bearing).

    Examples
    --------
    D = 12.7 mm, d_m = 65 mm, f = 0.52, radial contact (α → 0 gives γ = 12.7/65 =
    0.195385): inner R_x = 6.35·(1 − 0.195385) = 5.1093 mm, outer 6.35·1.195385 = 7.5907 mm,
    R_y = 0.52·12.7/0.04 = 165.1 mm.

    >>> Rx, Ry = radii_effective_ball_groove(0.0127, 0.065, 1e-9, 0.52, "screw")
    >>> round(Rx * 1e3, 4), round(Ry * 1e3, 1)
    (5.1093, 165.1)
    >>> round(radii_effective_ball_groove(0.0127, 0.065, 1e-9, 0.52, "nut")[0] * 1e3, 4)
    7.5907
    """
    D, d_m = _positive("ball_diameter", ball_diameter), _positive("pitch_diameter", pitch_diameter)
    gamma = D * np.cos(_contact_angle(contact_angle)) / d_m
    if np.any(gamma >= 1.0):
        raise ValueError("ball_diameter*cos(contact_angle) must be smaller than pitch_diameter")
    sign = {"screw": -1.0, "nut": 1.0}.get(race)
    if sign is None:
        raise ValueError(f"race must be 'screw' or 'nut' (got {race!r})")
    f = _conformity(conformity)
    return _out(D / 2.0 * (1.0 + sign * gamma)), _out(f * D / (2.0 * f - 1.0))


def elliptic_integral_Hamrock_Brewe(Ry, Rx):
    r"""Complete elliptic integral of the second kind of a Hertz contact (Hamrock–Brewe fit).

    .. math:: \bar{\mathcal{E}} \approx 1.0003 + 0.5968\,\frac{R_x}{R_y}

    Parameters
    ----------
    Ry, Rx : float or array_like
        Effective radii across and along the rolling direction, [m].

    Returns
    -------
    float or ndarray
        Ɛ, [-].

    Notes
    -----
    Companion of :func:`feedtherm.physics.screw_nut_rolling.ellipticity_Hamrock_Brewe`,
    fitted over the same 1 ≤ R_y/R_x ≤ 100 (warns outside); the exact value of a circle is
    π/2 = 1.5708 (the fit gives 1.5971).

    References
    ----------
    .. [1] Hamrock & Brewe, *J. Lubr. Technol.* 105 (1983) 171–177.

    Examples
    --------
    R_y/R_x = 10: 1.0003 + 0.5968/10 = 1.05998.

    >>> round(elliptic_integral_Hamrock_Brewe(0.05, 0.005), 5)
    1.05998
    """
    ratio = _positive("Ry", Ry) / _positive("Rx", Rx)
    check_range("elliptic_integral_Hamrock_Brewe", "Ry/Rx", ratio, 1.0, 100.0)
    return _out(1.0003 + 0.5968 / ratio)


def semi_minor_axis_coefficient(k, elliptic_integral):
    r"""Coefficient γ of the Hertz semi-axis in the rolling direction of an elliptical contact.

    .. math:: \gamma = \left(\frac{2\mathcal{E}}{\pi k}\right)^{1/3}, \qquad
              b = \gamma\left[\frac{3Q}{2E^*\sum\rho}\right]^{1/3}, \quad a = k\,b

    Parameters
    ----------
    k : float or array_like
        Ellipticity a/b, [-]; ≥ 1.
    elliptic_integral : float or array_like
        Complete elliptic integral of the second kind Ɛ (:func:`elliptic_integral_Hamrock_Brewe`),
        [-].

    Returns
    -------
    float or ndarray
        γ (Harris's b*), [-]; the ``gamma`` of
        :func:`feedtherm.physics.screw_nut_rolling.semi_minor_axis_Hertz`.

    Notes
    -----
    Hertz's semi-axes b = (6ƐQR/(πkE′))^{1/3}, a = kb with 1/R = Σρ and E′ = 2E*
    (Hamrock & Brewe) written in the form of the paper's Eq. 8. A circle (k = 1, Ɛ = π/2)
    gives γ = 1.

    References
    ----------
    .. [1] Hamrock & Brewe, *J. Lubr. Technol.* 105 (1983) 171–177; Harris & Kotzalas,
       *Rolling Bearing Analysis* 5th ed. (a*, b*).

    Examples
    --------
    Circle: (2·(π/2)/π)^{1/3} = 1. R_y/R_x = 10 (k = 4.4717605, Ɛ = 1.05998):
    (2.11996/14.048450)^{1/3} = 0.150903^{1/3} = 0.532394.

    >>> import math
    >>> semi_minor_axis_coefficient(1.0, math.pi / 2)
    1.0
    >>> round(semi_minor_axis_coefficient(4.4717605, 1.05998), 6)
    0.532394
    """
    k = _positive("k", k)
    return _out(np.cbrt(2.0 * _positive("elliptic_integral", elliptic_integral) / (math.pi * k)))


def radius_contact_surface_ball_groove(ball_diameter, conformity):
    r"""Transverse radius of the deformed contact surface between a ball and its groove.

    .. math:: R_c = \frac{2fD}{2f+1}

    Parameters
    ----------
    ball_diameter : float or array_like
        D, [m].
    conformity : float or array_like
        Groove radius over ball diameter f, [-]; > 0.5.

    Returns
    -------
    float or ndarray
        R_c, [m]: the radius R of Heathcote's slip lever z = x²/(2R) in
        :func:`feedtherm.physics.screw_nut_rolling.torque_differential_sliding_contact`.

    Notes
    -----
    Two bodies of the same elastic constants deform equally, so the pressed surface takes
    the mean of the ball's and the groove's curvatures: 1/R_c = (2/D + 1/(fD))/2, i.e.
    R_c = 2r·D/(2r + D) with the groove radius r = fD.

    References
    ----------
    .. [1] Harris & Kotzalas, *Rolling Bearing Analysis* 5th ed. (radius of the deformed
       surface); Johnson, *Contact Mechanics* (1985) §8 (Heathcote slip).

    Examples
    --------
    D = 10 mm, f = 0.52: 2·0.52·10/2.04 = 5.0980 mm, just above the ball's 5 mm.

    >>> round(radius_contact_surface_ball_groove(0.010, 0.52) * 1e3, 4)
    5.098
    """
    D, f = _positive("ball_diameter", ball_diameter), _conformity(conformity)
    return _out(2.0 * f * D / (2.0 * f + 1.0))


def lever_arm_rolling_ball_screw(pitch_diameter, ball_diameter, contact_angle, helix_angle):
    r"""Lever that turns a rolling resistance at a ball contact into screw torque.

    .. math:: r_e = \frac{u}{|\omega|} = \frac{d_m\,(1-\gamma^2)}{4\cos\lambda},
              \qquad \gamma = \frac{D\cos\alpha}{d_m}

    Parameters
    ----------
    pitch_diameter, ball_diameter : float or array_like
        Ball-centre diameter d_m and ball diameter D, [m].
    contact_angle : float or array_like
        α, [rad]; validity (0, π/2).
    helix_angle : float or array_like
        λ at the pitch diameter, [rad].

    Returns
    -------
    float or ndarray
        r_e, [m]. The rolling (entraining) speed of each contact is u = r_e|ω| at the
        relative angular speed ω of screw and nut, and the ball turns about its own axis
        at Ω = 2u/D = (2r_e/D)|ω|.

    Notes
    -----
    With the nut as the outer race held still, the balls orbit at ω(1 − γ)/2 and both
    contacts roll at u = ω d_m(1 − γ²)/4 relative to their groove (ball-bearing
    kinematics, no gross sliding); along the helical groove the path is longer by 1/cos λ.
    A resistance F at a contact dissipates F·u, which the screw supplies as M·ω, so
    M = F·r_e: the lever is about d_m/4, not the pitch radius.

    References
    ----------
    .. [1] Harris & Kotzalas, *Rolling Bearing Analysis* 5th ed. (ball and cage speeds);
       docs/paper-audit.md §1 (Eqs. 5, 8, 11).

    Examples
    --------
    Bearing check, d_m = 65 mm, D = 12.7 mm, α → 0, λ = 0: γ = 0.195385, 1 − γ² = 0.961825,
    r_e = 0.065·0.961825/4 = 0.0156297 m.

    >>> round(lever_arm_rolling_ball_screw(0.065, 0.0127, 1e-9, 0.0), 7)
    0.0156297
    """
    d_m, D = _positive("pitch_diameter", pitch_diameter), _positive("ball_diameter", ball_diameter)
    gamma = D * np.cos(_contact_angle(contact_angle)) / d_m
    return _out(d_m * (1.0 - gamma**2) / (4.0 * np.cos(np.asarray(helix_angle, dtype=float))))
