r"""Servo-motor output power and heat loss (paper Eq. 14, corrected and as printed).

A motor delivering the shaft power :math:`P_{out} = M\omega` at efficiency η draws
:math:`P_{in} = P_{out}/\eta`, so its heat loss is
:math:`P_{in} - P_{out} = P_{out}(1/\eta - 1)`.  The paper's Eq. 14 writes
:math:`P_{out}(1 - \delta)`, which is the loss for a given *input* power; it
underestimates the loss for a given output by the factor η.  Reproducing the paper's
Table 1 needs the printed form, kept as :func:`heat_motor_paper`.

A constant η makes the loss grow with the shaft power M·ω; a servo motor's copper loss grows
with M² and its no-load loss with the speed: :mod:`feedtherm.physics.servo_motor` models
those from data-sheet values.

References
----------
.. [1] Paper, §3.1, Eq. 14, and Table 1.
.. [2] docs/paper-audit.md §1 row 14 and §4 (M_m = 0.30 N·m, δ = 0.85 reproduce 1.87 / 1.70 W).
"""

from __future__ import annotations

import numpy as np

from feedtherm.physics._arrays import finite as _finite
from feedtherm.physics._arrays import scalar_or_array as _out
from feedtherm.physics.mechanics import angular_speed

#: The paper's constant in Eq. 14: M [N·mm] · n [rpm] / 9550 = P [W].
#: (Exact: 60/(2π)·1000 = 9549.3; 9550 is the printed, rounded value.)
PAPER_POWER_CONSTANT = 9550.0


def power_motor_output(torque, n_rpm):
    r"""Mechanical output power of a motor shaft.

    .. math:: P_{out} = |M| \, \frac{2\pi |n|}{60}

    Parameters
    ----------
    torque : float or array_like
        Shaft output torque, [N·m]. Magnitude is used.
    n_rpm : float or array_like
        Motor speed, [rpm]. Magnitude is used.

    Returns
    -------
    float or ndarray
        Output power, [W], never negative.

    References
    ----------
    .. [1] Paper, Eq. 14 (the factor M n / 9550).

    Examples
    --------
    0.30 N·m at 396 rpm: 0.30·41.4690 = 12.441 W.

    >>> round(power_motor_output(0.30, 396.0), 3)
    12.441
    """
    torque = _finite(torque, "torque", "[N·m]")
    power = np.abs(torque) * np.abs(np.asarray(angular_speed(n_rpm), dtype=float))
    return _out(power)


def heat_motor(torque, n_rpm, efficiency):
    r"""Heat loss of a motor delivering a given output torque (Eq. 14 corrected).

    .. math:: H_m = P_{out}\left(\frac{1}{\eta} - 1\right),
              \qquad P_{out} = |M| \frac{2\pi |n|}{60}

    Parameters
    ----------
    torque : float or array_like
        Shaft output torque, [N·m]. Magnitude is used.
    n_rpm : float or array_like
        The motor's own speed, [rpm] (screw motor at n_s, nut motor at n_n).
    efficiency : float or array_like
        Motor efficiency η, [-], in (0, 1].

    Returns
    -------
    float or ndarray
        Heat loss, [W].

    Notes
    -----
    Motoring operation; magnitudes of torque and speed are used.  For the same η the
    loss is 1/η times the paper's printed form :func:`heat_motor_paper`.  The paper
    never defines M_m; state it explicitly (docs/paper-audit.md §1 row 14).

    References
    ----------
    .. [1] Paper, Eq. 14 (corrected: P_out(1/η − 1), not P_out(1 − η)).
    .. [2] docs/paper-audit.md §1 row 14.

    Examples
    --------
    docs/paper-audit.md §1, Eq. 14: 0.30 N·m at 396 rpm, η = 0.85:
    12.4407·(1/0.85 − 1) = 12.4407·0.176471 = 2.1954 W (the printed form gives 1.866 W).

    >>> round(heat_motor(0.30, 396.0, 0.85), 4)
    2.1954
    """
    eta = _efficiency(efficiency)
    return _out(power_motor_output(torque, n_rpm) * (1.0 / eta - 1.0))


def heat_motor_braking(torque, n_rpm, efficiency):
    r"""Heat loss of a motor that is braking: the shaft drives it (regeneration).

    .. math:: H_m = P_{in}\,(1 - \eta), \qquad P_{in} = |M| \frac{2\pi |n|}{60}

    Parameters
    ----------
    torque : float or array_like
        Braking torque on the shaft, [N·m]. Magnitude is used.
    n_rpm : float or array_like
        The motor's own speed, [rpm].
    efficiency : float or array_like
        Conversion efficiency η, [-], in (0, 1], taken equal in both directions.

    Returns
    -------
    float or ndarray
        Heat loss, [W].

    Notes
    -----
    In a dual drive with a friction-locked thread, the screw drags the nut: the nut motor
    then holds back a torque and converts the mechanical input power; what it does not
    return to the drive is lost as heat.  The same η in motoring and generating is an
    assumption (real drives differ by a few per cent).

    References
    ----------
    .. [1] Fitzgerald & Kingsley, *Electric Machinery*, 6th ed. (2003), §1.7 (energy
       balance of a machine in generator operation).

    Examples
    --------
    A nut motor braked by 1.5 N·m at 360 rpm, η = 0.85: P_in = 1.5·37.6991 = 56.549 W,
    loss = 56.549·0.15 = 8.4823 W.

    >>> round(heat_motor_braking(1.5, 360.0, 0.85), 4)
    8.4823
    """
    eta = _efficiency(efficiency)
    return _out(power_motor_output(torque, n_rpm) * (1.0 - eta))


def heat_motor_paper(torque, n_rpm, efficiency):
    r"""Motor heat as printed in the paper (Eq. 14), kept to reproduce Table 1.

    .. math:: H_m = \frac{M_m n_m}{9550}(1 - \delta), \qquad M_m \text{ in N·mm}

    Parameters
    ----------
    torque : float or array_like
        Motor torque M_m, [N·m] (converted to N·mm internally).
    n_rpm : float or array_like
        Motor speed n_m, [rpm]. Magnitude is used.
    efficiency : float or array_like
        Mechanical efficiency δ, [-], in (0, 1].

    Returns
    -------
    float or ndarray
        Heat, [W].

    Notes
    -----
    **Paper-reproduction variant; physically the loss of a given output is
    P_out(1/η − 1), see** :func:`heat_motor`.  With M_m = 0.30 N·m and δ = 0.85 it
    reproduces Table 1: 1.87 W at 396 rpm and 1.70 W at 360 rpm (docs/paper-audit.md §4). The
    printed constant 9550 is used as printed (exact 9549.3; difference 0.007 %).

    References
    ----------
    .. [1] Paper, Eq. 14 and Table 1.
    .. [2] docs/paper-audit.md §1 row 14 and §4.

    Examples
    --------
    Paper Table 1: 1.87 W (screw motor, 396 rpm) and 1.70 W (nut motor, 360 rpm), reproduced
    with M_m = 0.30 N·m, δ = 0.85 (docs/paper-audit.md §1, Eq. 14): 300·396/9550·0.15 = 1.866 W,
    300·360/9550·0.15 = 1.696 W.

    >>> round(heat_motor_paper(0.30, 396.0, 0.85), 2), round(heat_motor_paper(0.30, 360.0, 0.85), 2)
    (1.87, 1.7)
    """
    eta = _efficiency(efficiency)
    torque_Nmm = np.abs(_finite(torque, "torque", "[N·m]")) * 1e3
    n = np.abs(np.asarray(n_rpm, dtype=float))
    return _out(torque_Nmm * n / PAPER_POWER_CONSTANT * (1.0 - eta))


def _efficiency(efficiency):
    eta = np.asarray(efficiency, dtype=float)
    if np.any(~np.isfinite(eta)) or np.any(eta <= 0) or np.any(eta > 1):
        raise ValueError(f"efficiency must lie in (0, 1] [-], got {efficiency!r}")
    return eta
