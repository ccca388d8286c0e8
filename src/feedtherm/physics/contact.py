"""Thermal contact resistance of a joint (paper §3.3, Table 3)."""

from __future__ import annotations


def conductance_contact(tcr: float, area: float) -> float:
    r"""Conductance of a joint with a thermal contact resistance per unit area.

    .. math:: G = \frac{A}{R''_c}

    Parameters
    ----------
    tcr : float
        Thermal contact resistance per unit area :math:`R''_c`, [m²·K/W].
    area : float
        Apparent (nominal) contact area, [m²].

    Returns
    -------
    float
        Conductance, [W/K].

    Notes
    -----
    Valid for a joint thin compared with the parts it joins (the temperature drop is a
    jump at the interface). The paper's Table 3 values lie between 1.5e-4 and 3.7e-3 m²·K/W.

    References
    ----------
    .. [1] Paper §3.3, Table 3.
    .. [2] Incropera et al., Fundamentals of Heat and Mass Transfer, 6th ed. (2007), §3.1.4.

    Examples
    --------
    Paper Table 3, nut–screw joint, 1.65e-4 m²·K/W over π·0.032·0.060 = 6.0319e-3 m²:
    G = 6.0319e-3/1.65e-4 = 36.56 W/K.

    >>> import math
    >>> round(conductance_contact(1.65e-4, math.pi * 0.032 * 0.060), 2)
    36.56
    """
    if tcr <= 0 or area <= 0:
        raise ValueError(f"tcr and area must be positive, got tcr={tcr!r} m^2K/W, area={area!r} m^2")
    return area / tcr


def temperature_jump(heat_flux: float, tcr: float) -> float:
    r"""Temperature drop across a contact carrying a heat flux.

    .. math:: \Delta T = q'' \, R''_c

    Parameters
    ----------
    heat_flux : float
        Heat flux through the joint, [W/m²].
    tcr : float
        Thermal contact resistance per unit area, [m²·K/W].

    Returns
    -------
    float
        Temperature difference across the joint, [K], with the sign of the flux.

    References
    ----------
    .. [1] Incropera et al., Fundamentals of Heat and Mass Transfer, 6th ed. (2007), Eq. 3.20.

    Examples
    --------
    1000 W/m² through a joint of 1.25e-3 m²·K/W: ΔT = 1000·1.25e-3 = 1.25 K.

    >>> temperature_jump(1000.0, 1.25e-3)
    1.25
    """
    if tcr <= 0:
        raise ValueError(f"tcr must be positive, got {tcr!r} m^2K/W")
    return heat_flux * tcr
