"""The fast model's sub-volumes: grids, face samples, contacts, exposed areas, sensors.

Reference values are hand counts of the description's geometry (written out below), not
numbers the code returned once.
"""

import math
import tomllib

import numpy as np
import pytest

from feedtherm.benches import bench
from feedtherm.boundary import boundary_conditions
from feedtherm.models.fast.cells import part_cells
from feedtherm.models.fast.contacts import aggregate, spread_along
from feedtherm.models.fast.grids import box_grid, cylinder_grid, graded_edges
from feedtherm.models.fast.samples import part_samples
from feedtherm.models.options import ModelOptions
from feedtherm.simulate import discretize
from feedtherm.system.geometry import part_volume
from feedtherm.system.load import load_system, validate_data
from feedtherm.system.schema import Box, Cylinder, Part


def m(*values):
    """Lengths in metres as the description writes them."""
    out = tuple(f"{v!r} m" for v in values)
    return out if len(out) > 1 else out[0]


@pytest.fixture(scope="module")
def paper():
    return load_system("paper").system


@pytest.fixture(scope="module")
def fast(paper):
    return discretize(paper, "fast", ModelOptions())


# ------------------------------------------------------------------------------ grids
def test_grid_lines_pass_through_the_features_and_cells_keep_their_size():
    edges = graded_edges(0.0, 1.0, [([0.30, 0.31, 0.72], 0.02)], 0.1)
    assert 0.30 in edges and 0.72 in edges and 0.31 not in edges  # 10 mm from a kept line: merged
    assert edges[0] == 0.0 and edges[-1] == 1.0 and np.all(np.diff(edges) > 0)
    assert np.diff(edges).max() <= 0.1 * 1.5


def test_a_box_grid_conducts_like_the_bar_it_is():
    # 100 x 20 x 20 mm bar in 5 cells of 20 mm: neighbours conduct A/Δ, so the chain of
    # 4 links plus the two half cells to the end faces is A/L, the bar's own conductance
    grid = box_grid(Box(origin=m(0, 0, 0), size=m(0.1, 0.02, 0.02)), [], 0.02)
    assert grid.shape == (5, 1, 1)
    a, b, g = grid.links
    assert len(g) == 4 and np.allclose(g, 0.02 * 0.02 / 0.02)
    resistance = (1 / g).sum() + 2 * (0.01 / (0.02 * 0.02))
    assert 1 / resistance == pytest.approx(0.02 * 0.02 / 0.1, rel=1e-12)
    assert grid.volumes.sum() == pytest.approx(0.1 * 0.02 * 0.02, rel=1e-12)


def test_a_hole_is_cut_from_the_cells():
    box = Box(origin=m(0, -0.05, -0.05), size=m(0.04, 0.1, 0.1))
    hole = Cylinder(origin=m(0, 0, 0), length=m(0.04), outer_diameter=m(0.06))
    grid = box_grid(box, [hole], 0.02)
    solid = 0.04 * 0.1 * 0.1 - math.pi / 4 * 0.06**2 * 0.04
    assert grid.volumes.sum() == pytest.approx(solid, rel=1e-12)
    for c in (-0.03, 0.0, 0.03):  # the hole's edges and centre are grid lines across it
        assert np.isclose(grid.edges[1], c).any() and np.isclose(grid.edges[2], c).any()
    # no cell remains in the middle of the hole
    inside = np.hypot(grid.centroids[:, 1], grid.centroids[:, 2]) < 0.03 * math.sin(math.pi / 8)
    assert not inside.any()


def test_a_cylinder_along_z_keeps_its_volume_and_conducts_axially():
    cyl = Cylinder(origin=m(0.1, 0.2, 0.0), axis="z", length=m(0.09), outer_diameter=m(0.05), inner_diameter=m(0.02))
    grid = cylinder_grid(cyl, 0.03)
    assert grid.shape[0] == 3 and grid.shape[1] >= 2
    assert grid.volumes.sum() == pytest.approx(math.pi / 4 * (0.05**2 - 0.02**2) * 0.09, rel=1e-12)
    assert grid.locate(np.array([[0.1, 0.2 + 0.024, 0.085]]))[0] == 2 * grid.shape[1] + grid.shape[1] - 1


# ------------------------------------------------------------------------------ face samples
def test_face_samples_add_up_to_the_faces():
    part = Part(material="steel", boxes=[Box(origin=m(0, -0.05, -0.05), size=m(0.04, 0.1, 0.1))],
                holes=[Cylinder(origin=m(0, 0, 0), length=m(0.04), outer_diameter=m(0.06))])
    cells = part_cells("p", part, 50.0, 0.02, 0)
    s = part_samples(cells, 0.02)
    face = s.face.astype(str)
    assert s.areas[face == "+z"].sum() == pytest.approx(0.04 * 0.1, rel=1e-12)
    assert s.areas[face == "+x"].sum() == pytest.approx(0.1 * 0.1 - math.pi / 4 * 0.06**2, rel=0.01)
    assert s.areas[face == "bore"].sum() == pytest.approx(math.pi * 0.06 * 0.04, rel=1e-12)
    ring = Part(material="steel", cylinders=[Cylinder(origin=m(0, 0, 0), axis="y", length=m(0.03),
                                                      outer_diameter=m(0.08), inner_diameter=m(0.05))])
    s = part_samples(part_cells("r", ring, 50.0, 0.02, 0), 0.02)
    face = s.face.astype(str)
    assert s.areas[face == "lateral"].sum() == pytest.approx(math.pi * 0.08 * 0.03, rel=1e-12)
    assert s.areas[face == "+y"].sum() == pytest.approx(math.pi / 4 * (0.08**2 - 0.05**2), rel=1e-12)


def test_spreading_a_patch_over_axial_cells_keeps_its_length():
    edges = np.linspace(0.0, 0.1, 11)
    patch, cell, frac = spread_along(edges, np.array([0.0345, 0.05]), np.array([0.021, 0.0]))
    assert np.bincount(patch, weights=frac) == pytest.approx([1.0, 1.0])
    assert set(cell[patch == 0]) == {2, 3, 4}


def test_a_patch_wider_than_the_cells_beside_a_narrow_one_stays_in_range():
    """Found by the description fuzzer: a 60 m carriage on a rail of 10 cells indexed past the last
    edge.  The wide patch keeps the share that lies over the cells: 0.1 m of its 60 m."""
    edges = np.linspace(0.0, 0.1, 11)
    patch, cell, frac = spread_along(edges, np.array([0.05, 0.05]), np.array([60.0, 0.01]))
    assert cell.max() <= 9
    assert np.bincount(patch, weights=frac) == pytest.approx([0.1 / 60.0, 1.0])
    assert set(cell[patch == 0]) == set(range(10))


def test_contact_conductance_is_area_over_resistance_in_series_with_the_sides():
    a, b, g = aggregate([0, 0, 1], [5, 5, 5], np.array([1.0, 3.0, 2.0]), np.zeros(3), np.full(3, 0.5), 0.5)
    assert list(zip(a, b)) == [(0, 5), (1, 5)]
    assert g == pytest.approx([4.0 / 1.0, 2.0 / 1.0])


# ------------------------------------------------------------------------------ the paper bench
def test_capacity_of_every_part_is_rho_c_v(paper, fast):
    for name, part in paper.parts.items():
        material = paper.materials[part.material]
        nodes = fast.layout.part_nodes(name)
        assert fast.capacity[nodes].sum() == pytest.approx(material.density * material.specific_heat * part_volume(part),
                                                           rel=1e-9), name


@pytest.mark.parametrize("k", [0, 17, 40])
def test_conductances_are_symmetric_and_conserve_heat(fast, k):
    G = fast.conductance(k)
    scale = abs(G).max()
    assert abs(G - G.T).max() < 1e-12 * scale
    np.testing.assert_allclose(G @ np.ones(fast.n_nodes), 0.0, atol=1e-11 * scale)
    assert (G.diagonal() > 0).all()  # every node conducts to something


def test_joint_contacts_are_the_geometric_overlaps(paper, fast):
    """Hand counts: the declared areas are the geometric overlaps, except the nut's bore
    (pi x 32 x 87 mm, longer than the 60 mm of engaged thread) and the belt's wraps."""
    for contact in fast.network.contacts:
        joint = contact.joint
        area = contact.geometric_area(20)
        if set(joint.between) == {"nut", "screw"}:
            assert area == pytest.approx(math.pi * 0.032 * 0.087, rel=0.01)
        elif "belt" not in joint.between:
            assert area == pytest.approx(joint.area, rel=0.01), joint.between


def test_exposed_area_of_the_front_housing_is_the_hand_count(paper, fast):
    """Faces +-x, +-y, +z of both boxes, less what is fused or covered (mm^2):
    housing 60x110x95 with a 62 mm bore: +x 110*95 - pi*31^2; -x the same less the bracket's
    end 80*30; +-y 2*60*95; +z 60*110. Bracket 190x80x30: +x fused; -x 80*30; +-y 2*190*30;
    +z 190*80 less the motor's footprint 120*60."""
    bore = math.pi * 31**2
    housing = (110 * 95 - bore) + (110 * 95 - bore - 80 * 30) + 2 * 60 * 95 + 60 * 110
    bracket = 80 * 30 + 2 * 190 * 30 + (190 * 80 - 120 * 60)
    nodes, areas = fast.surface_exposure("front_housing", 0)
    assert areas.sum() == pytest.approx((housing + bracket) * 1e-6, rel=0.01)
    assert np.isin(nodes, fast.layout.part_nodes("front_housing")).all()


def test_a_declared_area_is_kept(paper, fast):
    for name in ("base_top", "worktable_bottom"):
        assert fast.surface_exposure(name, 7)[1].sum() == pytest.approx(paper.surfaces[name].area, rel=1e-12)


def test_what_rides_on_the_screw_and_the_rails_covers_them(paper, fast):
    """Rails: faces +z, +-y of 2 x 800 mm (20 wide, 18 high) less the four carriages' bottoms
    on the rail tops, 60 x 20 mm each, wherever the group is. A declared area on the screw
    (the ball-screw example's) is spread over the exposed cells, not reduced again."""
    for k in (0, 13, 40):
        areas = fast.surface_exposure("guideways", k)[1]
        assert areas.sum() == pytest.approx(2 * 800 * (20 + 2 * 18) * 1e-6 - 4 * 60 * 20 * 1e-6, rel=1e-9)
    example = load_system("ballscrew_example").system
    model = discretize(example, "fast", ModelOptions())
    nodes, areas = model.surface_exposure("screw_shaft", 5)
    assert areas.sum() == pytest.approx(example.surfaces["screw_shaft"].area, rel=1e-12)
    screw = model.layout.screw
    under_nut = screw.nodes[screw.cell_at(0.300 + model.positions[5]), -1]
    assert areas[list(nodes).index(under_nut)] == 0.0


def test_heat_enters_where_it_arises(paper, fast):
    bc = boundary_conditions(paper, "I")
    nut, screw = fast.layout.part_nodes("nut"), fast.layout.part_nodes("screw")
    half = bc.heats["screw_nut"].power * 0.5
    for k in (0, 20, 40):
        q = fast.heat_vector(bc, k)
        assert q.sum() == pytest.approx(bc.total_heat, rel=1e-12)
        assert q[screw].sum() == pytest.approx(half, rel=1e-12)
        # the nut's half enters its bore: the sleeve's inner rings, nothing into the flange
        sleeve = fast.layout.cells["nut"].grids[0]
        inner = fast.layout.cells["nut"].first[0] + np.arange(sleeve.size).reshape(sleeve.shape)[:, 0]
        assert q[nut].sum() == pytest.approx(half, rel=1e-12) and q[inner].sum() == pytest.approx(half, rel=1e-12)
        # a motor's loss by volume over its cells
        motor = fast.layout.cells["screw_motor"]
        np.testing.assert_allclose(q[motor.nodes], bc.heats["screw_motor"].power * motor.volumes / motor.volumes.sum())


def test_sensors_read_their_spot(paper, fast):
    # a uniform field reads the same everywhere; the laser's loop (base, front housing and
    # bearing, screw) is steel at one alpha, so a uniform rise scales it about any point:
    # D = alpha dT (x_target - x_mount) = 1.2e-5 (450 - 480) mm dT (test_bars.py for the chain)
    T = np.full(fast.n_nodes, 310.0)
    values = dict(zip(fast.probe_names, fast.probe(T)))
    assert all(values[n] == pytest.approx(310.0) for n in ["T1", "T2", "T3", "T4", "T5"])
    assert values["D"] == pytest.approx(1.2e-5 * -0.030 * (310.0 - 293.15), rel=1e-9)
    # a field linear in x and y reads its value at the sensor (T5 on the worktable: no holes)
    table = fast.layout.cells["worktable"]
    points = table.node_points()
    T = np.zeros(fast.n_nodes)
    T[table.nodes] = 300.0 + 20.0 * points[:, 0] - 7.0 * points[:, 1]
    x, y, _ = paper.sensors["T5"].position
    assert dict(zip(fast.probe_names, fast.probe(T)))["T5"] == pytest.approx(300.0 + 20.0 * x - 7.0 * y, abs=1e-9)


def test_parts_that_do_not_touch_are_joined_at_their_nearest_cells():
    text = bench("paper").description.read_text(encoding="utf-8")
    data = tomllib.loads(text)
    data["parts"]["screw_motor"]["boxes"][0]["origin"][2] = "-25 mm"  # lifted 5 mm off its bracket
    system = validate_data(data, "variant").system
    model = discretize(system, "fast", ModelOptions())
    index = next(i for i, j in enumerate(system.joints) if set(j.between) == {"screw_motor", "front_housing"})
    contact = model.network.contacts[index]
    a, b, g = contact.links(0)
    assert contact.geometric_area(0) == 0.0 and len(g) == 1
    assert g[0] == pytest.approx(system.joints[index].area / system.joints[index].tcr)
    motor, housing = model.layout.part_nodes("screw_motor"), model.layout.part_nodes("front_housing")
    assert {a[0], b[0]} <= set(motor) | set(housing) and (a[0] in motor) != (b[0] in motor)
    G = model.conductance(0)
    np.testing.assert_allclose(G @ np.ones(model.n_nodes), 0.0, atol=1e-11 * abs(G).max())
