"""``check`` refuses what no machine can be: overlapping solids, holes outside their boxes, a face
declared twice, selections of primitives a part does not have (system/topology.py, issue 35)."""

import pytest

from feedtherm.benches import bench
from feedtherm.cli import main
from feedtherm.system import topology
from feedtherm.system.checks import check_errors, check_system
from feedtherm.system.load import validate_data

from topology_cases import BLOCK_BOX, PLATE_BOX, box, system, text


def findings(description: str, severity: str | None = None) -> list[str]:
    found = check_system(system(description))
    return [str(f) for f in found if severity is None or f.severity == severity]


def test_the_block_on_its_plate_has_no_finding():
    assert findings(text()) == []


# --------------------------------------------------------------------------- faces


def test_a_face_in_two_surfaces_is_an_error_naming_both():
    extra = '[surfaces.again]\npart = "block"\nfaces = ["+z", "+x"]\nconvection = { kind = "fixed", ' \
            'coefficient = "5 W/(m^2*K)" }\nemissivity = 0\n\n[sensors.plate]'
    [error] = findings(text(PLATE_BOX, BLOCK_BOX, ("[sensors.plate]", extra)), "error")
    assert error.startswith("surfaces.again.faces: face +z of 'block' boxes[0] is also surfaces.block_top's")


def test_a_face_listed_twice_in_one_surface_is_an_error():
    [error] = findings(text(PLATE_BOX, BLOCK_BOX, ('faces = ["+z"]', 'faces = ["+z", "-x", "+z"]')), "error")
    assert error.startswith("surfaces.block_top.faces: face +z of 'block' boxes[0] is selected twice")


def test_a_cylinder_end_named_and_in_ends_is_selected_twice():
    cylinder = 'cylinders = [{ origin = ["50 mm", "50 mm", "80 mm"], length = "40 mm", outer_diameter = "20 mm" }]'
    description = text(PLATE_BOX, BLOCK_BOX, ('[sources.heater]', f'[parts.pin]\nmaterial = "steel"\n{cylinder}\n\n'
                                               '[surfaces.pin]\npart = "pin"\nfaces = ["ends", "+x"]\nconvection = '
                                               '{ kind = "fixed", coefficient = "5 W/(m^2*K)" }\nemissivity = 0\n\n'
                                               '[sources.heater]'))
    errors = findings(description, "error")
    assert any(e.startswith("surfaces.pin.faces: face +x of 'pin' cylinders[0] is selected twice") for e in errors)


@pytest.mark.parametrize("index", ["1", "-1"])
def test_a_box_index_the_part_does_not_have_is_an_error(index):
    [error] = findings(text(PLATE_BOX, BLOCK_BOX, ('faces = ["+z"]', f'faces = ["+z"]\nboxes = [{index}]')), "error")
    assert error == f"surfaces.block_top.boxes: index {index} is out of range: part 'block' has 1 boxes (indices 0..0)"


def test_a_cylinder_index_on_a_part_without_cylinders_is_an_error():
    [error] = findings(text(PLATE_BOX, BLOCK_BOX, ('faces = ["+z"]', 'faces = ["+z"]\ncylinders = [0]')), "error")
    assert error == "surfaces.block_top.cylinders: index 0 is out of range: part 'block' has no cylinders"


# --------------------------------------------------------------------------- holes


def _with_hole(hole: str, part: str = "block") -> str:
    return text(PLATE_BOX, BLOCK_BOX, (f'[parts.{part}]\nmaterial = "steel"\n',
                                       f'[parts.{part}]\nmaterial = "steel"\nholes = [{hole}]\n'))


def test_a_through_hole_is_accepted():
    assert findings(_with_hole('{ origin = ["50 mm", "50 mm", "40 mm"], length = "100 mm", outer_diameter = "20 mm" }'),
                    "error") == []


def test_a_hole_longer_than_its_box_is_an_error():
    [error] = findings(_with_hole('{ origin = ["50 mm", "50 mm", "40 mm"], length = "120 mm", '
                                  'outer_diameter = "20 mm" }'), "error")
    assert error.startswith("parts.block.holes[0]: runs 50..170 mm along x, beyond its box (50..150 mm)")


def test_a_hole_outside_its_box_is_an_error():
    [error] = findings(_with_hole('{ origin = ["50 mm", "50 mm", "90 mm"], length = "100 mm", '
                                  'outer_diameter = "20 mm" }'), "error")
    assert error == "parts.block.holes[0]: its axis lies outside every box of 'block'"


def test_a_hole_that_breaks_out_of_its_box_side_is_an_error():
    [error] = findings(_with_hole('{ origin = ["50 mm", "50 mm", "40 mm"], length = "100 mm", '
                                  'outer_diameter = "50 mm" }'), "error")
    assert error.startswith("parts.block.holes[0]: its 50 mm disc reaches out of the side of its box")


def test_a_hole_on_a_part_without_boxes_is_an_error():
    cylinder = 'cylinders = [{ origin = ["50 mm", "50 mm", "20 mm"], axis = "z", length = "40 mm", outer_diameter = "60 mm" }]'
    description = text(PLATE_BOX, BLOCK_BOX, (f"boxes = [{BLOCK_BOX}]", cylinder), ('faces = ["+z"]', 'faces = ["+z"]'))
    description = description.replace('[parts.block]\nmaterial = "steel"\n', '[parts.block]\nmaterial = "steel"\n'
                                      'holes = [{ origin = ["50 mm", "50 mm", "20 mm"], axis = "z", length = "40 mm", '
                                      'outer_diameter = "20 mm" }]\n')
    errors = findings(description, "error")
    assert any(e.startswith("parts.block.holes[0]: 'block' has no boxes, and holes are cut from a part's boxes")
               for e in errors)


# --------------------------------------------------------------------------- overlaps


def test_two_boxes_of_a_part_that_overlap_are_an_error_with_the_volume():
    block = f'{BLOCK_BOX}, {box((140, 20, 20), (50, 60, 40))}'  # 10 mm into the first: 10 x 60 x 40 mm
    [error] = findings(text(PLATE_BOX, block), "error")
    assert error.startswith("parts.block: boxes[0] and boxes[1] overlap by 2.4e+04 mm^3")


def test_two_boxes_of_a_part_that_touch_are_accepted():
    block = f'{BLOCK_BOX}, {box((150, 20, 20), (50, 60, 40))}'
    assert findings(text(PLATE_BOX, block), "error") == []


def test_a_block_sunk_into_its_plate_names_both_parts_and_the_volume():
    [finding] = topology.overlaps(system(text(PLATE_BOX, box((50, 20, 15), (100, 60, 40)))))
    assert str(finding).startswith("parts.plate.boxes[0]: overlaps part 'block' (boxes[0]) by 3e+04 mm^3")
    assert finding.severity == "error"  # no machine is two parts in one place


def test_a_press_fit_declared_on_the_joint_may_overlap():
    sunk = text(PLATE_BOX, box((50, 20, 15), (100, 60, 40)), ('area = "6000 mm^2" }', 'area = "6000 mm^2", fit = true }'))
    assert topology.overlaps(system(sunk)) == []


def test_fit_is_left_out_of_the_serialised_joint_at_its_default():
    assert "fit" not in system(text()).joints[0].model_dump()
    assert system(text(PLATE_BOX, BLOCK_BOX, ('area = "6000 mm^2" }', 'area = "6000 mm^2", fit = true }'))) \
        .joints[0].model_dump()["fit"] is True


def _pin_in_plate_hole(pin_diameter: str) -> str:
    hole = '{ origin = ["100 mm", "50 mm", "0 mm"], axis = "z", length = "20 mm", outer_diameter = "20 mm" }'
    pin = (f'cylinders = [{{ origin = ["100 mm", "50 mm", "-10 mm"], axis = "z", length = "30 mm", '
           f'outer_diameter = "{pin_diameter}" }}]')
    extra = (f'[parts.pin]\nmaterial = "steel"\n{pin}\n\n[surfaces.pin]\npart = "pin"\nfaces = ["ends"]\n'
             'convection = { kind = "fixed", coefficient = "5 W/(m^2*K)" }\nemissivity = 0\n\n[sources.heater]')
    return text(PLATE_BOX, BLOCK_BOX, ('[parts.plate]\nmaterial = "steel"\n',
                                       f'[parts.plate]\nmaterial = "steel"\nholes = [{hole}]\n'),
                ("[sources.heater]", extra),
                ('joints = [{ between = ["plate", "block"], tcr = "1e-4 m^2*K/W", area = "6000 mm^2" }]',
                 'joints = [{ between = ["plate", "block"], tcr = "1e-4 m^2*K/W", area = "6000 mm^2" },\n'
                 '          { between = ["plate", "pin"], tcr = "1e-4 m^2*K/W", area = "600 mm^2" }]'))


def test_a_cylinder_in_a_hole_of_its_diameter_does_not_overlap_the_box():
    assert topology.overlaps(system(_pin_in_plate_hole("20 mm"))) == []


def test_a_cylinder_a_hundredth_of_a_mm_wider_than_its_hole_overlaps_the_box():
    [finding] = topology.overlaps(system(_pin_in_plate_hole("20.01 mm")))
    assert "part 'pin'" in str(finding) and str(finding).startswith("parts.plate.boxes[0]")


def test_coaxial_cylinders_that_meet_at_a_face_are_one_part_and_those_that_overlap_are_not():
    sleeve = '{ origin = ["0 mm", "0 mm", "0 mm"], length = "87 mm", outer_diameter = "50 mm", inner_diameter = "32 mm" }'
    flange = '{ origin = ["75 mm", "0 mm", "0 mm"], length = "12 mm", outer_diameter = "80 mm", inner_diameter = "ID" }'
    from feedtherm.system.schema import Part

    def nut(inner):
        import tomllib
        return {"material": "steel", **tomllib.loads(f"cylinders = [{sleeve}, {flange.replace('ID', inner)}]")}

    for inner, volume in (("50 mm", None), ("40 mm", 3.1416 * (25**2 - 20**2) * 12)):
        data = {"parts": {"nut": nut(inner)}}
        solids = [s for s in topology._solids(type("S", (), {"parts": {"nut": Part.model_validate(data["parts"]["nut"])}})())]
        v = topology.overlap_volume(*solids) * 1e9
        assert (v == 0.0) if volume is None else v == pytest.approx(volume, rel=1e-4)


# --------------------------------------------------------------------------- the moving group


BALLSCREW = bench("ballscrew_example").description.read_text(encoding="utf-8")


def test_the_moving_group_is_checked_at_the_ends_of_its_stroke():
    """The example's nut flange clears a bearing housing by 23 mm at a stroke end: 60 mm more
    stroke takes it 7 mm into it (the nut still on the screw)."""
    import tomllib

    data = tomllib.loads(BALLSCREW.replace('stroke = "400 mm"', 'stroke = "460 mm"'))
    found = [str(f) for f in topology.overlaps(validate_data(data, "t").system)]
    assert found and all("with the moving group" in f for f in found)
    assert any("+230 mm" in f or "-230 mm" in f for f in found)


# --------------------------------------------------------------------------- bundled benches


def test_the_bundled_benches_have_no_topology_error():
    for name in ("paper", "ballscrew_example"):
        data = __import__("tomllib").loads(bench(name).description.read_text(encoding="utf-8"))
        loaded = validate_data(data, name).system
        assert topology.errors(loaded) == []


def test_the_paper_bench_belt_clears_the_screw_and_touches_what_it_is_joined_to():
    """Once a slab across the screw (issue 35), the belt is its two strands beside it, on the nut
    flange's and the nut motor's faces, with the slab's volume."""
    data = __import__("tomllib").loads(bench("paper").description.read_text(encoding="utf-8"))
    parts = validate_data(data, "paper").system.parts
    screw_radius = parts["screw"].cylinders[0].outer_diameter / 2.0
    for strand in parts["belt"].boxes:
        z_lo, z_hi = strand.origin[2], strand.origin[2] + strand.size[2]
        assert min(abs(z_lo), abs(z_hi)) > screw_radius + 2e-3  # a gap of more than 2 mm (4 mm drawn)
        assert strand.origin[0] == pytest.approx(0.257)  # on the flange's and the motor's +x faces
    flange, motor = parts["nut"].cylinders[1], parts["nut_motor"].boxes[0]
    assert flange.origin[0] + flange.length == pytest.approx(0.257)
    assert motor.origin[0] + motor.size[0] == pytest.approx(0.257)
    assert sum(b.size[0] * b.size[1] * b.size[2] for b in parts["belt"].boxes) == pytest.approx(50e-6)


# --------------------------------------------------------------------------- warnings


def test_a_part_joined_to_nothing_is_a_warning():
    pin = 'cylinders = [{ origin = ["50 mm", "50 mm", "80 mm"], length = "40 mm", outer_diameter = "20 mm" }]'
    extra = (f'[parts.pin]\nmaterial = "steel"\n{pin}\n\n[surfaces.pin]\npart = "pin"\nfaces = ["lateral"]\n'
             'convection = { kind = "fixed", coefficient = "5 W/(m^2*K)" }\nemissivity = 0\n\n[sources.heater]')
    warnings = findings(text(PLATE_BOX, BLOCK_BOX, ("[sources.heater]", extra)), "warning")
    assert [w for w in warnings if w.startswith("parts.pin: is joined to nothing")]


@pytest.mark.parametrize("area, warned", [("48000 mm^2", False), ("70000 mm^2", True), ("500 mm^2", True)])
def test_an_area_far_from_the_faces_is_a_warning(area, warned):
    # block_top is 100 x 60 mm = 6000 mm^2
    warnings = findings(text(PLATE_BOX, BLOCK_BOX, ('faces = ["+z"]', f'faces = ["+z"]\narea = "{area}"')), "warning")
    assert any(w.startswith("surfaces.block_top.area:") for w in warnings) is warned


# --------------------------------------------------------------------------- the command


def test_check_refuses_an_overlap_in_one_line(tmp_path, capsys):
    path = tmp_path / "d.toml"
    path.write_text(text(PLATE_BOX, f'{BLOCK_BOX}, {box((140, 20, 20), (50, 60, 40))}'), encoding="utf-8")
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "parts.block: boxes[0] and boxes[1] overlap by 2.4e+04 mm^3" in err


def test_an_overlap_between_parts_refuses_the_description(tmp_path, capsys):
    path = tmp_path / "d.toml"
    path.write_text(text(PLATE_BOX, box((50, 20, 15), (100, 60, 40))), encoding="utf-8")
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "overlaps part 'block'" in err
    assert check_errors(system(text(PLATE_BOX, box((50, 20, 15), (100, 60, 40)))))
