"""Joint contact areas and exposed surface areas from the geometry, against hand calculations."""

import math

import pytest

from feedtherm.benches.template import TEMPLATE
from feedtherm.errors import DescriptionError
from feedtherm.system.areas import contact_patches, disc_in_rectangle, exposed_area, joint_contact_area
from feedtherm.system.load import load_system
from feedtherm.system.schema import Part

MM = 1e-3


def box(origin, size):
    return {"origin": [f"{v} mm" for v in origin], "size": [f"{v} mm" for v in size]}


def cylinder(origin, length, outer, inner=0.0):
    return {"origin": [f"{v} mm" for v in origin], "length": f"{length} mm", "outer_diameter": f"{outer} mm",
            "inner_diameter": f"{inner} mm"}


def part(**geometry) -> Part:
    return Part.model_validate({"material": "steel", **geometry})


def area_between(a: Part, b: Part) -> float:
    return sum(p.area for p in contact_patches("a", a, "b", b) if p.part == "a")


def test_a_disc_in_a_rectangle():
    r = 10 * MM
    assert disc_in_rectangle(0.0, 0.0, r, ((-1.0, 1.0), (-1.0, 1.0))) == pytest.approx(math.pi * r * r, rel=1e-12)
    # centred on the rectangle's edge: half the disc; on its corner: a quarter
    assert disc_in_rectangle(0.0, 0.0, r, ((0.0, 1.0), (-1.0, 1.0))) == pytest.approx(math.pi * r * r / 2, rel=1e-6)
    assert disc_in_rectangle(0.0, 0.0, r, ((0.0, 1.0), (0.0, 1.0))) == pytest.approx(math.pi * r * r / 4, rel=1e-6)
    assert disc_in_rectangle(0.0, 0.0, r, ((2 * r, 1.0), (0.0, 1.0))) == 0.0


def test_two_boxes_share_the_overlap_of_their_facing_faces():
    # a 50x110 mm foot (x -25..25, y -55..55) on a slab top (x -300..700, y -200..200), both at z = -70 mm
    foot = part(boxes=[box((-25, -55, -70), (50, 110, 105))])
    slab = part(boxes=[box((-300, -200, -130), (1000, 400, 60))])
    assert area_between(foot, slab) == pytest.approx(50 * 110 * MM**2, rel=1e-12)
    # shifted half off the slab's end (x 675..725 over a slab ending at 700): 25 x 110
    off = part(boxes=[box((675, -55, -70), (50, 110, 105))])
    assert area_between(off, slab) == pytest.approx(25 * 110 * MM**2, rel=1e-12)
    # not touching (1 mm above): nothing
    above = part(boxes=[box((-25, -55, -69), (50, 110, 105))])
    assert area_between(above, slab) == 0.0


def test_a_flange_face_on_a_bored_box_and_a_body_in_its_bore():
    # The template's nut: body Ø40 x 80 mm in the housing's Ø40 bore (pi 40 80 = 10,053 mm^2), flange
    # Ø62 (bore 25) against the housing's -x face, which has the Ø40 hole: pi/4 (62^2 - 40^2) = 1,762 mm^2.
    nut = part(cylinders=[cylinder((260, 0, 0), 80, 40, 25), cylinder((248, 0, 0), 12, 62, 25)])
    housing = part(boxes=[box((260, -50, -45), (80, 100, 100))],
                   holes=[cylinder((260, 0, 0), 80, 40)])
    hand = (math.pi * 40 * 80 + math.pi / 4 * (62**2 - 40**2)) * MM**2
    assert area_between(nut, housing) == pytest.approx(hand, rel=1e-6)
    # a face hole's patch less a coaxial hole: the housing's faces keep pi/4 40^2 out of 100 x 100
    patches = contact_patches("h", housing, "n", nut)
    assert {p.face for p in patches if p.part == "h"} == {"bore", "-x"}


def test_a_ring_on_a_shaft_and_two_coaxial_end_faces():
    ring = part(cylinders=[cylinder((-15, 0, 0), 30, 47, 25)])
    shaft = part(cylinders=[cylinder((-25, 0, 0), 645, 25)])
    assert area_between(ring, shaft) == pytest.approx(math.pi * 25 * 30 * MM**2, rel=1e-12)
    # a Ø20 pin's end face on the shaft's end face: pi/4 20^2
    pin = part(cylinders=[cylinder((-45, 0, 0), 20, 20)])
    assert area_between(pin, shaft) == pytest.approx(math.pi / 4 * 20**2 * MM**2, rel=1e-12)
    # a ring of another bore does not touch the shaft's lateral face
    loose = part(cylinders=[cylinder((-15, 0, 0), 30, 47, 26)])
    assert area_between(loose, shaft) == 0.0


def template_text(name="t") -> str:
    return (TEMPLATE / "description.toml").read_text(encoding="utf-8").replace("__BENCH_NAME__", name)


def load_text(tmp_path, text: str):
    path = tmp_path / "description.toml"
    path.write_text(text, encoding="utf-8")
    return load_system(str(path))


def test_a_joint_without_area_takes_its_contact_and_a_given_area_wins(tmp_path):
    loaded = load_text(tmp_path, template_text())
    joints = loaded.system.joints
    # joints[10]: front housing foot 50 x 110 mm on the bed; joints[12]: the motor's 80 x 80 flange on
    # the housing's 105 mm high face (overlap 80 x 75 mm) less the housing's Ø47 bearing seat
    assert joints[10].area == pytest.approx(50 * 110 * MM**2, rel=1e-12)
    assert joints[12].area == pytest.approx((80 * 75 - math.pi / 4 * 47**2) * MM**2, rel=1e-6)
    assert 10 in loaded.derived_joint_areas
    given = template_text().replace('description = "front housing bolted to the bed"',
                                    'area = "4e-3 m^2"\ndescription = "front housing bolted to the bed"')
    loaded = load_text(tmp_path, given)
    assert loaded.system.joints[10].area == 4e-3 and 10 not in loaded.derived_joint_areas


def test_a_joint_of_parts_that_do_not_touch_and_give_no_area_is_one_line_naming_it(tmp_path):
    text = template_text().replace('between = ["rear_housing", "base"]', 'between = ["rear_housing", "table"]')
    with pytest.raises(DescriptionError) as info:
        load_text(tmp_path, text)
    message = str(info.value)
    assert "\n" not in message
    assert "joints[11].area: not given, and 'rear_housing' and 'table' have no faces that touch" in message


def test_a_surface_without_area_loses_what_joined_parts_cover(tmp_path):
    system = load_text(tmp_path, template_text()).system
    # the screw, Ø25 x 645 mm, less the bearing rings (30 + 14 mm) and the nut (80 + 12 mm) on it
    assert exposed_area(system, "screw") == pytest.approx(math.pi * 25 * (645 - 30 - 14 - 92) * MM**2, rel=1e-9)
    # the table's underside, 400 x 300 mm, less the nut housing (80 x 100) and four carriages (60 x 48)
    assert exposed_area(system, "table_bottom") == pytest.approx((400 * 300 - 80 * 100 - 4 * 60 * 48) * MM**2, rel=1e-9)
    # a face nothing covers keeps its area
    assert exposed_area(system, "table_top") == pytest.approx(400 * 300 * MM**2, rel=1e-12)


def test_the_paper_bench_states_every_joint_area_and_they_match_its_geometry():
    # The bench's frozen values are its own; where its drawing is the contact, the derivation agrees.
    loaded = load_system("paper")
    assert loaded.derived_joint_areas == ()
    system = loaded.system
    for index in (0, 2, 9, 10, 11, 12, 13, 14):
        assert joint_contact_area(system, index) == pytest.approx(system.joints[index].area, rel=1e-3)


def test_a_derived_area_follows_a_change_of_the_geometry_and_a_stated_one_does_not(tmp_path):
    from feedtherm.system.variants import with_values

    loaded = load_text(tmp_path, template_text())
    # the front housing's foot 50 mm -> 60 mm along x: its joint with the bed, 60 x 110 mm
    box = loaded.system.parts["front_housing"].boxes[0]
    wider = box.model_copy(update={"size": (0.060, box.size[1], box.size[2])})
    variant = with_values(loaded, {"parts.front_housing.boxes": [wider]})
    assert variant.system.joints[10].area == pytest.approx(60 * 110 * MM**2, rel=1e-12)
    stated = with_values(loaded, {"joints[10].area": 4e-3, "parts.front_housing.boxes": [wider]})
    assert stated.system.joints[10].area == 4e-3 and 10 not in stated.derived_joint_areas


def test_an_exposed_area_follows_a_changed_description_and_not_an_earlier_ones(tmp_path):
    """exposed_area keeps each description's areas; a variant (a new, frozen object) gets its own."""
    from feedtherm.system.variants import with_values

    loaded = load_text(tmp_path, template_text())
    before = exposed_area(loaded.system, "screw")
    assert exposed_area(loaded.system, "screw") == before  # the kept value
    # the nut's body 80 mm -> 60 mm long leaves 20 mm more of the screw's Ø25 mm bare
    body, flange = loaded.system.parts["nut"].cylinders
    shorter = body.model_copy(update={"length": body.length - 0.020})
    variant = with_values(loaded, {"parts.nut.cylinders": [shorter, flange]})
    assert exposed_area(variant.system, "screw") == pytest.approx(before + math.pi * 25 * 20 * MM**2, rel=1e-9)
    assert exposed_area(loaded.system, "screw") == before
