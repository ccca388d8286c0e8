"""A bearing source with friction_model = "skf": its torque and heat by hand, and its place in
the torque balance.

The hand calculation of one 7010 bearing (d = 50, D = 80 mm, single row, F_r = 25 N,
F_a = 300 N, 1080 rpm, nu = 100 mm²/s, grease, mineral oil) is written out step by step in
tests/unit/physics/test_bearings_skf.py: 52.2530 N·mm per bearing, every constant from SKF
General Catalogue 6000 (2006), Tables 2a, 3 and 5.
"""

from __future__ import annotations

import math

import pytest

from feedtherm.boundary import operating_point
from feedtherm.boundary.heat import source_heats
from feedtherm.system.sources import BearingSource

# The paper bench's nut bearing (a 7010 DB pair, 300 N preload, 50 N radial) under the SKF model.
NUT_PAIR_SKF = {
    "model": "bearing", "shaft": "nut", "bearing_type": "angular_contact", "friction_model": "skf",
    "bore_diameter": "50 mm", "outer_diameter": "80 mm", "series": "single_row", "bearings_in_set": 2,
    "static_load_rating": "20 kN", "axial_load": "300 N", "radial_load": "50 N",
    "lubricant_viscosity": "100 mm^2/s", "into": {"nut_bearing": 1.0},
}


def with_nut_bearing(loaded, fields):
    system = loaded.system
    sources = {**system.sources, "nut_bearing": BearingSource.model_validate(fields)}
    return system.model_copy(update={"sources": sources})


def heats(system, condition):
    return source_heats(system, operating_point(system, system.conditions[condition]))


def test_skf_pair_torque_and_heat_by_hand(paper):
    # Condition II: nut at 1080 rpm. Each bearing: F_r = 50/2 = 25 N, F_a = 300 N -> 52.2530 N·mm;
    # the pair 104.506 N·mm; heat 0.104506 N·m · 2π·1080/60 rad/s (113.0973) = 11.8193 W.
    heat = heats(with_nut_bearing(paper, NUT_PAIR_SKF), "II")["nut_bearing"]
    assert heat.details["friction_torque_Nm"] == pytest.approx(104.506e-3, rel=2e-5)
    assert heat.power == pytest.approx(0.104506 * 2 * math.pi * 1080 / 60, rel=2e-5)
    # The parts (per pair): M_rr = 2·65.1677 N·mm, phi_ish = 0.946976, phi_rs = 0.796026,
    # mu_sl = 0.05 (full film), M_sl = 2·3.12841 N·mm, no seal, no drag.
    assert heat.details["rolling_torque_Nm"] == pytest.approx(2 * 65.1677e-3, rel=2e-6)
    assert heat.details["phi_ish"] == pytest.approx(0.946976, abs=1e-6)
    assert heat.details["phi_rs"] == pytest.approx(0.796026, abs=1e-6)
    assert heat.details["mu_sl"] == pytest.approx(0.05, abs=1e-8)
    assert heat.details["sliding_torque_Nm"] == pytest.approx(2 * 3.12841e-3, rel=2e-6)
    assert heat.details["seal_torque_Nm"] == 0.0 and heat.details["drag_torque_Nm"] == 0.0


def test_skf_torque_loads_the_nut_motor(paper):
    # The nut motor delivers the bearing's torque: swapping Palmgren for SKF changes the nut
    # motor's torque by exactly the change of the bearing's torque (the nut turns at +1080 rpm).
    palmgren = heats(paper.system, "II")
    skf = heats(with_nut_bearing(paper, NUT_PAIR_SKF), "II")
    bearing_change = skf["nut_bearing"].details["friction_torque_Nm"] - palmgren["nut_bearing"].details["friction_torque_Nm"]
    motor_change = skf["nut_motor"].details["torque_Nm"] - palmgren["nut_motor"].details["torque_Nm"]
    assert motor_change == pytest.approx(bearing_change, rel=1e-9)


def test_oil_bath_has_no_starvation_factor_and_adds_its_drag(paper):
    # A full oil bath replenishes the tracks: phi_rs = 1; a declared drag of 5 N·mm per bearing
    # adds 10 N·mm to the pair: 2·(0.946976·65.1677 + 3.12841 + 5) = 139.6813 N·mm
    # (0.946976·65.1677 = 61.71225).
    fields = {**NUT_PAIR_SKF, "lubrication": "oil_bath", "drag_torque": "5 N*mm"}
    heat = heats(with_nut_bearing(paper, fields), "II")["nut_bearing"]
    assert heat.details["phi_rs"] == 1.0
    assert heat.details["friction_torque_Nm"] == pytest.approx(139.6813e-3, rel=2e-6)


def test_seals_add_their_table_4_moment(paper):
    # RS1 seals on a 7010 (Table 4: angular contact, 30 < D <= 120 mm: beta 2, K_S1 0.014,
    # K_S2 10) with d_s = 57.6 mm: 0.014·3317.76 + 10 = 56.44864 N·mm per bearing (two seals).
    fields = {**NUT_PAIR_SKF, "seal": "RS1", "seal_counterface_diameter": "57.6 mm"}
    heat = heats(with_nut_bearing(paper, fields), "II")["nut_bearing"]
    assert heat.details["seal_torque_Nm"] == pytest.approx(2 * 56.44864e-3, rel=1e-9)
    assert heat.details["friction_torque_Nm"] == pytest.approx(104.506e-3 + 2 * 56.44864e-3, rel=2e-5)


def test_default_model_is_palmgren_with_its_detail_keys(paper_equations):
    # A bearing that states no friction_model: Palmgren, whose detail keys are unchanged.
    heat = heats(paper_equations.system, "II")["nut_bearing"]
    assert paper_equations.system.sources["nut_bearing"].friction_model == "palmgren"
    assert {"f1", "P1_N", "load_torque_Nm", "viscous_torque_Nm"} <= set(heat.details)


def test_the_paper_bench_takes_its_bearings_by_the_skf_model(paper):
    for name in ("rear_bearing", "nut_bearing"):
        heat = heats(paper.system, "II")[name]
        assert paper.system.sources[name].friction_model == "skf"
        assert {"rolling_torque_Nm", "sliding_torque_Nm", "phi_ish", "phi_rs"} <= set(heat.details)
    # the front support pair by its catalogue preload drag (issue 32)
    assert paper.system.sources["front_bearing"].friction_model == "constant"
    assert {"equivalent_load_N", "friction_torque_Nm"} <= set(heats(paper.system, "II")["front_bearing"].details)
