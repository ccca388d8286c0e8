"""Unit tests of the bench model's pieces: facets, faces, the non-conforming contact, readout, gmsh."""

import numpy as np
import pytest
import scipy.sparse as sp
from scipy.sparse.linalg import spsolve
from skfem import MeshTet

from feedtherm.models.fem.conduction import cell_basis, conduction_matrix
from feedtherm.models.fem.coupling import Contact, interface_matrix, side_load
from feedtherm.models.fem.faces import curvature_sag, surface_facets
from feedtherm.models.fem.facets import RULE, NearestFacets, boundary_triangles, closest_points
from feedtherm.models.fem.geometry import mesh_size, mesh_system
from feedtherm.models.fem.readout import (
    point_matrix,
    refined_centroids,
    slab_matrix,
    tet_volumes,
)
from feedtherm.system.schema import Box, Cylinder, Part
from feedtherm.system.surfaces import Surface


def _box_mesh(x, y, z):
    m = MeshTet.init_tensor(np.asarray(x, float), np.asarray(y, float), np.asarray(z, float))
    return m.p, m.t


def test_quadrature_rule_integrates_quadratics_exactly():
    bary, w = RULE
    assert w.sum() == pytest.approx(1.0) and (w > 0).all()
    # on the reference triangle (area 1/2): ∫λ_i = 1/6, ∫λ_i² = 1/12, ∫λ_iλ_j = 1/24
    assert 0.5 * (w @ bary[:, 0]) == pytest.approx(1 / 6)
    assert 0.5 * (w @ bary[:, 0] ** 2) == pytest.approx(1 / 12)
    assert 0.5 * (w @ (bary[:, 0] * bary[:, 1])) == pytest.approx(1 / 24)


def test_closest_points_match_a_brute_force_search():
    rng = np.random.default_rng(1)
    a, b, c = rng.normal(size=(3, 200, 3))
    p = 2 * rng.normal(size=(200, 3))
    d, bary = closest_points(p, a, b, c)
    assert np.allclose(bary.sum(axis=1), 1.0) and (bary > -1e-12).all()
    s = np.linspace(0, 1, 201)
    u, v = np.meshgrid(s, s)
    keep = u + v <= 1
    u, v = u[keep], v[keep]
    for i in range(0, 200, 20):
        pts = a[i] + u[:, None] * (b[i] - a[i]) + v[:, None] * (c[i] - a[i])
        brute = np.linalg.norm(pts - p[i], axis=1).min()
        assert d[i] <= brute + 1e-12 and d[i] == pytest.approx(brute, abs=2e-2 * max(1.0, brute))


def test_boundary_triangles_of_a_box_are_its_faces_with_outward_normals():
    p, t = _box_mesh(np.linspace(0, 0.3, 4), np.linspace(0, 0.2, 3), np.linspace(0, 0.1, 2))
    tri = boundary_triangles(p, t)
    assert tri.areas.sum() == pytest.approx(2 * (0.3 * 0.2 + 0.3 * 0.1 + 0.2 * 0.1))
    centroid = p[:, tri.nodes].mean(axis=1)
    outward = np.einsum("ij,ij->j", tri.normals, centroid - np.array([[0.15], [0.1], [0.05]]))
    assert (outward > 0).all()
    # a surface integral of the normal over a closed surface vanishes
    np.testing.assert_allclose((tri.normals * tri.areas).sum(axis=1), 0.0, atol=1e-15)


def test_the_facets_bounds_drop_only_candidates_the_closest_point_test_refuses(monkeypatch):
    """NearestFacets.query takes a candidate to the closest-point test only within the facet's plane
    gap and radius: every answer is the one of the test applied to all 16 candidates, bit for bit.

    A block's facets against the quadrature points of a second, differently meshed block that
    slides along x (a sliding contact's queries), of a tilted copy, and points scattered near
    the face: hits, misses past the face's rim, misses across the gap."""
    pa, ta = _box_mesh(np.linspace(0.0, 0.01, 4), np.linspace(0, 0.01, 4), np.linspace(0, 0.01, 3))
    pb, tb = _box_mesh(np.linspace(0.01, 0.03, 6), np.linspace(0, 0.01, 5), np.linspace(0, 0.01, 6))
    points = np.hstack([pa, pb])
    tri_a, tri_b = boundary_triangles(points, ta), boundary_triangles(points, tb + pa.shape[1])
    facets = NearestFacets(points, tri_b)
    x, _, owner = tri_a.quadrature(points, level=2)
    normals = tri_a.normals[:, owner]
    rng = np.random.default_rng(3)
    scattered = np.array([[0.01], [0.005], [0.005]]) + rng.uniform(-1, 1, (3, 4000)) * [[3e-4], [7e-3], [7e-3]]
    tilt = np.array([[1.0, 0.0, 0.0], [0.0, np.cos(0.02), -np.sin(0.02)], [0.0, np.sin(0.02), np.cos(0.02)]])
    queries = [(x + [[shift], [0.0], [0.0]], normals) for shift in (0.0, 1e-4, -2e-3, 4e-3)]
    queries += [(tilt @ x, tilt @ normals), (scattered, np.tile([[1.0], [0.0], [0.0]], (1, 4000)))]
    bounded = [facets.query(q, n, 1e-4, 5e-4) for q, n in queries]
    monkeypatch.setattr(NearestFacets, "_within_bounds", lambda self, x, cand, point, normals, tol, tangential:
                        (cand, point, normals))
    for (q, n), (facet, bary, dist) in zip(queries, bounded):
        every_facet, every_bary, every_dist = facets.query(q, n, 1e-4, 5e-4)
        hit = every_facet >= 0
        np.testing.assert_array_equal(facet, every_facet)
        np.testing.assert_array_equal(dist, every_dist)
        np.testing.assert_array_equal(bary[hit], every_bary[hit])
        assert not bary[~hit].any()
    hits = [int((facet >= 0).sum()) for facet, _, _ in bounded]
    assert hits[0] > 500 and 0 < hits[-1] < 4000  # contacts found, and points missing the face


@pytest.mark.parametrize("lumped", [True, False])
@pytest.mark.parametrize("matching, rtol, spread", [(True, 1e-9, 1e-9), (False, 1e-4, 2e-3)])
def test_non_conforming_contact_gives_the_jump_q_times_r(lumped, matching, rtol, spread):
    """Two blocks meshed on their own: ΔT = q''·R'' across the contact, heat out of a = heat into b.

    With facets that match one for one the quadrature is exact and so is the jump; with
    different triangulations ∫N_B over a's facets is a quadrature, not exact: the jump is off by
    2e-5 and the nodes of b's face spread by 0.15 % of it here.
    """
    pa, ta = _box_mesh(np.linspace(0.0, 0.01, 4), np.linspace(0, 0.01, 4), np.linspace(0, 0.01, 3))
    if matching:
        pb, tb = _box_mesh(np.linspace(0.01, 0.03, 6), np.linspace(0, 0.01, 4), np.linspace(0, 0.01, 3))
    else:
        pb, tb = _box_mesh(np.linspace(0.01, 0.03, 6), np.linspace(0, 0.01, 5), np.linspace(0, 0.01, 6))
    points = np.hstack([pa, pb])
    tets = np.hstack([ta, tb + pa.shape[1]])
    n = points.shape[1]
    tri_a, tri_b = boundary_triangles(points, ta), boundary_triangles(points, tets[:, ta.shape[1]:])
    # b's facets are smaller than a's: one more level of the rule on a's facets (as the bench does)
    contact = Contact(points, tri_a, tri_b, tol=1e-4, name="a-b", level=1 if matching else 2)
    cq = contact.quadrature()
    assert cq.area == pytest.approx(1e-4, rel=1e-12)
    R = 2e-4  # m²·K/W
    K = interface_matrix(n, cq, 1.0 / R, lumped=lumped)
    np.testing.assert_allclose(K @ np.ones(n), 0.0, atol=1e-12)
    assert abs(K - K.T).max() < 1e-12
    if lumped:
        off = K - sp.diags(K.diagonal())
        assert off.max() <= 1e-15  # an M-matrix
    k = np.full(tets.shape[1], 50.0)
    G = conduction_matrix(cell_basis(MeshTet(points, tets)), k) + K
    # heat q'' = 1e5 W/m² into the face x = 0 of block a, T = 0 on the face x = 0.03 of block b
    left = tri_a.subset(np.abs(tri_a.normals[0] + 1) < 1e-9)
    q = 1e5 * np.bincount(left.nodes.ravel(), weights=np.tile(left.areas / 3, 3), minlength=n)
    fixed = np.nonzero(np.abs(points[0] - 0.03) < 1e-12)[0]
    fixed = fixed[fixed >= pa.shape[1]]
    free = np.setdiff1d(np.arange(n), fixed)  # T = 0 on the fixed nodes
    T = np.zeros(n)
    T[free] = spsolve(G.tocsr()[free][:, free], q[free])
    on_a = np.nonzero(np.abs(points[0, : pa.shape[1]] - 0.01) < 1e-12)[0]
    on_b = pa.shape[1] + np.nonzero(np.abs(pb[0] - 0.01) < 1e-12)[0]
    jump = T[on_a].mean() - T[on_b].mean()
    assert jump == pytest.approx(1e5 * R, rel=rtol)
    # one-dimensional, as it must be (to the quadrature's error with different triangulations)
    assert np.ptp(T[on_a]) < spread * jump and np.ptp(T[on_b]) < spread * jump
    # the heat leaving a through the contact equals the heat entering b
    flow = K @ T
    assert flow[: pa.shape[1]].sum() == pytest.approx(-flow[pa.shape[1]:].sum(), rel=1e-12)
    assert flow[: pa.shape[1]].sum() == pytest.approx(1e5 * 1e-4, rel=1e-9)


def test_contact_load_puts_the_heat_on_each_side_of_the_contact():
    pa, ta = _box_mesh(np.linspace(0, 0.01, 3), np.linspace(0, 0.01, 3), np.linspace(0, 0.01, 3))
    pb, tb = _box_mesh(np.linspace(0.01, 0.02, 4), np.linspace(-0.01, 0.02, 7), np.linspace(0, 0.01, 4))
    points = np.hstack([pa, pb])
    n = points.shape[1]
    tri_a = boundary_triangles(points, ta)
    tri_b = boundary_triangles(points, tb + pa.shape[1])
    cq = Contact(points, tri_a, tri_b, tol=1e-4).quadrature()
    assert cq.area == pytest.approx(1e-4, rel=1e-12)  # only the part of b's face a covers
    for side, lo, hi in (("a", 0, pa.shape[1]), ("b", pa.shape[1], n)):
        share = side_load(n, cq, side)
        assert share.sum() == pytest.approx(1.0) and share[lo:hi].sum() == pytest.approx(1.0)
        loaded = np.nonzero(share)[0]
        assert np.allclose(points[0, loaded], 0.01)
    # shifted by 15 mm along x the blocks are apart: no contact
    with pytest.raises(Exception, match="do not touch"):
        Contact(points, tri_a, tri_b, tol=1e-4, name="a-b").quadrature(shift=-0.015)


def test_refined_centroids_are_an_equal_volume_rule():
    lam = refined_centroids(2)
    assert lam.shape == (64, 4)
    np.testing.assert_allclose(lam.mean(axis=0), 0.25)
    # ∫λ_i² over a tetrahedron is V/10; a midpoint rule on 64 pieces gives 0.0972
    assert (lam[:, 0] ** 2).mean() == pytest.approx(0.1, rel=0.03)


def test_slab_means_and_probes_of_a_linear_field():
    p, t = _box_mesh(np.linspace(0, 0.1, 11), np.linspace(0, 0.02, 3), np.linspace(0, 0.02, 3))
    n = p.shape[1]
    T = 300.0 + 100.0 * p[0] + 20.0 * p[2]
    edges = np.linspace(0, 0.1, 6)  # slabs of 20 mm: planes of the grid
    W = slab_matrix(p, t, edges, n)
    centres = 0.5 * (edges[1:] + edges[:-1])
    np.testing.assert_allclose(W @ T, 300.0 + 100.0 * centres + 20.0 * 0.01, rtol=1e-12)
    assert tet_volumes(p, t).sum() == pytest.approx(0.1 * 0.02 * 0.02)
    P = point_matrix(p, t, [np.array([0.033, 0.007, 0.011])], n)
    assert (P @ T)[0] == pytest.approx(300.0 + 3.3 + 0.22)


def test_gmsh_meshes_a_tube_and_a_box_with_a_bore(tmp_path, monkeypatch):
    pytest.importorskip("gmsh")
    from feedtherm.system.load import load_system

    monkeypatch.setenv("FEEDTHERM_CACHE", str(tmp_path))
    system = load_system("paper").system
    small = system.model_copy(update={"parts": {k: system.parts[k] for k in ("front_housing", "front_bearing")}})
    mesh = mesh_system(small, "coarse")
    assert not mesh.cached and mesh.path.exists()
    again = mesh_system(small, "coarse")
    assert again.cached and np.array_equal(again.tets, mesh.tets)
    bearing = mesh.part_tets("front_bearing")
    volume = tet_volumes(mesh.points, mesh.tets[:, bearing]).sum()
    exact = np.pi / 4 * (0.062**2 - 0.032**2) * 0.030
    assert volume == pytest.approx(exact, rel=0.03)  # faceted circles
    assert mesh_size(small, "front_bearing", "coarse") <= 0.015 / 1.5 + 1e-12
    # the bearing's lateral face and the housing's bore: chord heights, faces found
    part = small.parts["front_bearing"]
    tri = boundary_triangles(mesh.points, mesh.tets[:, bearing])
    lateral = surface_facets(Surface(part="front_bearing", faces=["lateral"], convection={"kind": "natural",
                             "orientation": "vertical_plate", "length": "30 mm"}, emissivity=0.5), part, mesh.points, tri)
    assert tri.areas[lateral].sum() == pytest.approx(np.pi * 0.062 * 0.030, rel=0.02)
    assert 0 < curvature_sag(part, mesh.points, tri) < 2e-3
    housing = small.parts["front_housing"]
    tri_h = boundary_triangles(mesh.points, mesh.tets[:, mesh.part_tets("front_housing")])
    bore = surface_facets(Surface(part="front_housing", faces=["bore"], boxes=[0], convection={"kind": "natural",
                          "orientation": "vertical_plate", "length": "30 mm"}, emissivity=0.5), housing, mesh.points, tri_h)
    assert tri_h.areas[bore].sum() == pytest.approx(np.pi * 0.062 * 0.060, rel=0.02)


def test_face_selectors_of_boxes_and_cylinders():
    p, t = _box_mesh(np.linspace(0, 0.3, 4), np.linspace(0, 0.2, 3), np.linspace(0, 0.1, 2))
    tri = boundary_triangles(p, t)
    part = Part(material="m", boxes=[Box(origin=("0 m", "0 m", "0 m"), size=("0.3 m", "0.2 m", "0.1 m"))])
    conv = {"kind": "natural", "orientation": "vertical_plate", "length": "0.1 m"}
    for faces, area in ((["+z"], 0.06), (["+x", "-x"], 0.04), (["+y", "-y", "-z"], 0.12)):
        mask = surface_facets(Surface(part="p", faces=faces, convection=conv, emissivity=0.5), part, p, tri)
        assert tri.areas[mask].sum() == pytest.approx(area)
    rod = Part(material="m", cylinders=[Cylinder(origin=("0 m", "0 m", "0 m"), length="0.1 m", outer_diameter="20 mm")])
    with pytest.raises(Exception, match="does not exist on a cylinder"):
        surface_facets(Surface(part="p", faces=["+y"], convection=conv, emissivity=0.5), rod, p, tri)


def test_a_face_shared_by_two_coplanar_boxes_keeps_its_whole_area():
    # One block described as two boxes that meet at x = 0.15 m; the mesh's nodes sit at
    # x = 0, 0.1, 0.2, 0.3, so the top facets between 0.1 and 0.2 straddle the boxes' edge.
    # Every facet goes to the box that holds its centroid: the two tops add up to the
    # block's top, and each box's top alone is half of it to within one element.
    p, t = _box_mesh(np.linspace(0, 0.3, 4), np.linspace(0, 0.2, 3), np.linspace(0, 0.1, 2))
    tri = boundary_triangles(p, t)
    part = Part(material="m", boxes=[Box(origin=("0 m", "0 m", "0 m"), size=("0.15 m", "0.2 m", "0.1 m")),
                                     Box(origin=("0.15 m", "0 m", "0 m"), size=("0.15 m", "0.2 m", "0.1 m"))])
    conv = {"kind": "natural", "orientation": "horizontal_plate_up", "length": "0.1 m"}
    both = surface_facets(Surface(part="p", faces=["+z"], convection=conv, emissivity=0.5), part, p, tri)
    assert tri.areas[both].sum() == pytest.approx(0.3 * 0.2)
    first = surface_facets(Surface(part="p", faces=["+z"], boxes=[0], convection=conv, emissivity=0.5), part, p, tri)
    second = surface_facets(Surface(part="p", faces=["+z"], boxes=[1], convection=conv, emissivity=0.5), part, p, tri)
    assert not (first & second).any()
    assert tri.areas[first].sum() == pytest.approx(0.03, abs=0.1 * 0.2 / 2)
