"""NAFEMS T3: one-dimensional transient conduction with a sinusoidal end temperature.

Bar 0.1 m, k = 35 W/(m·K), ρc = 7200·440 J/(m³·K), T = 0 °C at t = 0 and at x = 0,
T(x = 0.1 m) = 100·sin(πt/40) °C. Reference: T(0.08 m, 32 s) = 36.60 °C (NAFEMS, "The
Standard NAFEMS Benchmarks", TNSB rev. 3, test T3). Modelled as a 3D bar
0.1 × 0.01 × 0.01 m, insulated sides, both ends Dirichlet, Crank–Nicolson.

The separated-variables series below is the exact solution (it gives 36.626 °C); the
mesh-convergence test measures the error against it:

    T = (x/L)·g(t) + Σ b_n(t) sin(nπx/L),   g = 100 sin(ωt), ω = π/40,
    b_n = -c_n·100ω·[λ_n cos ωt + ω sin ωt - λ_n e^{-λ_n t}] / (λ_n² + ω²),
    c_n = 2(-1)^{n+1}/(nπ),  λ_n = a(nπ/L)²,  a = k/(ρc).
"""

import math
import time

import numpy as np

from feedtherm.models.fem.heat import HeatOperator, ThetaStepper, capacity_matrix, cell_basis, conduction_matrix
from feedtherm.models.fem.meshes import bar

K, RHO_C, L = 35.0, 7200.0 * 440.0, 0.1
OMEGA = math.pi / 40.0
NAFEMS_T3 = 36.60  # °C at x = 0.08 m, t = 32 s


def exact(x: float, t: float, terms: int = 4000) -> float:
    a = K / RHO_C
    n = np.arange(1, terms + 1)
    lam = a * (n * math.pi / L) ** 2
    c = 2.0 * (-1.0) ** (n + 1) / (n * math.pi)
    b = -c * 100.0 * OMEGA * (lam * math.cos(OMEGA * t) + OMEGA * math.sin(OMEGA * t) - lam * np.exp(-lam * t)) / (lam**2 + OMEGA**2)
    return x / L * 100.0 * math.sin(OMEGA * t) + float(np.sum(b * np.sin(n * math.pi * x / L)))


def t3(nx: int, dt: float) -> float:
    """Cross-section mean of T at x = 0.08 m, t = 32 s on a bar of nx × 1 × 1 hexahedra."""
    mesh = bar(L, 0.01, 0.01, nx)
    basis = cell_basis(mesh)
    conduction = HeatOperator.conduction(conduction_matrix(basis, K))
    cold = mesh.nodes_satisfying(lambda p: p[0] < 1e-9 * L)
    hot = mesh.nodes_satisfying(lambda p: p[0] > L * (1 - 1e-9))
    stepper = ThetaStepper(capacity_matrix(basis, RHO_C), theta=0.5, fixed=np.concatenate([cold, hot]))
    T = np.zeros(mesh.nvertices)
    steps = round(32.0 / dt)
    for i in range(1, steps + 1):
        g = 100.0 * math.sin(OMEGA * i * dt)
        T = stepper.step(T, dt, conduction, conduction, key="bar", fixed_values=np.r_[np.zeros(cold.size), np.full(hot.size, g)])
    at = mesh.nodes_satisfying(lambda p: np.abs(p[0] - 0.08) < 1e-9 * L)
    return float(T[at].mean())


def test_series_solution_matches_the_nafems_value():
    assert abs(exact(0.08, 32.0) - NAFEMS_T3) < 0.05


def test_nafems_t3_within_one_percent():
    start = time.perf_counter()
    value = t3(nx=40, dt=0.1)
    error = (value - NAFEMS_T3) / NAFEMS_T3
    print(f"NAFEMS T3: {value:.3f} °C vs {NAFEMS_T3} °C ({100 * error:+.2f} %), exact {exact(0.08, 32.0):.3f} °C; "
          f"40×1×1 hexahedra (240 tets), Crank–Nicolson dt = 0.1 s, {time.perf_counter() - start:.2f} s")
    assert abs(error) < 0.01


def test_mesh_convergence_is_second_order():
    reference = exact(0.08, 32.0)
    errors = [abs(t3(nx, dt=0.1) - reference) for nx in (10, 20, 40)]
    orders = [math.log2(errors[i] / errors[i + 1]) for i in range(2)]
    print(f"T3 errors at h = L/10, L/20, L/40: {[f'{e:.4f}' for e in errors]} K, observed orders {[f'{o:.2f}' for o in orders]}")
    assert all(1.8 < order < 2.3 for order in orders)
