"""Where a point lies in a part's material: a hole's bore is empty, its wall and a blind hole's
floor are material (within the tolerance), its mouth is empty beyond the face; and the whole
surface a joint's area is held against."""

import math

import pytest
from scipy.special import ndtri

from feedtherm.analysis.uncertainty.sampling import EDGE
from feedtherm.system.geometry import contains, hole_at, part_surface_area
from feedtherm.system.schema import Part
from feedtherm.system.uncertainty_checks import SAMPLED_SIGMAS

MM = 1e-3
# a 100 x 100 x 100 mm block at the origin: a through hole Ø40 along x on (y, z) = (50, 50) mm,
# a blind hole Ø20 along z on (x, y) = (20, 20) mm, drilled 30 mm down from the top (z 70..100)
BLOCK = Part.model_validate({
    "material": "steel",
    "boxes": [{"origin": ["0 mm", "0 mm", "0 mm"], "size": ["100 mm", "100 mm", "100 mm"]}],
    "holes": [{"origin": ["0 mm", "50 mm", "50 mm"], "length": "100 mm", "outer_diameter": "40 mm"},
              {"origin": ["20 mm", "20 mm", "70 mm"], "axis": "z", "length": "30 mm", "outer_diameter": "20 mm"}],
})


def at(x, y, z):
    return (x * MM, y * MM, z * MM)


@pytest.mark.parametrize("point, hole", [
    (at(50, 50, 50), 0),      # on the through hole's axis
    (at(50, 50, 68.5), 0),    # 1.5 mm inside its wall
    (at(0, 50, 50), 0),       # in its mouth, on the block's face
    (at(-0.5, 50, 50), 0),    # just beyond the face, still the mouth's air
    (at(20, 20, 85), 1),      # in the blind hole
])
def test_a_point_in_a_bore_is_in_the_hole(point, hole):
    assert hole_at(BLOCK, point) == hole
    assert not contains(BLOCK, point)


@pytest.mark.parametrize("point", [
    at(50, 50, 70),      # on the through hole's wall
    at(50, 50, 69.5),    # 0.5 mm inside it: within the 1 mm tolerance of the wall
    at(50, 50, 80),      # in the material beside it
    at(20, 20, 70),      # on the blind hole's floor (a thermocouple at the bottom of a drilled hole)
    at(20, 20, 70.5),    # 0.5 mm above the floor: within the tolerance
    at(100.5, 10, 10),   # 0.5 mm off a face, away from any hole
])
def test_a_point_on_a_wall_or_floor_is_in_the_material(point):
    assert hole_at(BLOCK, point) is None
    assert contains(BLOCK, point)


def test_a_point_above_the_floor_by_more_than_the_tolerance_is_in_the_hole():
    assert hole_at(BLOCK, at(20, 20, 71.5)) == 1


def test_the_whole_surface_is_an_upper_bound_of_the_drawn_one():
    # 6 faces of 100 x 100 mm, the walls pi 40 100 and pi 20 30 (mouths and floor counted in the faces)
    expected = 6 * 100 * 100 + math.pi * 40 * 100 + math.pi * 20 * 30
    assert part_surface_area(BLOCK) == pytest.approx(expected * MM**2, rel=1e-12)


def test_the_reach_of_an_unbounded_normal_is_the_samplers():
    assert -ndtri(EDGE) <= SAMPLED_SIGMAS < -ndtri(EDGE) + 0.01


def test_the_benches_moving_groups_are_driven_through_their_joints(paper):
    from feedtherm.system.points import driven_moving_parts

    system = paper.system
    moving = {name for name, part in system.parts.items() if part.moving}
    # the worktable reaches the frame only through the sliders or the nut housing, the nut: every one is held by the drive
    assert moving and driven_moving_parts(system) == moving


def test_a_moving_group_joined_to_nothing_fixed_is_not_driven(paper):
    from feedtherm.system.points import driven_moving_parts

    system = paper.system
    moving = {name for name, part in system.parts.items() if part.moving}
    loose = system.model_copy(update={"joints": [j for j in system.joints
                                                 if (j.between[0] in moving) == (j.between[1] in moving)]})
    assert driven_moving_parts(loose) == set()
