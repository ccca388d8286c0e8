"""The paper bench's boundary conditions at conditions I and III, against hand calculations.

Each expected value is computed step by step here from the bench's declared inputs and the
textbook formulas, not from feedtherm's functions.  Air properties at the film temperature
(298.15 K: ambient 20 degC + half the declared 10 K rise) are CoolProp's, which
tests/unit/physics/test_air.py checks against Incropera Table A.4:
nu = 1.55770e-5 m^2/s, k = 0.0262469 W/(m K), Pr = 0.707300, alpha = 2.20231e-5 m^2/s.
"""

import math

import pytest

from feedtherm.boundary import boundary_conditions
from feedtherm.system.overlay import available_overlay

NU, K_AIR, PR, ALPHA, BETA = 1.55770e-5, 0.0262469, 0.707300, 2.20231e-5, 1 / 298.15
G = 9.80665


@pytest.fixture(scope="module")
def bench(paper_equations):
    """The hand calculations here follow the paper's own equations (Eq. 14 motors, Palmgren)."""
    return paper_equations.system


@pytest.fixture(scope="module")
def tables(paper_equations):
    """The paper bench's overlay: Tables 1 and 2 at condition I."""
    return available_overlay(paper_equations)


def rpm_to_rad(n):
    return n * 2 * math.pi / 60


@pytest.mark.parametrize("condition, n_screw", [("I", 396.0), ("III", 2214.0)])
def test_screw_shaft_chtc_eq27_mixed_with_natural(bench, condition, n_screw):
    d = 0.032
    # forced: Eq. 27 with Re = omega d^2 / nu
    re = rpm_to_rad(n_screw) * d**2 / NU  # I: 2726, III: 15242
    h_forced = 0.133 * re ** (2 / 3) * PR ** (1 / 3) * K_AIR / d
    # natural, horizontal cylinder, Morgan: Ra = g beta dT d^3 / (nu alpha) with dT = 10 K
    ra = G * BETA * 10.0 * d**3 / (NU * ALPHA)  # = 3.14e4 -> regime 1e4..1e7: C = 0.48, n = 1/4
    assert 1e4 < ra < 1e7
    h_natural = 0.48 * ra**0.25 * K_AIR / d
    # mixed convection, Churchill n = 3
    expected = (h_forced**3 + h_natural**3) ** (1 / 3)
    got = boundary_conditions(bench, condition).surfaces["screw_shaft"]
    assert got.convection == pytest.approx(expected, rel=2e-4)
    # radiation at eps = 0.3 between 303.15 K and 293.15 K
    ts, ta = 303.15, 293.15
    assert got.radiation == pytest.approx(0.3 * 5.670374419e-8 * (ts**2 + ta**2) * (ts + ta), rel=1e-6)


def palmgren_heat(n, f1, p1, dm_mm, f0, nu_mm2s):
    m_load = f1 * p1 * dm_mm  # N mm
    m_visc = 1e-7 * f0 * (nu_mm2s * n) ** (2 / 3) * dm_mm**3 if nu_mm2s * n >= 2000 else 160e-7 * f0 * dm_mm**3
    return (m_load + m_visc) * 1e-3 * rpm_to_rad(n)


@pytest.mark.parametrize("condition, n_screw, n_nut", [("I", 396.0, 360.0), ("III", 2214.0, 2160.0)])
def test_each_bearing_heat_at_its_own_speed(bench, condition, n_screw, n_nut):
    bc = boundary_conditions(bench, condition)
    # front: angular-contact pair, Fa 3150 N, Fr 50 N, C0 40.5 kN, dm 43.5 mm, f0 4, nu 100 mm^2/s
    f1 = 1e-3 * (3150 / 40500) ** 0.33  # P0 = max(Fa, Fr) = 3150 N
    p1 = max(1.4 * 3150 - 0.1 * 50, 50)  # 4405 N
    assert bc.heats["front_bearing"].power == pytest.approx(palmgren_heat(n_screw, f1, p1, 43.5, 4.0, 100.0), rel=1e-9)
    # rear: floating deep-groove 6205, Fa 0, Fr 50 N, C0 7.8 kN, dm 38.5 mm, f0 1.5, z = 5e-4
    f1 = 5e-4 * (50 / 7800) ** 0.55
    p1 = max(3 * 0 - 0.1 * 50, 50)  # the P1 >= Fr rule gives 50 N
    assert bc.heats["rear_bearing"].power == pytest.approx(palmgren_heat(n_screw, f1, p1, 38.5, 1.5, 100.0), rel=1e-9)
    # nut: 7010 DB pair at the NUT speed, Fa 300 N, Fr 50 N, C0 20 kN, dm 65 mm, f0 4
    f1 = 1e-3 * (300 / 20000) ** 0.33
    p1 = 1.4 * 300 - 0.1 * 50  # 415 N
    assert bc.heats["nut_bearing"].power == pytest.approx(palmgren_heat(n_nut, f1, p1, 65.0, 4.0, 100.0), rel=1e-9)


@pytest.mark.parametrize("condition, n_rel", [("I", 36.0), ("III", 54.0)])
def test_screw_nut_heat_at_relative_speed(bench, condition, n_rel):
    # axial load = guideway friction: mu W + seals = 0.005 * 35 kg * g + 4 carriages * 4 N
    force = 0.005 * 35 * G + 4 * 4.0  # 17.716 N
    d2, lead, mu, beta = 0.0295, 0.010, 0.10, math.radians(15)
    r2 = d2 / 2
    phi = math.atan(lead / (math.pi * d2))  # 6.16 deg
    rho = math.atan(mu / math.cos(beta))  # 5.91 deg
    m_load = force * r2 * (math.tan(phi + rho) - math.tan(phi))
    m_preload = 500 * r2 * (math.tan(phi + rho) - math.tan(phi - rho))  # 1.545 N m
    omega = rpm_to_rad(n_rel)
    m_grease = 1.0 * omega * r2**2 * (math.pi * d2 * 0.060) / 0.2e-3
    expected = (m_load + m_preload + m_grease) * omega  # I: 6.0 W, III: 9.1 W
    got = boundary_conditions(bench, condition).heats["screw_nut"]
    assert got.power == pytest.approx(expected, rel=1e-9)
    assert got.speed_rpm == pytest.approx(n_rel)


def test_paper_mode_at_I_reproduces_tables_1_and_2(bench, tables):
    bc = boundary_conditions(bench, "I", tables)
    table1 = {"guideways": 0.39, "screw_motor": 1.87, "nut_motor": 1.70, "front_bearing": 4.95,
              "nut_bearing": 5.31, "rear_bearing": 4.36}
    for source, value in table1.items():
        assert bc.heats[source].power == pytest.approx(value, rel=1e-12)
    table2 = {"screw_pair": 9.17, "screw_shaft": 56.3, "nut_motor": 15.52, "nut_housing": 31.26,
              "slider": 14.53, "worktable": 16.23}
    for surface, value in table2.items():
        assert bc.surfaces[surface].convection == pytest.approx(value, rel=1e-12)
        assert bc.surfaces[surface].radiation == 0.0  # radiation off in paper mode


def test_paper_mode_at_III_follows_the_written_scaling_rule(bench, tables):
    # rule: value(III) = printed value(I) * physics(III) / physics(I); uncovered values = physics(III)
    physics_i = boundary_conditions(bench, "I")
    physics_iii = boundary_conditions(bench, "III")
    paper_iii = boundary_conditions(bench, "III", tables)
    printed = {"front_bearing": 4.95, "nut_bearing": 5.31, "rear_bearing": 4.36, "screw_motor": 1.87,
               "nut_motor": 1.70, "guideways": 0.39}
    for source, value in printed.items():
        expected = value * physics_iii.heats[source].power / physics_i.heats[source].power
        assert paper_iii.heats[source].power == pytest.approx(expected, rel=1e-12)
    # e.g. the front bearing: 4.95 W * 46.83 / 5.024 = 46.1 W (the physics ratio III/I is 9.3)
    ratio = physics_iii.heats["front_bearing"].power / physics_i.heats["front_bearing"].power
    assert 8.0 < ratio < 11.0  # docs/paper-audit.md §3: x9.4 for this pair from I to III
    assert paper_iii.heats["screw_nut"].power == pytest.approx(physics_iii.heats["screw_nut"].power, rel=1e-12)
    expected_shaft = 56.3 * physics_iii.surfaces["screw_shaft"].convection / physics_i.surfaces["screw_shaft"].convection
    assert paper_iii.surfaces["screw_shaft"].convection == pytest.approx(expected_shaft, rel=1e-12)
    assert paper_iii.surfaces["base_top"].convection == pytest.approx(physics_iii.surfaces["base_top"].convection)


def test_motor_loads_follow_the_torque_balance(bench):
    # The screw motor turns the two screw bearings and drives the thread; the thread's friction
    # drags the nut, so the nut motor brakes by (thread torque - nut bearing torque).
    bc = boundary_conditions(bench, "I")
    thread = bc.heats["screw_nut"].details["friction_torque_Nm"] + 17.716 * 0.010 / (2 * math.pi)
    screw_load = bc.heats["front_bearing"].details["friction_torque_Nm"] + bc.heats["rear_bearing"].details["friction_torque_Nm"] + thread
    nut_load = bc.heats["nut_bearing"].details["friction_torque_Nm"] - thread
    assert bc.heats["screw_motor"].details["torque_Nm"] == pytest.approx(screw_load, rel=1e-4)
    assert bc.heats["nut_motor"].details["torque_Nm"] == pytest.approx(nut_load, rel=1e-4)
    # screw motor drives: loss = P (1/eta - 1); nut motor brakes: loss = |P| (1 - eta)
    assert bc.heats["screw_motor"].power == pytest.approx(screw_load * rpm_to_rad(396) * (1 / 0.85 - 1), rel=1e-4)
    assert bc.heats["nut_motor"].power == pytest.approx(-nut_load * rpm_to_rad(360) * (1 - 0.85), rel=1e-4)


def test_reversed_stroke_gives_the_same_heats(bench):
    # Both motor speeds change sign at a stroke end; every heat keeps its magnitude.
    from dataclasses import replace

    from feedtherm.boundary.heat import source_heats
    from feedtherm.boundary.operating import operating_point

    forward = operating_point(bench, bench.conditions["II"])
    backward = replace(forward, screw_rpm=-forward.screw_rpm, nut_rpm=-forward.nut_rpm)
    a, b = source_heats(bench, forward), source_heats(bench, backward)
    for name in a:
        assert b[name].power == pytest.approx(a[name].power, rel=1e-12)
