"""The temperature jump across a thermal contact resistance between two blocks.

Block a (L1 = 20 mm, k1 = 50 W/(m·K)) and block b (L2 = 30 mm, k2 = 15 W/(m·K)) touch with
R'' = 1e-3 m²·K/W, their nodes on the common face duplicated (no merged nodes). The outer
faces are held at 100 °C and 0 °C, the sides insulated. In series:

    q = ΔT_total / (L1/k1 + R'' + L2/k2) = 100 / 3.4e-3 = 29 411.76 W/m²,
    jump = q·R'' = 29.41 K.

Linear elements hold the two linear profiles exactly, so the result is exact to round-off;
both the lumped and the consistent facet mass matrix are checked.
"""

import time

import numpy as np
import pytest

from feedtherm.models.fem.heat import HeatOperator, cell_basis, conduction_matrix, solve_steady
from feedtherm.models.fem.interfaces import contact, jump_heat_flow, pair_nodes
from feedtherm.models.fem.meshes import two_blocks

L1, L2, K1, K2, R = 0.02, 0.03, 50.0, 15.0, 1e-3
W = 0.01


@pytest.mark.parametrize("lumped", [True, False])
def test_jump_equals_flux_times_resistance(lumped):
    start = time.perf_counter()
    blocks = two_blocks(L1, L2, W, W, 4, 6, 2, 2)
    mesh = blocks.mesh
    k = np.where(np.isin(np.arange(mesh.nelements), blocks.elements_a), K1, K2)
    operator = HeatOperator.conduction(conduction_matrix(cell_basis(mesh), k)) + contact(mesh, blocks.interface_a, blocks.interface_b, R, lumped=lumped)
    hot = np.unique(mesh.facets[:, blocks.outer_a])
    cold = np.unique(mesh.facets[:, blocks.outer_b])
    T = solve_steady(operator, fixed=np.r_[hot, cold], fixed_values=np.r_[np.full(hot.size, 100.0), np.zeros(cold.size)])

    q = 100.0 / (L1 / K1 + R + L2 / K2)
    nodes_a, nodes_b = pair_nodes(mesh, blocks.interface_a, blocks.interface_b)
    jump = T[nodes_a] - T[nodes_b]
    flow = jump_heat_flow(mesh, blocks.interface_a, nodes_a, nodes_b, T, R)
    print(f"contact ({'lumped' if lumped else 'consistent'}): jump {jump.mean():.6f} K vs q·R'' = {q * R:.6f} K, "
          f"flux {flow / W**2:.3f} vs {q:.3f} W/m², {time.perf_counter() - start:.3f} s")
    np.testing.assert_allclose(jump, q * R, rtol=1e-9)
    np.testing.assert_allclose(T[nodes_a], 100.0 - q * L1 / K1, rtol=1e-9)
    np.testing.assert_allclose(flow, q * W * W, rtol=1e-9)


def test_mismatched_faces_are_refused():
    blocks = two_blocks(L1, L2, W, W, 4, 6, 2, 2)
    with pytest.raises(ValueError, match="do not match node for node"):
        contact(blocks.mesh, blocks.interface_a, blocks.outer_b, R)
