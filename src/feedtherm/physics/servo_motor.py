r"""Losses of a permanent-magnet servo motor from its data sheet: copper loss and no-load loss.

A servo motor's heat is the sum of two losses that scale differently:

- the **copper loss** of the current that makes the torque, :math:`\tfrac{3}{2} I^2 R_{tt}`
  with :math:`I = |M|/k_T`: it grows with the square of the torque and does not depend on speed;
- the **no-load loss** of a motor that turns: bearing and seal friction and the iron loss that
  the magnets' rotating field causes in the stator (its iron is magnetised whether or not the
  winding carries current). A data sheet states it as a drag torque, a constant friction torque
  plus a viscous damping, :math:`P_0 = (T_F + D\omega)\,\omega`: a part that grows with the
  speed and a part that grows with its square, as hysteresis and eddy-current losses do at
  constant flux density.

The efficiency model of :mod:`feedtherm.physics.motors` instead makes the loss proportional
to the shaft power M·ω; it is kept, and a description chooses per motor.

A braking motor (the nut motor that the preloaded thread drags along in the dual drive) loses
the same two: its current flows in the same windings and its rotor turns in the same
bearings and field. The mechanical power it takes in is not heat in the motor: the servo
amplifier returns it to its DC bus, where a regenerative supply feeds it back to the mains, a
shared bus passes it to the other motor's amplifier, or a brake resistor (in the cabinet, not
in the feed system) burns it.

References
----------
.. [1] Kollmorgen, *Motor Data Legend* (2013): K_T is the torque per A r.m.s. of sinusoidal
   current, "M = I × K_T (up to I = 2 × I0)"; R20 is the winding resistance measured phase to
   phase at 20 °C; M_R the static friction torque.
.. [2] WITTENSTEIN alpha, premo operating manual, rev. 02 (4022-D045530), Tbl-16 "Motor
   specifications, premo 320 V": K_t, K_e, connection resistance R_tt, continuous stall
   torque T_0 and current I_0 per stator.
.. [3] AMETEK Pittman, motor data sheet 14204S004: friction torque T_F = 1.1e-2 N·m, viscous
   damping D = 1.2e-5 N·m·s.
.. [4] Modelica Standard Library, Modelica.Electrical.Machines.Losses (Core: iron loss
   separated into a hysteresis share ∝ f and an eddy-current share ∝ f² at constant flux;
   Friction).
.. [5] G. Bertotti, "General properties of power losses in soft ferromagnetic materials",
   IEEE Trans. Magn. 24(1), 621–630 (1988): hysteresis loss ∝ f, classical eddy-current
   loss ∝ f² at a given peak flux density.
"""

from __future__ import annotations

import numpy as np

from feedtherm.physics._arrays import finite as _finite
from feedtherm.physics._arrays import any_true as _any
from feedtherm.physics._arrays import scalar_or_array as _out
from feedtherm.physics.mechanics import angular_speed
from feedtherm.physics.validity import check_range

#: Torque is proportional to current up to twice the standstill current (Kollmorgen [1]);
#: the rated form's |M|/M_rated is checked against it (rated and standstill torque are close).
TORQUE_RATIO_LINEAR_RANGE = (0.0, 2.0)


def heat_motor_copper(torque, torque_constant, terminal_resistance):
    r"""Copper loss of a three-phase servo motor from its torque constant and resistance.

    .. math:: P_{cu} = 3 I^2 R_{ph} = \tfrac{3}{2} I^2 R_{tt},
              \qquad I = \frac{|M|}{k_T}

    Parameters
    ----------
    torque : float or array_like
        Shaft torque M, [N·m], either sign (driving or braking).
    torque_constant : float or array_like
        k_T, torque per A r.m.s. of line current, [N·m/A] (the data sheet's K_T,rms).
    terminal_resistance : float or array_like
        R_tt, winding resistance between two motor terminals ("phase to phase"), [Ω], at the
        winding's running temperature.

    Returns
    -------
    float or ndarray
        Copper loss, [W].

    Notes
    -----
    Between two terminals of a star winding lie two phase resistances, so
    3 I²R_ph = 1.5 I²R_tt; a delta winding gives the same 1.5 I²R_tt with I the line current
    (R_tt = 2R_Δ/3 and a phase current I/√3). The current is the data sheet's M = I·k_T [1]_,
    valid up to twice the standstill current; beyond it the iron saturates and the loss is
    larger. A sinusoidal motor's k_T is √3 times its line-to-line r.m.s. voltage constant in
    V·s/rad, which checks that a data sheet's k_T is per A r.m.s. (premo stator 2C [2]_:
    √3·23.7 V/krpm = √3·0.22632 = 0.392 N·m/A against K_t = 0.39).

    Data sheets give R at 20 °C; a copper winding's resistance grows as (235 + θ) (the
    resistance method of IEC 60034-1), by 31 % at 100 °C: give the resistance at the winding's
    running temperature. The loss depends on |M| only: a braking motor heats by the same
    copper loss, and the power it takes in goes back to the amplifier's DC bus (module notes).

    References
    ----------
    .. [1] Kollmorgen, *Motor Data Legend* (2013): K_T, R20.
    .. [2] WITTENSTEIN alpha, premo operating manual, rev. 02, Tbl-16 (premo 320 V).

    Examples
    --------
    premo 320 V, stator 2C [2]_: K_t = 0.39 N·m/A, R_tt = 5.70 Ω, continuous stall torque
    T_0 = 1.17 N·m: I = 1.17/0.39 = 3.0 A, P = 1.5·3.0²·5.70 = 1.5·9·5.70 = 76.95 W.

    >>> round(heat_motor_copper(1.17, 0.39, 5.70), 2)
    76.95
    """
    torque = _finite(torque, "torque", "[N·m]")
    k_t = _positive(torque_constant, "torque_constant", "[N·m/A]")
    resistance = _positive(terminal_resistance, "terminal_resistance", "[Ω]")
    current = np.abs(torque) / k_t
    return _out(1.5 * current**2 * resistance)


def heat_motor_copper_rated(torque, rated_torque, rated_copper_loss):
    r"""Copper loss of a servo motor scaled from its copper loss at rated torque.

    .. math:: P_{cu} = P_{cu,N} \left(\frac{M}{M_N}\right)^2

    Parameters
    ----------
    torque : float or array_like
        Shaft torque M, [N·m], either sign (driving or braking).
    rated_torque : float or array_like
        M_N, the torque at which the copper loss is known, [N·m], > 0.
    rated_copper_loss : float or array_like
        P_cu,N, the copper loss at M_N, [W], ≥ 0.

    Returns
    -------
    float or ndarray
        Copper loss, [W].

    Notes
    -----
    The same law as :func:`heat_motor_copper`, with P_cu,N = 1.5(M_N/k_T)²R_tt: use it where
    a maker or a test states the loss instead of k_T and R (the I²R load loss of a loss
    separation, or a motor constant K_M = M/√P_cu, which gives P_cu,N/M_N² = 1/K_M²). Torque
    is proportional to current up to twice the standstill current [1]_; a warning is emitted
    for |M|/M_N outside [0, 2]. The loss depends on |M| only: a braking motor heats by the same
    copper loss (module notes).

    References
    ----------
    .. [1] Kollmorgen, *Motor Data Legend* (2013): "M = I × K_T (up to I = 2 × I0)".

    Examples
    --------
    The premo stator 2C of :func:`heat_motor_copper` loses 76.95 W at 1.17 N·m; at half that
    torque, 0.585 N·m: 76.95·(0.5)² = 19.2375 W.

    >>> round(heat_motor_copper_rated(0.585, 1.17, 76.95), 4)
    19.2375
    """
    torque = _finite(torque, "torque", "[N·m]")
    m_n = _positive(rated_torque, "rated_torque", "[N·m]")
    p_n = _nonnegative(rated_copper_loss, "rated_copper_loss", "[W]")
    ratio = np.abs(torque) / m_n
    check_range("heat_motor_copper_rated", "|M|/M_rated", ratio, *TORQUE_RATIO_LINEAR_RANGE)
    return _out(p_n * ratio**2)


def heat_motor_no_load(n_rpm, friction_torque, viscous_damping):
    r"""No-load loss of a servo motor (friction and iron loss) from its drag torque.

    .. math:: P_0 = (T_F + D|\omega|)\,|\omega|, \qquad \omega = \frac{2\pi n}{60}

    Parameters
    ----------
    n_rpm : float or array_like
        The motor's speed, [rpm]; magnitude is used.
    friction_torque : float or array_like
        T_F, the speed-independent drag torque, [N·m] (a data sheet's "friction torque" or
        "static friction torque").
    viscous_damping : float or array_like
        D, the drag torque per angular speed, [N·m·s/rad] (a data sheet's "viscous damping";
        1 N·m/krpm = 9.5493e-3 N·m·s/rad).

    Returns
    -------
    float or ndarray
        No-load loss, [W].

    Notes
    -----
    A constant drag torque costs power ∝ n, a viscous one ∝ n²: the two terms are the
    k_h n + k_e n² of the iron loss at the constant flux of the magnets, hysteresis ∝ f and
    classical eddy current ∝ f² [2]_ [3]_, plus the Coulomb and viscous parts of the bearing and
    seal friction. From a no-load loss P_0,ref measured at ω_ref with a hysteresis share x (the
    Modelica core-loss model's ratioHysteresis [3]_, whose loss
    P_ref(x ω_ref/ω + 1 − x)(V/V_ref)² becomes P_ref[x ω/ω_ref + (1 − x)(ω/ω_ref)²] with
    the back-EMF V ∝ ω): T_F = x P_0,ref/ω_ref and D = (1 − x)P_0,ref/ω_ref².

    Valid below the base speed (no field weakening, which lowers the flux and the iron loss).
    The excess-loss term ∝ f^1.5 [2]_ is folded into the two; the windage of the smooth rotor of
    a totally enclosed servo, which has no fan, is left out. The loss is the same whether the
    motor drives or brakes (module notes).

    References
    ----------
    .. [1] AMETEK Pittman, motor data sheet 14204S004: T_F and D.
    .. [2] G. Bertotti, IEEE Trans. Magn. 24(1), 621–630 (1988).
    .. [3] Modelica Standard Library, Modelica.Electrical.Machines.Losses.InductionMachines.Core.

    Examples
    --------
    Pittman 14204S004 [1]_: T_F = 1.1e-2 N·m, D = 1.2e-5 N·m·s, at 3000 rpm:
    ω = 314.1593 rad/s, T_F ω = 3.45575 W, D ω² = 1.2e-5·98696.04 = 1.18435 W, P_0 = 4.6401 W.

    >>> round(heat_motor_no_load(3000.0, 1.1e-2, 1.2e-5), 4)
    4.6401
    """
    t_f = _nonnegative(friction_torque, "friction_torque", "[N·m]")
    damping = _nonnegative(viscous_damping, "viscous_damping", "[N·m·s/rad]")
    omega = np.abs(np.asarray(angular_speed(_finite(n_rpm, "n_rpm", "[rpm]")), dtype=float))
    return _out((t_f + damping * omega) * omega)


#: Inferred zero-resistance temperature of annealed copper, [°C] (IEC 60034-1, §8.6.2.3.1).
COPPER_INFERRED_ZERO_C = 235.0


def resistance_winding_copper(resistance_ref, temperature_ref, temperature):
    r"""Resistance of a copper winding at another temperature.

    .. math:: R(T) = R_{ref}\,\frac{235 + \vartheta}{235 + \vartheta_{ref}},
              \qquad \vartheta = T - 273.15\ \mathrm{K}

    Parameters
    ----------
    resistance_ref : float or array_like
        The resistance at ``temperature_ref``, [Ω] (a data sheet's R_tt, stated cold at
        20 °C or 25 °C, or hot).
    temperature_ref, temperature : float or array_like
        Winding temperatures, [K].

    Returns
    -------
    float or ndarray
        R at ``temperature``, [Ω].

    Notes
    -----
    The linear law of annealed copper, whose resistance extrapolates to zero at −235 °C
    (α = 1/(235 + 20) = 3.92e-3 1/K at 20 °C), as IEC 60034-1 prescribes for the
    resistance method of measuring a winding's temperature rise [1]_. Valid from −50 to
    250 °C, the range of winding insulation classes (class H: 180 °C hot spot).

    References
    ----------
    .. [1] IEC 60034-1:2017, Rotating electrical machines — Rating and performance, §8.6.2.3.1.

    Examples
    --------
    A winding of 5.70 Ω at 20 °C, at 60 °C: 5.70·(235 + 60)/(235 + 20) = 5.70·295/255 = 6.5941 Ω.

    >>> round(resistance_winding_copper(5.70, 293.15, 333.15), 4)
    6.5941
    """
    r_ref = _positive(resistance_ref, "resistance_ref", "[Ω]")
    theta_ref = _finite(temperature_ref, "temperature_ref", "[K]") - 273.15
    theta = _finite(temperature, "temperature", "[K]") - 273.15
    for label, value in (("temperature_ref", theta_ref), ("temperature", theta)):
        if _any(value <= -COPPER_INFERRED_ZERO_C):
            raise ValueError(f"{label} must be above -235 degC, the copper's inferred zero of resistance")
        check_range("resistance_winding_copper", label + " [degC]", value, -50.0, 250.0)
    return _out(r_ref * (COPPER_INFERRED_ZERO_C + theta) / (COPPER_INFERRED_ZERO_C + theta_ref))


def _positive(value, label, unit):
    arr = _finite(value, label, unit)
    if _any(arr <= 0.0):
        raise ValueError(f"{label} must be positive {unit}, got {value!r}")
    return arr


def _nonnegative(value, label, unit):
    arr = _finite(value, label, unit)
    if _any(arr < 0.0):
        raise ValueError(f"{label} must not be negative {unit}, got {value!r}")
    return arr
