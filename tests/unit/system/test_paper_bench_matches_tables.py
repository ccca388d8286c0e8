"""The `paper` description carries Tables 1-5 exactly as printed (benches/paper/tables/*.csv)."""

import math

import pytest

from feedtherm import benches
from feedtherm.system.load import load_system
from feedtherm.system.overlay import available_overlay

MATERIAL_KEYS = {"nut": "copper_alloy", "screw/bearing": "gcr15", "base/bearing housing": "q345b",
                 "guideways/slider": "cr40"}
SOURCE_KEYS = {"guideways": "guideways", "screw_servo_motor": "screw_motor", "nut_servo_motor": "nut_motor",
               "front_bearing": "front_bearing", "nut_bearing": "nut_bearing", "rear_bearing": "rear_bearing"}
TCR_JOINTS = {  # Table 3 row -> joints of the bench that use it
    "bearing_outer_ring-bearing_housing": [("front_bearing", "front_housing"), ("rear_bearing", "rear_housing"), ("nut_bearing", "nut_housing")],
    "bearing_inner_ring-screw_shaft": [("front_bearing", "screw"), ("rear_bearing", "screw")],
    "nut-screw": [("nut", "screw")],
    "guideway-slider": [("sliders", "guideways")],
    "nut_servo_motor-nut": [("nut_motor", "nut_housing")],
}
TABLES = benches.bench("paper")  # its tables/ folder holds Tables 1-7 as printed


@pytest.fixture(scope="module")
def bench():
    return load_system("paper").system


def test_table4_materials(bench):
    for row in TABLES.table(4):
        m = bench.materials[MATERIAL_KEYS[row["components"]]]
        assert m.density == pytest.approx(float(row["density_kg_per_m3"]))
        assert m.youngs_modulus == pytest.approx(float(row["youngs_modulus_GPa"]) * 1e9)
        assert m.poisson_ratio == pytest.approx(float(row["poisson_ratio"]))
        assert m.expansion == pytest.approx(float(row["expansion_coefficient_per_K"]))
        assert m.conductivity == pytest.approx(float(row["conductivity_W_per_mK"]))
        assert m.specific_heat == pytest.approx(float(row["specific_heat_J_per_kgK"]))


def test_table3_contact_resistances(bench):
    joints = {tuple(j.between): j for j in bench.joints}
    for row in TABLES.table(3):
        for pair in TCR_JOINTS[row["joint"]]:
            assert joints[pair].tcr == pytest.approx(float(row["tcr_m2K_per_W"])), pair


def test_table5_conditions(bench):
    for row in TABLES.table(5):
        c = bench.conditions[row["condition"]]
        assert c.screw_speed == pytest.approx(float(row["screw_speed_rpm"]) * 2 * math.pi / 60)
        assert c.nut_speed == pytest.approx(float(row["nut_speed_rpm"]) * 2 * math.pi / 60)
        assert c.ambient == pytest.approx(float(row["ambient_C"]) + 273.15)
        assert c.feed_speed == pytest.approx(float(row["feed_speed_m_per_min"]) / 60)
        assert c.duration == 10800.0  # paper §4.3


def test_tables_1_and_2_in_paper_mode_mapping():
    overlay = available_overlay(load_system("paper"))
    heat = {row.source: row.value for row in overlay.heat}
    assert heat == {SOURCE_KEYS[r["source"]]: pytest.approx(float(r["heat_W"])) for r in TABLES.table(1)}
    chtc = {row.table_label.lower().replace(" ", "_"): row.value for row in overlay.chtc}
    printed = {r["surface"]: float(r["chtc_W_per_m2K"]) for r in TABLES.table(2)}
    assert chtc == {k: pytest.approx(v) for k, v in printed.items()}
    assert overlay.reference_condition == "I"


def test_measurements_are_not_inputs(bench):
    # Tables 6 and 7 may be used to compare, never as inputs: no provenance entry cites them.
    for entry in bench.provenance:
        assert "Table 6" not in entry.source and "Table 7" not in entry.source
