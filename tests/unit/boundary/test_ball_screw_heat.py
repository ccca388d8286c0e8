"""The ball_screw heat source: its torque and heat by hand, its place in the torque balance,
its range warnings, and a ball-screw variant of the bundled example against two independent
estimates of a ball nut's drag.

The expected numbers are hand calculations written out below (calculator arithmetic, 8+
significant digits) or come from the example's own catalogue figure; none is the code's output.
"""

from __future__ import annotations

import math

import pytest

from feedtherm.boundary import boundary_conditions, operating_point
from feedtherm.boundary.heat import source_heats
from feedtherm.physics import bearings
from feedtherm.system.sources import BallScrewSource
from feedtherm.system.variants import with_values

HAND = 1e-6

# A ball nut for the hand calculation: round sizes, no preload, a 1000 N cutting force.
HAND_NUT = {
    "model": "ball_screw", "into": {"nut": 0.5, "screw": 0.5},
    "pitch_diameter": "25 mm", "ball_diameter": "5 mm", "contact_angle": "45 deg",
    "screw_conformity": 0.55, "nut_conformity": 0.55, "loaded_balls": 20,
    "external_axial_load": "1000 N", "slip_friction_coefficient": 0.1, "hysteresis_loss_fraction": 0.01,
    "lubricant_dynamic_viscosity": "0.087 Pa*s", "pressure_viscosity_coefficient": "2e-8 1/Pa",
    "youngs_modulus": "210 GPa", "poisson_ratio": 0.3,
}

# The example's Ø25x10 nut as a ball_screw source.  Stated data, each an assumption:
# - d_m = 26 mm and the preload 1280 N (8 % of Ca = 16 kN): the example's own provenance of
#   sources.ball_nut, so the two sources describe the same nut;
# - D = 4.7625 mm (3/16 in) balls, 45 deg contact, conformity 0.55 on both grooves (gothic arch);
# - 40 loaded balls per nut half: 2.5 turns of pi*26/4.7625 = 17.2 balls, less those in the return;
# - slip mu 0.1 (boundary-lubricated steel), hysteresis loss 1 %;
# - eta_0 = 0.087 Pa s: the example's ISO VG 100 grease base oil at 40 degC, 100 mm^2/s * 870 kg/m^3;
#   alpha_p = 2e-8 1/Pa, a mineral oil; E = 210 GPa, nu = 0.3: the example's bearing steel.
EXAMPLE_NUT = {
    **HAND_NUT,
    "pitch_diameter": "26 mm", "ball_diameter": "4.7625 mm", "loaded_balls": 40,
    "preload": "1280 N", "external_axial_load": "0 N",
}


def with_ball_nut(loaded, **fields):
    """The example with its catalogue-torque ball nut swapped for a ball_screw source."""
    source = BallScrewSource.model_validate(fields)
    return with_values(loaded, {"sources": {**loaded.system.sources, "ball_nut": source}}).system


def heats_at(system, condition):
    return source_heats(system, operating_point(system, system.conditions[condition]))


def test_torque_and_heat_by_hand_at_1000_rpm(ballscrew):
    # Example condition v10: screw 1000 rpm, nut still, lead 10 mm: omega = 2 pi 1000/60 = 104.71976 rad/s.
    # Axial load: the guideways' friction 0.004 * 45 kg * 9.80665 + 4 * 5 N = 1.7651970 + 20 = 21.765197 N,
    #   plus the 1000 N cutting force: F = 1021.765197 N, all on one set (no preload).
    # Helix: tan lambda = 10/(pi 25) = 0.12732395, lambda = 0.12664254 rad, cos lambda = 0.99199155.
    # Ball load: Q = F/(z sin 45 cos lambda) = 1021.765197/(20 * 0.70710678 * 0.99199155)
    #   = 1021.765197/14.028879 = 72.832990 N.
    # Kinematics: gamma = D cos 45/d_m = 5 * 0.70710678/25 = 0.14142136, 1 - gamma^2 = 0.98;
    #   lever r_e = d_m (1 - gamma^2)/(4 cos lambda) = 0.025 * 0.98/3.9679662 = 6.1744478e-3 m;
    #   rolling speed u = r_e omega = 0.64658666 m/s; ball spin Omega/omega = 2 r_e/D = 2.4697791.
    # Moduli: E* = 210e9/(2 * 0.91) = 1.1538462e11 Pa, E' = 2 E* = 2.3076923e11 Pa.
    # Both grooves: R_y = f D/(2f - 1) = 0.55 * 5/0.1 = 27.5 mm; contact surface
    #   R_c = 2 f D/(2f + 1) = 5.5/2.1 = 2.6190476 mm; Heathcote's lines +-2cos 80 = +-0.34729636,
    #   bracket 4/15 - 4(c^3/3 - c^5/5) = 0.21485653.
    # Screw contact: R_x = 2.5 (1 - 0.14142136) = 2.1464466 mm, R_y/R_x = 12.811872;
    #   k = 1.0339 * 12.811872^0.636 = 5.2350418, E_bar = 1.0003 + 0.5968/12.811872 = 1.0468818;
    #   gamma_b = (2 * 1.0468818/(pi * 5.2350418))^(1/3) = 0.50305933;
    #   sum rho = 1/2.1464466e-3 + 1/0.0275 = 465.88627 + 36.363636 = 502.24990 1/m;
    #   b = 0.50305933 * (3 * 72.832990/(2 * 1.1538462e11 * 502.24990))^(1/3)
    #     = 0.50305933 * 1.2353325e-4 = 6.2144555e-5 m, a = k b = 3.2532934e-4 m;
    #   sliding: M_dj = 0.75 * 0.1 * 72.832990 * a^2/(2 * 2.6190476e-3) * 0.21485653 = 2.3714340e-5 N m,
    #     on the screw M_dj * 2.4697791 = 5.8569181e-5 N m;
    #   hysteresis: F_h = (3/16) * 0.01 * 72.832990 * 6.2144555e-5/2.5e-3 = 3.3946303e-3 N,
    #     * r_e = 2.0959967e-5 N m;
    #   EHL: U = 0.087 * 0.64658666/(2.3076923e11 * 2.1464466e-3) = 1.1356591e-10,
    #     G = 2e-8 * 2.3076923e11 = 4615.3846, W = 72.832990/(2.3076923e11 * 2.1464466e-3^2) = 6.8503073e-5;
    #     F_l = 2.86 * E' R_x^2 k^0.348 G^0.022 U^0.66 W^0.47
    #         = 2.86 * 1063207.6 * 1.7790339 * 1.2039614 * 2.7318930e-7 * 0.011035289 = 0.019634883 N,
    #     * r_e = 1.2123456e-4 N m.
    # Nut contact: R_x = 2.5 (1 + 0.14142136) = 2.8535534 mm, R_y/R_x = 9.6371072;
    #   k = 4.3678592, E_bar = 1.0622273, gamma_b = 0.53696130, sum rho = 386.80390 1/m;
    #   b = 0.53696130 * 1.3477010e-4 = 7.2366327e-5 m, a = 3.1608593e-4 m;
    #   sliding: M_dj = 2.2385917e-5 N m, on the screw 5.5288271e-5 N m;
    #   hysteresis: F_h = (3/16) * 0.01 * 72.832990 * 7.2366327e-5/2.5e-3 = 3.9529920e-3 N, * r_e = 2.4407543e-5 N m;
    #   EHL: U = 8.5424430e-11, W = 3.8759506e-5, E' R_x^2 = 1879100.1 N, k^0.348 = 1.6703731,
    #     U^0.66 = 2.2638319e-7, W^0.47 = 8.4437967e-3: F_l = 0.020659697 N, * r_e = 1.2756222e-4 N m.
    # Twenty balls:
    #   M_d = 20 * (5.8569181e-5 + 5.5288271e-5) = 2.2771490e-3 N m
    #   M_f = 20 * (2.0959967e-5 + 2.4407543e-5) = 9.0735020e-4 N m
    #   M_l = 20 * (1.2123456e-4 + 1.2756222e-4) = 4.9759355e-3 N m
    #   M_T = 2.2771490e-3 + 9.0735020e-4 + 4.9759355e-3 = 8.1604347e-3 N m
    #   H = M_T omega = 8.1604347e-3 * 104.71976 = 0.85455873 W
    heat = heats_at(with_ball_nut(ballscrew, **HAND_NUT), "v10")["ball_nut"]
    assert heat.details["axial_load_N"] == pytest.approx(1021.765197, rel=HAND)
    assert heat.details["differential_sliding_torque_Nm"] == pytest.approx(2.2771490e-3, rel=HAND)
    assert heat.details["hysteresis_torque_Nm"] == pytest.approx(9.0735020e-4, rel=HAND)
    assert heat.details["rolling_resistance_torque_Nm"] == pytest.approx(4.9759355e-3, rel=HAND)
    assert heat.details["friction_torque_Nm"] == pytest.approx(8.1604347e-3, rel=HAND)
    assert heat.power == pytest.approx(0.85455873, rel=HAND)
    assert heat.speed_rpm == 1000.0 and heat.into == {"nut": 0.5, "screw": 0.5}


def test_the_motor_delivers_the_ball_screw_torque_and_pushes_the_table(ballscrew):
    # As for the sliding screw: the screw motor carries both bearings, the ball nut's friction
    # and F lead/(2 pi), the ideal torque that moves the table (docs/paper-audit.md §5).
    heats = heats_at(with_ball_nut(ballscrew, **HAND_NUT), "v10")
    nut = heats["ball_nut"].details
    push = nut["axial_load_N"] * 0.010 / (2.0 * math.pi)  # 1021.765197 * 0.01/(2 pi) = 1.6261898 N m
    assert push == pytest.approx(1.6261898, rel=HAND)
    expected = (heats["front_bearing"].details["friction_torque_Nm"]
                + heats["rear_bearing"].details["friction_torque_Nm"] + nut["friction_torque_Nm"] + push)
    assert heats["servo_motor"].details["torque_Nm"] == pytest.approx(expected, rel=1e-12)


def test_preloaded_nut_shares_the_load_between_its_two_sets_as_hertz_contacts(ballscrew):
    heat = heats_at(with_ball_nut(ballscrew, **{**EXAMPLE_NUT, "external_axial_load": "1000 N"}), "v10")["ball_nut"]
    F1, F2, F = heat.details["ball_set_1_load_N"], heat.details["ball_set_2_load_N"], heat.details["axial_load_N"]
    assert F1 - F2 == pytest.approx(F, rel=1e-9)
    # Hertz: delta ~ F^(2/3) and delta_1 + delta_2 = 2 delta_p, 2 * 1280^(2/3) = 2 * 117.88 = 235.76
    assert F1 ** (2 / 3) + F2 ** (2 / 3) == pytest.approx(2.0 * 1280.0 ** (2 / 3), rel=1e-9)
    # beyond 2^1.5 * 1280 = 3620.4 N the relieved set lifts off and only one set carries the load
    lifted = heats_at(with_ball_nut(ballscrew, **{**EXAMPLE_NUT, "external_axial_load": "4000 N"}), "v10")["ball_nut"]
    assert lifted.details["ball_set_2_load_N"] == 0.0
    assert lifted.details["ball_set_1_load_N"] == pytest.approx(4021.765197, rel=HAND)


def test_standstill_makes_no_heat_and_no_motor_torque(ballscrew):
    system = with_ball_nut(ballscrew, **EXAMPLE_NUT)
    point = operating_point(system, system.conditions["v10"].model_copy(update={"screw_speed": 0.0}))
    heats = source_heats(system, point)
    assert heats["ball_nut"].power == 0.0
    assert heats["ball_nut"].details["rolling_resistance_torque_Nm"] == 0.0  # U = 0 without rolling
    assert heats["servo_motor"].details["torque_Nm"] == 0.0


def test_a_nearly_conforming_groove_is_reported_outside_the_ellipticity_fit(ballscrew):
    # f = 0.505: R_y = 0.505 * 5/0.01 = 252.5 mm, R_y/R_x = 252.5/2.1464466 = 117.6 > 100, the
    # end of Hamrock & Brewe's fit; the boundary step collects the physics function's warning.
    system = with_ball_nut(ballscrew, **{**HAND_NUT, "screw_conformity": 0.505})
    warnings = boundary_conditions(system, "v10").warnings
    assert any(w.startswith("sources: ellipticity_Hamrock_Brewe") and "Ry/Rx = 117.6" in w for w in warnings), warnings


def test_example_as_a_ball_screw_source_lies_between_two_independent_estimates(ballscrew):
    """The three rolling terms of the example's nut at 1000 rpm, against
    - above: the example's catalogue preload drag torque, 0.291 N m (THK's formula in its
      provenance), measured on whole nuts and so including what the three terms leave out
      (seals, ball recirculation, ball-ball rubbing, spin): the rolling terms must stay below;
    - below: Palmgren's load torque f1 P1 d_m of two angular-contact ball sets of the same pitch
      diameter, each carrying the preload: an empirical fit to measured ball-bearing torques,
      whose load part is made of the same hysteresis and micro-slip (plus spin).  The three terms
      must reach its order of magnitude: at least a third of it.
    """
    omega = 2.0 * math.pi * 1000.0 / 60.0  # 104.71976 rad/s
    catalogue = heats_at(ballscrew.system, "v10")["ball_nut"].power
    assert catalogue == pytest.approx(0.291 * omega, rel=1e-12)  # 30.473 W
    # C0 = 30 kN assumed for the nut (about twice the Ca = 16 kN of the provenance); f1 goes as
    # C0^-0.33, so 25-40 kN moves the bound by less than 10 %.
    f1 = bearings.f1_angular_contact_Palmgren(1280.0, 30e3)
    P1 = bearings.P1_angular_contact_Palmgren(1280.0, 0.0)  # 1.4 * 1280 = 1792 N
    palmgren = 2.0 * bearings.torque_bearing_load_Palmgren(f1, P1, 0.026) * omega
    assert palmgren == pytest.approx(2.0 * 0.001 * (1280.0 / 30e3) ** 0.33 * 1792.0 * 0.026 * omega, rel=1e-9)
    heat = heats_at(with_ball_nut(ballscrew, **EXAMPLE_NUT), "v10")["ball_nut"].power
    assert palmgren / 3.0 <= heat <= catalogue, (palmgren, heat, catalogue)
