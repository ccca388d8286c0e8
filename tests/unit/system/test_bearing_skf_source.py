"""A bearing with friction_model = "skf" in a description: units converted, bad values named."""

from __future__ import annotations

import pytest

from feedtherm.benches import bench
from feedtherm.errors import DescriptionError
from feedtherm.system.load import load_system

PAPER = bench("paper").description.read_text(encoding="utf-8")
PALMGREN_NUT = '''bearing_type = "angular_contact"
mean_diameter = "65 mm"
static_load_rating = "20 kN"
axial_load = "300 N"
radial_load = "50 N"
f0 = 4.0
lubricant_viscosity = "100 mm^2/s"
into = { nut_bearing = 1.0 }'''
SKF_NUT = '''bearing_type = "angular_contact"
friction_model = "skf"
bore_diameter = "50 mm"
outer_diameter = "80 mm"
series = "single_row"
bearings_in_set = 2
static_load_rating = "20 kN"
axial_load = "300 N"
radial_load = "50 N"
lubricant = { grade = "ISO VG 100", viscosity_100C = "11 mm^2/s" }
into = { nut_bearing = 1.0 }'''


def write_variant(tmp_path, block: str) -> str:
    """The paper bench with its nut bearing (declared as ``SKF_NUT``) replaced by ``block``."""
    assert PAPER.count(SKF_NUT) == 1, "test fixture out of date: the paper bench's nut bearing changed"
    path = tmp_path / "skf_variant.toml"
    path.write_text(PAPER.replace(SKF_NUT, block, 1), encoding="utf-8")
    return str(path)


def load_error(tmp_path, block: str) -> str:
    with pytest.raises(DescriptionError) as info:
        load_system(write_variant(tmp_path, block))
    message = str(info.value)
    assert "\n" not in message
    return message


def test_skf_bearing_loads_in_si(tmp_path):
    source = load_system(write_variant(tmp_path, SKF_NUT)).system.sources["nut_bearing"]
    assert source.friction_model == "skf"
    assert (source.bore_diameter, source.outer_diameter) == pytest.approx((0.050, 0.080))
    assert source.dm == pytest.approx(0.065)  # (50 + 80)/2 mm
    assert source.bearings_in_set == 2 and source.lubrication == "grease" and source.base_oil == "mineral"


def test_palmgren_may_take_its_mean_diameter_from_d_and_D(tmp_path):
    block = PALMGREN_NUT.replace('mean_diameter = "65 mm"', 'bore_diameter = "50 mm"\nouter_diameter = "80 mm"')
    source = load_system(write_variant(tmp_path, block)).system.sources["nut_bearing"]
    assert source.dm == pytest.approx(0.065)


def test_skf_seal_with_units(tmp_path):
    block = SKF_NUT + '\nseal = "RS1"\nseal_counterface_diameter = "57.6 mm"\nseals_per_bearing = 1'
    source = load_system(write_variant(tmp_path, block)).system.sources["nut_bearing"]
    assert source.seal == "RS1" and source.seal_counterface_diameter == pytest.approx(0.0576)


@pytest.mark.parametrize(
    ("edit", "reason"),
    [
        (lambda b: b.replace('series = "single_row"\n', ""), "series: needed by friction_model = 'skf'"),
        (lambda b: b.replace('bore_diameter = "50 mm"\n', ""), "bore_diameter: needed by friction_model = 'skf'"),
        (lambda b: b.replace('"single_row"', '"72"'), "series: SKF gives no friction constants for angular_contact series '72'"),
        (lambda b: b.replace('"80 mm"', '"40 mm"'), "outer_diameter must be larger than bore_diameter"),
        (lambda b: b + '\nmean_diameter = "60 mm"', "mean_diameter must be (bore_diameter + outer_diameter)/2"),
        (lambda b: b + '\nseal = "RS1"', "seal_counterface_diameter: needed with a seal"),
        (lambda b: b + '\nseal = "RSH"\nseal_counterface_diameter = "57.6 mm"', "seal: SKF Table 4 gives no constants for 'RSH'"),
        (lambda b: b + '\nseals_per_bearing = 1', "used only with a seal"),
        (lambda b: b + '\ndrag_torque = "5 N*mm"', "drag_torque: an oil bath's or oil jet's drag"),
        (lambda b: b + '\nlubrication = "oil_mist"', "lubrication"),
        (lambda b: b.replace('bearings_in_set = 2', 'bearings_in_set = 0'), "bearings_in_set"),
    ],
)
def test_bad_skf_bearing_is_named(tmp_path, edit, reason):
    message = load_error(tmp_path, edit(SKF_NUT))
    assert "sources.nut_bearing" in message and reason in message, message


@pytest.mark.parametrize(
    ("edit", "reason"),
    [
        (lambda b: b.replace("f0 = 4.0\n", ""), "f0: needed by friction_model = 'palmgren'"),
        (lambda b: b.replace('mean_diameter = "65 mm"\n', ""), "mean_diameter: needed by friction_model = 'palmgren'"),
        (lambda b: b + '\nseries = "single_row"', "series: used only by friction_model = 'skf'"),
    ],
)
def test_bad_palmgren_bearing_is_named(tmp_path, edit, reason):
    message = load_error(tmp_path, edit(PALMGREN_NUT))
    assert "sources.nut_bearing" in message and reason in message, message


def test_a_palmgren_bearing_serialises_without_the_skf_fields(tmp_path):
    # The SKF fields of a Palmgren bearing are left out of the serialised form (and the hash).
    source = load_system(write_variant(tmp_path, PALMGREN_NUT)).system.sources["nut_bearing"]
    assert source.friction_model == "palmgren"
    dumped = source.model_dump()
    assert not {"friction_model", "series", "bore_diameter", "bearings_in_set", "lubrication", "lubricant"} & set(dumped)


def test_the_bench_serialises_its_skf_bearings_without_the_unused_options(paper):
    # The bench's nut bearing is an SKF bearing: its declared SKF fields are serialised; the
    # Palmgren fields and the SKF options left at their defaults are left out (and the hash).
    source = paper.system.sources["nut_bearing"]
    assert source.friction_model == "skf"
    dumped = source.model_dump()
    assert {"friction_model", "series", "bore_diameter", "outer_diameter", "bearings_in_set", "lubricant"} <= set(dumped)
    assert (dumped["friction_model"], dumped["series"], dumped["bearings_in_set"]) == ("skf", "single_row", 2)
    assert not {"mean_diameter", "f0", "lubricant_viscosity", "lubrication", "base_oil",
                "seal", "seal_counterface_diameter", "seals_per_bearing", "drag_torque"} & set(dumped)
