"""Energy balance of a transient with a source and convection, from separate integrals.

A steel block 40 × 20 × 10 mm holds a 10 W source in its left half and convects to 20 °C
(h = 25 W/(m²·K) on the top, 8 W/(m²·K) on the four sides). Heat in, from the source's
definition (power density × element volume), must equal the heat stored (∫ρc(T - T0)dV) plus
the heat lost (∫h(T - T∞)dA, integrated in time with the scheme's weights), within 1e-3
(it closes to round-off). A tampered run, whose solver misses part of the convection the
ledger accounts for, must fail the check: the balance has teeth.
"""

import numpy as np
import pytest

from feedtherm.models.fem.energy import ConvectiveLoss, EnergyLedger, stored_heat, volumetric_power
from feedtherm.models.fem.heat import (
    ConjugateGradient,
    HeatOperator,
    ThetaStepper,
    capacity_matrix,
    cell_basis,
    conduction_matrix,
    convection,
    solve_steady,
    volumetric_load,
)
from feedtherm.models.fem.meshes import box

K, RHO_C, T_AIR = 45.0, 3.6e6, 20.0


def block():
    mesh = box(np.linspace(0, 0.04, 9), np.linspace(0, 0.02, 5), np.linspace(0, 0.01, 3))
    hot = mesh.p[0, mesh.t].mean(axis=0) < 0.02
    volume = 0.02 * 0.02 * 0.01
    q = np.where(hot, 10.0 / volume, 0.0)
    top = mesh.boundaries["z1"]
    sides = np.concatenate([mesh.boundaries[n] for n in ("x0", "x1", "y0", "y1")])
    return mesh, q, top, sides


def run(theta, lumped, drop_sides_from_solver=False, steps=60, dt=20.0, solver=None):
    mesh, q, top, sides = block()
    basis = cell_basis(mesh)
    operator = HeatOperator.conduction(conduction_matrix(basis, K)) + convection(mesh, top, 25.0, T_AIR) + HeatOperator.source(volumetric_load(basis, q))
    if not drop_sides_from_solver:
        operator = operator + convection(mesh, sides, 8.0, T_AIR)
    losses = [ConvectiveLoss(mesh, top, 25.0, T_AIR), ConvectiveLoss(mesh, sides, 8.0, T_AIR)]
    stepper = ThetaStepper(capacity_matrix(basis, RHO_C, lumped=lumped), theta=theta, solver=solver)
    T = np.full(mesh.nvertices, T_AIR)
    power = volumetric_power(mesh, q)
    assert power == pytest.approx(10.0, rel=1e-12)
    ledger = EnergyLedger(power=power, loss=sum(f(T) for f in losses), theta=theta)
    for _ in range(steps):
        T = stepper.step(T, dt, operator, operator, key="block")
        ledger.add_step(dt, power, sum(f(T) for f in losses))
    return ledger.error(stored_heat(basis, RHO_C, T, T_AIR)), ledger, T, operator, losses


@pytest.mark.parametrize("theta", [1.0, 0.5])
@pytest.mark.parametrize("lumped", [False, True])
def test_energy_balance_closes(theta, lumped):
    error, ledger, T, _, _ = run(theta, lumped)
    print(f"energy balance (theta={theta}, lumped={lumped}): in {ledger.heat_in:.1f} J, lost {ledger.heat_lost:.1f} J, error {error:.1e}")
    assert ledger.heat_lost > 0.05 * ledger.heat_in  # a real share of both stored and lost
    assert error < 1e-3


def test_a_solver_missing_a_surface_fails_the_balance():
    error, *_ = run(1.0, False, drop_sides_from_solver=True)
    assert error > 1e-3


def test_steady_state_loses_what_comes_in():
    _, _, _, operator, losses = run(1.0, False, steps=1)
    T = solve_steady(operator)
    assert sum(f(T) for f in losses) == pytest.approx(10.0, rel=1e-10)


def test_conjugate_gradients_agree_with_the_direct_solver():
    error, _, T_cg, operator, _ = run(0.5, False, solver=ConjugateGradient(rtol=1e-12))
    _, _, T_lu, _, _ = run(0.5, False)
    assert error < 1e-6
    np.testing.assert_allclose(T_cg, T_lu, atol=1e-8)
    np.testing.assert_allclose(solve_steady(operator, solver=ConjugateGradient(rtol=1e-12)), solve_steady(operator), atol=1e-8)
