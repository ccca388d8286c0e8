"""Steady conduction with convection against analytic values.

1. A pin fin: square rod 10 × 10 mm, 0.1 m long, k = 200 W/(m·K), base held at 100 °C,
   convection h = 25 W/(m²·K) to 20 °C on the four sides and the tip. The 1D fin solution
   (Incropera, Fundamentals of Heat and Mass Transfer, Table 3.4, case A):

       θ(x)/θ_b = [cosh m(L-x) + (h/mk) sinh m(L-x)] / [cosh mL + (h/mk) sinh mL],
       q_f = √(hPkA)·θ_b·[sinh mL + (h/mk) cosh mL] / [cosh mL + (h/mk) sinh mL],
       m = √(hP/(kA)).

   Its Biot number h·(t/2)/k = 6e-4 makes the 1D solution an accurate reference for the 3D
   bar (the transverse temperature differences are of that relative order).
2. A wall with convection on one face and a fixed temperature on the other: q = ΔT/(L/k + 1/h),
   exact for linear elements (to round-off).
"""

import math
import time

import numpy as np

from feedtherm.models.fem.energy import convective_loss
from feedtherm.models.fem.fields import section_means
from feedtherm.models.fem.heat import HeatOperator, cell_basis, conduction_matrix, convection, solve_steady
from feedtherm.models.fem.meshes import bar
from feedtherm.models.fem.topology import part_facets

K, H, T_BASE, T_AIR = 200.0, 25.0, 100.0, 20.0
L, W = 0.1, 0.01


def fin_analytic(x):
    P, A = 4 * W, W * W
    m = math.sqrt(H * P / (K * A))
    r = H / (m * K)
    den = math.cosh(m * L) + r * math.sinh(m * L)
    theta = (np.cosh(m * (L - x)) + r * np.sinh(m * (L - x))) / den
    q = math.sqrt(H * P * K * A) * (T_BASE - T_AIR) * (math.sinh(m * L) + r * math.cosh(m * L)) / den
    return T_AIR + (T_BASE - T_AIR) * theta, q


def test_pin_fin_tip_temperature_and_heat_flow():
    start = time.perf_counter()
    nx = 20
    mesh = bar(L, W, W, nx, 2, 2)
    basis = cell_basis(mesh)
    cooled = part_facets(mesh, np.arange(mesh.nelements), lambda m: m[0] > 1e-9)  # all but the base
    operator = HeatOperator.conduction(conduction_matrix(basis, K)) + convection(mesh, cooled, H, T_AIR)
    base = mesh.nodes_satisfying(lambda p: p[0] < 1e-9)
    T = solve_steady(operator, fixed=base, fixed_values=T_BASE)
    tip_nodes = mesh.nodes_satisfying(lambda p: p[0] > L - 1e-9)
    tip = float(T[tip_nodes].mean())
    tip_exact, q_exact = fin_analytic(L)
    q = convective_loss(mesh, cooled, H, T_AIR, T)
    # the profile: slab means against the analytic slab means (5-point Gauss in each slab)
    edges = np.linspace(0, L, nx + 1)
    g, wg = np.polynomial.legendre.leggauss(5)
    exact_means = [0.5 * np.sum(wg * fin_analytic(0.5 * (a + b) + 0.5 * (b - a) * g)[0]) for a, b in zip(edges[:-1], edges[1:])]
    profile = np.max(np.abs(section_means(mesh, T, 0, edges) - exact_means)) / (T_BASE - T_AIR)
    rel_tip = (tip - tip_exact) / (tip_exact - T_AIR)
    print(f"pin fin: tip {tip:.4f} °C vs {tip_exact:.4f} °C ({100 * rel_tip:+.3f} % of the tip rise), "
          f"heat {q:.4f} W vs {q_exact:.4f} W ({100 * (q / q_exact - 1):+.3f} %), profile max dev {100 * profile:.3f} % of θ_b; "
          f"{nx}×2×2 hexahedra, {time.perf_counter() - start:.2f} s")
    assert abs(rel_tip) < 0.01
    assert abs(q / q_exact - 1) < 0.01
    assert profile < 0.01


def test_wall_with_convection_is_exact():
    mesh = bar(0.05, 0.02, 0.02, 5, 2, 2)
    k, h = 15.0, 300.0
    operator = HeatOperator.conduction(conduction_matrix(cell_basis(mesh), k)) + convection(mesh, mesh.boundaries["x1"], h, T_AIR)
    hot = mesh.nodes_satisfying(lambda p: p[0] < 1e-9)
    T = solve_steady(operator, fixed=hot, fixed_values=T_BASE)
    q = (T_BASE - T_AIR) / (0.05 / k + 1 / h)
    face = mesh.nodes_satisfying(lambda p: p[0] > 0.05 - 1e-9)
    np.testing.assert_allclose(T[face], T_AIR + q / h, rtol=1e-10)
    np.testing.assert_allclose(convective_loss(mesh, mesh.boundaries["x1"], h, T_AIR, T), q * 0.02 * 0.02, rtol=1e-10)
