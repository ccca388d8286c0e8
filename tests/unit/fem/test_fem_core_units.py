"""Unit tests of the FE core: topology, layers, assembly, interfaces, fields."""

import numpy as np
import pytest
import scipy.sparse as sp

from feedtherm.models.fem.fields import probe, section_means
from feedtherm.models.fem.heat import (
    HeatOperator,
    ThetaStepper,
    capacity_matrix,
    cell_basis,
    conduction_matrix,
    facet_mass_matrix,
    solve_steady,
)
from feedtherm.models.fem.interfaces import SlidingInterface, contact
from feedtherm.models.fem.layers import layered_surface
from feedtherm.models.fem.meshes import bar, box, rod_and_slider, two_blocks
from feedtherm.models.fem.topology import element_volumes, facet_areas, join, part_facets, split_nodes


def test_split_nodes_duplicates_only_the_interface():
    mesh = box(np.linspace(0, 0.02, 5), np.linspace(0, 0.01, 3), np.linspace(0, 0.01, 3))
    right = np.nonzero(mesh.p[0, mesh.t].mean(axis=0) > 0.01)[0]
    split, copies = split_nodes(mesh, right)
    assert copies.shape == (2, 9)  # the 3 × 3 nodes of the plane x = 0.01
    np.testing.assert_allclose(split.p[:, copies[0]], split.p[:, copies[1]])
    assert split.nvertices == mesh.nvertices + 9
    np.testing.assert_allclose(element_volumes(split).sum(), 0.02 * 0.01 * 0.01)
    # the plane is now two sets of boundary facets, one per side
    at_plane = lambda m: np.abs(m[0] - 0.01) < 1e-12  # noqa: E731
    left = np.setdiff1d(np.arange(mesh.nelements), right)
    a, b = part_facets(split, left, at_plane), part_facets(split, right, at_plane)
    assert a.size == b.size == 8
    np.testing.assert_allclose(facet_areas(split, a).sum(), 1e-4)


def test_join_keeps_coincident_nodes_apart():
    one = bar(0.01, 0.01, 0.01, 1)
    two = box([0.01, 0.02], [0, 0.01], [0, 0.01])
    mesh, (ea, eb) = join([one, two])
    assert mesh.nvertices == one.nvertices + two.nvertices
    assert ea.size == one.nelements and eb.size == two.nelements


def test_capacity_conduction_and_facet_mass_totals():
    mesh = bar(0.1, 0.02, 0.01, 10, 2, 1)
    basis = cell_basis(mesh)
    for lumped in (False, True):
        C = capacity_matrix(basis, 3.6e6, lumped=lumped)
        assert C.sum() == pytest.approx(3.6e6 * 0.1 * 0.02 * 0.01, rel=1e-12)
        M = facet_mass_matrix(mesh, mesh.boundaries["y0"], 7.0, lumped=lumped)
        assert M.sum() == pytest.approx(7.0 * 0.1 * 0.01, rel=1e-12)
    G = conduction_matrix(basis, 45.0)
    np.testing.assert_allclose(G @ np.ones(mesh.nvertices), 0.0, atol=1e-9)
    # a linear field carries the flux k·A·dT/dx: check it on the x = 0 nodes' reactions
    T = 100.0 * mesh.p[0]
    assert -(G @ T)[mesh.p[0] < 1e-12].sum() == pytest.approx(45.0 * 0.02 * 0.01 * 100.0, rel=1e-12)


def test_per_element_values_must_have_the_right_length():
    basis = cell_basis(bar(0.1, 0.01, 0.01, 2))
    with pytest.raises(ValueError, match="one per element"):
        conduction_matrix(basis, np.ones(5))


def test_fixed_values_follow_the_callers_order():
    mesh = bar(0.1, 0.01, 0.01, 4)
    G = HeatOperator.conduction(conduction_matrix(cell_basis(mesh), 10.0))
    right = mesh.nodes_satisfying(lambda p: p[0] > 0.1 - 1e-12)
    left = mesh.nodes_satisfying(lambda p: p[0] < 1e-12)
    T = solve_steady(G, fixed=np.r_[right, left], fixed_values=np.r_[np.full(right.size, 50.0), np.zeros(left.size)])
    np.testing.assert_allclose(T, 500.0 * mesh.p[0], atol=1e-9)
    with pytest.raises(ValueError, match="fixed twice"):
        ThetaStepper(sp.identity(mesh.nvertices), fixed=np.r_[left, left])
    with pytest.raises(ValueError, match="theta"):
        ThetaStepper(sp.identity(mesh.nvertices), theta=0.3)


def test_layered_surface_grid_and_loads():
    geo = rod_and_slider(0.005, 12, 3, 0.01, 0.01)
    track = layered_surface(geo.mesh, geo.rod_top, axis=0, spacing=0.005)
    assert track.n_layers == 12 and track.grid.shape == (13, 3)  # 3 nodes across the top face
    np.testing.assert_allclose(geo.mesh.p[0, track.grid], np.repeat(np.arange(13)[:, None] * 0.005, 3, axis=1), atol=1e-15)
    np.testing.assert_allclose(track.layer_areas(), 0.005 * 0.01)
    assert track.load(range(2, 5), 1000.0).sum() == pytest.approx(1000.0 * 3 * 0.005 * 0.01)
    with pytest.raises(IndexError):
        track.load(range(11, 13), 1.0)
    with pytest.raises(ValueError, match="layer"):
        layered_surface(geo.mesh, geo.rod_top, axis=0, spacing=0.0075)


def test_sliding_interface_equals_a_fixed_contact_at_each_rest_position():
    for start in (0, 5):
        geo = rod_and_slider(0.005, 12, 3, 0.01, 0.01, slider_start=start)
        track = layered_surface(geo.mesh, geo.rod_top, 0, 0.005)
        face = layered_surface(geo.mesh, geo.slider_bottom, 0, 0.005)
        for lumped in (True, False):
            sliding = SlidingInterface(track, face, 1e-4, lumped=lumped)
            assert sliding.rest_position == start
            fixed = contact(geo.mesh, sliding.track_facets(start), geo.slider_bottom, 1e-4, lumped=lumped)
            assert abs(sliding.operator(start).conductance - fixed.conductance).max() < 1e-9 * abs(fixed.conductance).max()
            for s in range(sliding.n_positions):
                G = sliding.operator(s).conductance
                np.testing.assert_allclose(G @ np.ones(geo.mesh.nvertices), 0.0, atol=1e-9)  # conservative
                assert abs(G - G.T).max() < 1e-12 * abs(G).max()


def test_contact_lumped_and_consistent_carry_the_same_total_heat():
    blocks = two_blocks(0.01, 0.01, 0.01, 0.01, 2, 2, 2, 2)
    T = np.random.default_rng(1).normal(size=blocks.mesh.nvertices)
    from feedtherm.models.fem.interfaces import pair_nodes

    _, nodes_b = pair_nodes(blocks.mesh, blocks.interface_a, blocks.interface_b)
    flows = [(contact(blocks.mesh, blocks.interface_a, blocks.interface_b, 1e-3, lumped=lumped).conductance @ T)[nodes_b].sum() for lumped in (True, False)]
    assert flows[0] == pytest.approx(flows[1], rel=1e-12)


def test_section_means_and_probe_are_exact_for_linear_fields():
    mesh = bar(0.1, 0.02, 0.01, 10, 2, 2)
    T = 3.0 + 40.0 * mesh.p[0] + 7.0 * mesh.p[1]
    edges = np.linspace(0, 0.1, 6)
    np.testing.assert_allclose(section_means(mesh, T, 0, edges), 3.0 + 40.0 * (edges[:-1] + 0.01) + 7.0 * 0.01, rtol=1e-12)
    points = np.array([[0.033, 0.071], [0.004, 0.013], [0.002, 0.009]])
    np.testing.assert_allclose(probe(mesh, T, points), 3.0 + 40.0 * points[0] + 7.0 * points[1], rtol=1e-12)


def test_layer_mass_selection_equals_a_fresh_assembly():
    geo = rod_and_slider(0.005, 12, 3, 0.01, 0.01)
    track = layered_surface(geo.mesh, geo.rod_top, 0, 0.005)
    for lumped in (True, False):
        chosen = track.mass([1, 2, 7], lumped=lumped)
        fresh = facet_mass_matrix(geo.mesh, track.layer_facets([1, 2, 7]), lumped=lumped)
        assert abs(chosen - fresh).max() < 1e-12 * abs(fresh).max()
    op = track.convection(range(12), 10.0, 20.0)
    assert op.load.sum() == pytest.approx(10.0 * 20.0 * 0.06 * 0.01)
