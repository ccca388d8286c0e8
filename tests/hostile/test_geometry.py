"""A description's geometry, handed over careless or hostile: points in holes, joints between parts
that do not touch, joint areas no contact has, supports and references on the moving table, sizes
below a micrometre, a hole drawn outside its box.

Each case is a variant of a bundled bench written by text replacement into ``tmp_path`` and given
to ``feedtherm check``: refused in one line naming the field, or run with a warning naming it.
"""

from __future__ import annotations

import pytest

from feedtherm import cli
from bench_text import paper_text  # tests/: the paper bench with changes made


FOURTH_SUPPORT = "[mechanics.elongation]\ntarget"


def variant(tmp_path, *changes: tuple[str, str]) -> str:
    """The paper bench's text with each ``(old, new)`` replaced once, written to ``tmp_path``."""
    path = tmp_path / "variant.toml"
    path.write_text(paper_text(*changes), encoding="utf-8")
    return str(path)


def accepted(tmp_path, monkeypatch, capsys, path: str) -> str:
    """``feedtherm check path`` exits 0; returns what it printed."""
    monkeypatch.chdir(tmp_path)
    code = cli.main(["check", path])
    out, err = capsys.readouterr()
    assert code == 0, (code, out, err)
    return out + err


def support(part: str, point: str, fix: str) -> tuple[str, str]:
    """A fourth support, declared before the elongation sensor."""
    return (FOURTH_SUPPORT, f'[[mechanics.supports]]\npart = "{part}"\npoint = {point}\nfix = {fix}\n\n'
                            + FOURTH_SUPPORT)


# --------------------------------------------------------------------------- points in holes


def test_a_sensor_in_a_bore_is_refused(tmp_path, refused):
    # the nut housing's bore is 80 mm across: 20 mm above the axis is inside it, in the nut bearing's space
    path = variant(tmp_path, ('position = ["245 mm", "0 mm", "45 mm"]', 'position = ["200 mm", "0 mm", "20 mm"]'))
    refused("check", path, says=("sensors.T3.position", "(200, 0, 20) mm lies in the hole of part 'nut_housing'",
                                 "holes[0]"))


def test_a_sensor_on_a_bores_wall_is_accepted(tmp_path, monkeypatch, capsys):
    # the front housing's 62 mm bore: a PT100 on its wall, 31 mm above the axis, reads the housing
    path = variant(tmp_path, ('position = ["0 mm", "0 mm", "35 mm"]', 'position = ["0 mm", "0 mm", "31 mm"]'))
    assert "sensors.T1" not in accepted(tmp_path, monkeypatch, capsys, path)


def test_the_positioning_reference_in_a_bore_is_refused(tmp_path, refused):
    path = variant(tmp_path, ('reference = { part = "base", point = ["0 mm", "0 mm", "-60 mm"] }',
                              'reference = { part = "front_housing", point = ["0 mm", "0 mm", "0 mm"] }'))
    refused("check", path, says=("mechanics.positioning.reference.point", "lies in the hole of part 'front_housing'"))


def test_a_support_in_a_bore_is_refused(tmp_path, refused):
    path = variant(tmp_path, support("rear_housing", '["400 mm", "0 mm", "-10 mm"]', '["z"]'))
    refused("check", path, says=("mechanics.supports[3].point", "lies in the hole of part 'rear_housing'"))


def test_the_elongation_mount_in_a_bore_is_refused(tmp_path, refused):
    path = variant(tmp_path, ('mount = { part = "base", point = ["480 mm", "0 mm", "-60 mm"] }',
                              'mount = { part = "rear_housing", point = ["400 mm", "0 mm", "10 mm"] }'))
    refused("check", path, says=("mechanics.elongation.mount.point", "lies in the hole of part 'rear_housing'"))


# --------------------------------------------------------------------------- joints are contacts


def test_a_joint_whose_parts_no_longer_touch_is_refused(tmp_path, refused):
    # the screw motor's bracket plate 540 mm lower, below the base: the housing's bounding box still
    # reaches the motor, but no face of the housing touches it
    path = variant(tmp_path, ('{ origin = ["-220 mm", "-40 mm", "-60 mm"], size = ["190 mm", "80 mm", "30 mm"] }',
                              '{ origin = ["-220 mm", "-40 mm", "-600 mm"], size = ["190 mm", "80 mm", "30 mm"] }'))
    refused("check", path, says=("joints[11].between", "'screw_motor' and 'front_housing' have no faces that touch"))


def test_a_joint_area_larger_than_its_parts_is_refused(tmp_path, refused):
    # 9,900 m^2 for the 90 x 110 mm face of the nut housing under the table (a unit slip)
    path = variant(tmp_path, ('area = "9.9e-3 m^2"', 'area = "9900 m^2"'))
    refused("check", path, says=("joints[14].area", "9900 m^2 is larger than the whole surface of 'nut_housing'"))


def test_a_joint_area_far_above_its_contact_is_warned(tmp_path, warned):
    path = variant(tmp_path, ('area = "9.9e-3 m^2"', 'area = "3e-2 m^2"'))
    warned("check", path, says=("joints[14].area", "3.03 times the contact of 'nut_housing' and 'worktable'",
                                "9900 mm^2"))


def test_the_paper_benchs_joints_lie_within_twice_their_contact(tmp_path, monkeypatch, capsys):
    path = variant(tmp_path)
    assert "joints[" not in accepted(tmp_path, monkeypatch, capsys, path).replace("  joints[", "")


def test_the_ballscrew_examples_coupling_hub_is_warned(tmp_path, warned):
    # its hub clamps a 16 mm journal the drawing leaves out: 2.57 times the screw's end face it draws
    warned("check", "ballscrew_example", says=("joints[16].area", "2.57 times the contact of 'coupling' and 'screw'"))


# --------------------------------------------------------------------------- the moving group


def test_a_support_along_x_on_the_moving_table_is_refused(tmp_path, refused):
    path = variant(tmp_path, support("worktable", '["200 mm", "0 mm", "85 mm"]', '["x", "z"]'))
    refused("check", path, says=("mechanics.supports[3].fix", "holds 'worktable' along x", "moves with the table"))


def test_a_support_across_the_travel_of_the_moving_table_is_its_guides(tmp_path, monkeypatch, capsys):
    # held along z only: as guides hold a table, travelling with it (docs/system-description.md)
    path = variant(tmp_path, support("worktable", '["200 mm", "0 mm", "85 mm"]', '["z"]'))
    assert "supports[3]" not in accepted(tmp_path, monkeypatch, capsys, path)


def test_the_positioning_reference_on_the_moving_table_is_refused(tmp_path, refused):
    path = variant(tmp_path, ('reference = { part = "base", point = ["0 mm", "0 mm", "-60 mm"] }',
                              'reference = { part = "worktable", point = ["200 mm", "0 mm", "85 mm"] }'))
    refused("check", path, says=("mechanics.positioning.reference.part", "'worktable' moves with the table"))


# --------------------------------------------------------------------------- sizes below a micrometre


@pytest.mark.parametrize("old, new, field", [
    ('size = ["300 mm", "350 mm", "25 mm"]', 'size = ["300 mm", "350 mm", "1e-7 mm"]', "parts.worktable.boxes[0].size[2]"),
    ('length = "510 mm", outer_diameter = "32 mm"', 'length = "510 mm", outer_diameter = "32e-7 mm"',
     "parts.screw.cylinders[0].outer_diameter"),
    ('length = "60 mm", outer_diameter = "62 mm" }]', 'length = "60 mm", outer_diameter = "1e-4 mm" }]',
     "parts.front_housing.holes[0].outer_diameter"),
    ('outer_diameter = "62 mm", inner_diameter = "32 mm"', 'outer_diameter = "62 mm", inner_diameter = "1 nm"',
     "parts.front_bearing.cylinders[0].inner_diameter"),
    ('convection = { kind = "natural", orientation = "vertical_plate", length = "18 mm" }',
     'convection = { kind = "natural", orientation = "vertical_plate", length = "1e-5 mm" }',
     "surfaces.guideways.convection.length"),
    ('lead = "10 mm"', 'lead = "0.5 um"', "kinematics.lead"),
    ('grease_gap = "0.2 mm"', 'grease_gap = "1e-10 m"', "sources.screw_nut.grease_gap"),
])
def test_a_size_below_a_micrometre_is_refused(tmp_path, refused, old, new, field):
    refused("check", variant(tmp_path, (old, new)), says=(field, "below the smallest accepted size, 1 µm"))


# --------------------------------------------------------------------------- holes and their boxes


def test_a_hole_outside_its_box_says_so(tmp_path, refused):
    path = variant(tmp_path, ('holes = [{ origin = ["-30 mm", "0 mm", "0 mm"], length = "60 mm"',
                              'holes = [{ origin = ["100 mm", "0 mm", "0 mm"], length = "60 mm"'))
    line = refused("check", path, says=("parts.front_housing.holes[0]", "runs 100..160 mm along x",
                                        "outside its box (-30..30 mm)"))
    assert "longer" not in line


def test_a_hole_longer_than_its_box_says_so(tmp_path, refused):
    path = variant(tmp_path, ('holes = [{ origin = ["-30 mm", "0 mm", "0 mm"], length = "60 mm"',
                              'holes = [{ origin = ["-30 mm", "0 mm", "0 mm"], length = "70 mm"'))
    refused("check", path, says=("parts.front_housing.holes[0]", "beyond its box", "longer than its box"))


def test_a_hole_reaching_out_of_its_box_end_says_so(tmp_path, refused):
    path = variant(tmp_path, ('holes = [{ origin = ["-30 mm", "0 mm", "0 mm"], length = "60 mm"',
                              'holes = [{ origin = ["-20 mm", "0 mm", "0 mm"], length = "60 mm"'))
    line = refused("check", path, says=("parts.front_housing.holes[0]", "runs -20..40 mm along x",
                                        "reaches out of its box's end"))
    assert "longer" not in line
