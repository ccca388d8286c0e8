"""A bar free to expand under a uniform rise: case ``cases/free_bar.toml``, both models.

Steel bar L = 100 mm, α = 1.2e-5 1/K, held 3-2-1 at x = 0, everything at 70 °C against a
reference of 20 °C (ΔT = 50 K, no heat). Free thermal expansion strains it without stress,
u = α ΔT (p − p_A) from the held point p_A = (0, 0, 10 mm), so the sensor at the centre of the
free end face on the ground reads

    D = α L ΔT = 1.2e-5 · 0.1 m · 50 K = 6.0e-5 m (60 µm),

and the screw's axial displacement relative to the positioning reference (the held point) is
α ΔT x: at the table positions (the nut's centre, 45…55 mm) 6e-4 · (0.045 … 0.055) m = 2.7e-5 … 3.3e-5 m.

The field is linear, so linear elements hold it exactly: the FE model's D is exact to round-off
at any density (required: 1e-6), every node's displacement is the expansion plus the rigid
motion the supports leave (the support points that are not mesh nodes turn the bar about x,
without strain), and the fast model's bars integrate a uniform rise exactly.
"""

import numpy as np
import pytest
from fem_cases import load_case

from feedtherm.simulate import simulate
from feedtherm.system.variants import with_values

ALPHA, L, DT = 1.2e-5, 0.100, 70.0 - 20.0
D_EXACT = ALPHA * L * DT
HELD = np.array([0.0, 0.0, 0.010])  # the x, y, z support: the seam vertex of the end circle


def rigid_residual(points: np.ndarray, u: np.ndarray) -> float:
    """Largest nodal displacement left after the best rigid motion t + ω × p is taken off [m]."""
    A = np.zeros((3 * len(points), 6))
    for k in range(3):
        A[k::3, k] = 1.0
    x, y, z = points.T
    A[0::3, 4], A[0::3, 5] = z, -y  # ω × p, x: ω_y z − ω_z y
    A[1::3, 3], A[1::3, 5] = -z, x  # y: ω_z x − ω_x z
    A[2::3, 3], A[2::3, 4] = y, -x  # z: ω_x y − ω_y x
    coef, *_ = np.linalg.lstsq(A, u.ravel(), rcond=None)
    return float(np.abs(u.ravel() - A @ coef).max())


@pytest.mark.parametrize("mesh", ["coarse", "medium"])
def test_fe_free_expansion_is_exact(mesh):
    run = simulate(load_case("free_bar"), condition="warm", model="fem", mesh=mesh)
    assert run.final["D"] == pytest.approx(D_EXACT, rel=1e-6)
    np.testing.assert_allclose(run.elongation, D_EXACT, rtol=1e-6)
    fields = run.fields
    u = fields.displacements[-1]
    assert rigid_residual(fields.points, u - ALPHA * DT * (fields.points - HELD)) < 1e-9 * D_EXACT
    # the positioning error: the screw's section-mean displacement under the nut's centre less the
    # reference's. The section means are volume quadratures over axial slabs whose edges they
    # resolve to a quarter of an element (readout.slab_matrix: 64 sub-tetrahedra each), so they are
    # exact only to α ΔT times that; measured 4e-5 (coarse) and 4e-5 (medium) of D.
    assert np.max(np.abs(run.positioning_error[-1] - ALPHA * DT * run.table_x)) < 1e-4 * D_EXACT


def test_fast_free_expansion_is_exact():
    run = simulate(load_case("free_bar"), condition="warm", model="fast")
    assert run.final["D"] == pytest.approx(D_EXACT, rel=1e-6)
    np.testing.assert_allclose(run.screw_displacement[-1], ALPHA * DT * run.screw_x, rtol=1e-9, atol=1e-9 * D_EXACT)
    np.testing.assert_allclose(run.positioning_error[-1], ALPHA * DT * run.table_x, rtol=1e-9)
    assert run.positioning_error[-1][[0, -1]] == pytest.approx([2.7e-5, 3.3e-5], rel=1e-9)


def test_fe_free_expansion_with_the_ring_tied_across():
    # the case as a ball nut would be drawn: the joint centres the ring on the bar (ties y, z)
    # instead of the ring's own supports; a uniform expansion still leaves both parts unstrained,
    # which a tie passes only if it reads both sides' fields at the same points (the patch test:
    # pairing each point with the closest point of the other faceted cylinder, a chord's height
    # away, put D off by 1.4e-4 on the coarse mesh)
    loaded = load_case("free_bar")
    tied = with_values(loaded, {"joints[0].release": ["x"],
                                "mechanics.supports": list(loaded.system.mechanics.supports[:3])})
    run = simulate(tied, condition="warm", model="fem", mesh="coarse")
    assert run.final["D"] == pytest.approx(D_EXACT, rel=1e-6)


def test_quadratic_elements_expand_freely_with_the_ring_tied_across():
    # the 10-node tetrahedra hold a linear field too, and their ties and drive read the quadratic
    # field at the same points on both sides: still no jump, still exact
    loaded = load_case("free_bar")
    tied = with_values(loaded, {"mechanics.elements": "quadratic", "joints[0].release": ["x"],
                                "mechanics.supports": list(loaded.system.mechanics.supports[:3])})
    run = simulate(tied, condition="warm", model="fem", mesh="coarse")
    assert run.info["mesh_statistics"]["elastic_elements"] == "quadratic"
    assert run.final["D"] == pytest.approx(D_EXACT, rel=1e-6)
    fields = run.fields
    u = fields.displacements[-1]
    assert rigid_residual(fields.points, u - ALPHA * DT * (fields.points - HELD)) < 1e-9 * D_EXACT
