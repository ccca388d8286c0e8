"""A block sliding along a rod through a sliding contact resistance.

A steel rod (40 layers of 5 mm, 10 × 10 mm section) carries a cast-iron slider (4 layers
long, 10 mm high) on its top face, through a contact resistance R'' = 2e-4 m²·K/W. The
slider holds a 5 W volumetric source; friction of 2 W arises at the contact, half into the
slider's face, half into the rod's layers under it (a band moving with the slider). The
slider's free faces and the rod's sides convect to 20 °C; the rod's top convects only where
the slider does not cover it. The slider moves back and forth one layer per step.

At every step:

- the heat leaving the slider through the contact, integrated over the slider's facets,
  equals the heat entering the rod, integrated over the rod's facets under it (two
  separate surface integrals), to solver precision;
- the same from the assembled coupling: the contact's nodal heat flows sum to zero.

Over the run, heat in (from the source definitions) = heat stored + heat lost (from
surface integrals), within 1e-3 (in fact to round-off).
"""

import time

import numpy as np
import pytest

from feedtherm.models.fem.energy import ConvectiveLoss, EnergyLedger, stored_heat, surface_power, volumetric_power
from feedtherm.models.fem.heat import (
    HeatOperator,
    ThetaStepper,
    capacity_matrix,
    cell_basis,
    conduction_matrix,
    convection,
    facet_load,
    volumetric_load,
)
from feedtherm.models.fem.interfaces import SlidingInterface
from feedtherm.models.fem.layers import layered_surface
from feedtherm.models.fem.meshes import rod_and_slider
from feedtherm.models.fem.topology import element_volumes

LAYER, ROD_LAYERS, SLIDER_LAYERS, WIDTH = 5e-3, 40, 4, 0.01
K_ROD, C_ROD, K_SLIDER, C_SLIDER = 45.0, 3.6e6, 40.0, 3.9e6
R_CONTACT, H_ROD, H_SLIDER, T_AIR = 2e-4, 10.0, 15.0, 20.0
SOURCE, FRICTION, SPEED = 5.0, 2.0, 0.5e-3


def positions(steps, n_positions):
    """Back and forth over 0 … n_positions - 1, one layer per step, starting at 0."""
    period = 2 * (n_positions - 1)
    phase = np.arange(1, steps + 1) % period
    return np.where(phase < n_positions, phase, period - phase)


@pytest.mark.parametrize("theta", [1.0, 0.5])
def test_heat_across_the_sliding_contact_is_conserved(theta):
    start = time.perf_counter()
    geo = rod_and_slider(LAYER, ROD_LAYERS, SLIDER_LAYERS, WIDTH, slider_height=0.01)
    mesh = geo.mesh
    basis = cell_basis(mesh)
    in_slider = np.isin(np.arange(mesh.nelements), geo.slider_elements)
    k = np.where(in_slider, K_SLIDER, K_ROD)
    rho_c = np.where(in_slider, C_SLIDER, C_ROD)
    q_volume = np.where(in_slider, SOURCE / element_volumes(mesh)[geo.slider_elements].sum(), 0.0)

    track = layered_surface(mesh, geo.rod_top, axis=0, spacing=LAYER)
    face = layered_surface(mesh, geo.slider_bottom, axis=0, spacing=LAYER)
    sliding = SlidingInterface(track, face, R_CONTACT)
    assert sliding.n_positions == ROD_LAYERS - SLIDER_LAYERS + 1
    contact_area = SLIDER_LAYERS * LAYER * WIDTH
    flux = FRICTION / 2 / contact_area

    fixed_part = (
        HeatOperator.conduction(conduction_matrix(basis, k))
        + convection(mesh, geo.rod_sides, H_ROD, T_AIR)
        + convection(mesh, geo.slider_free, H_SLIDER, T_AIR)
        + HeatOperator.source(volumetric_load(basis, q_volume) + facet_load(mesh, geo.slider_bottom, flux))
    )
    all_layers = set(range(ROD_LAYERS))

    def covered(s):
        return range(s, s + SLIDER_LAYERS)

    def exposed(s):
        return sorted(all_layers - set(covered(s)))

    operators = {}

    def at(s):  # one assembly per position, then reused: a move is a lookup
        if s not in operators:
            operators[s] = (
                fixed_part
                + sliding.operator(s)
                + track.convection(exposed(s), H_ROD, T_AIR)
                + HeatOperator.source(track.load(covered(s), flux))
            )
        return operators[s]

    # the energy ledger's own integrals, built from the definitions
    fixed_losses = [ConvectiveLoss(mesh, geo.rod_sides, H_ROD, T_AIR), ConvectiveLoss(mesh, geo.slider_free, H_SLIDER, T_AIR)]
    top_losses = {}

    def loss(T, s):
        if s not in top_losses:
            top_losses[s] = ConvectiveLoss(mesh, track.layer_facets(exposed(s)), H_ROD, T_AIR)
        return sum(f(T) for f in fixed_losses) + top_losses[s](T)

    def power(s):
        return (
            volumetric_power(mesh, q_volume)
            + surface_power(mesh, geo.slider_bottom, flux)
            + surface_power(mesh, track.layer_facets(covered(s)), flux)
        )

    dt = LAYER / SPEED
    steps = 6 * (sliding.n_positions - 1)  # three double strokes
    stepper = ThetaStepper(capacity_matrix(basis, rho_c), theta=theta)
    T = np.full(mesh.nvertices, T_AIR)
    s_old = 0
    ledger = EnergyLedger(power=power(0), loss=loss(T, 0), theta=theta)
    slider_nodes = np.unique(mesh.t[:, geo.slider_elements])
    worst = 0.0
    for s in positions(steps, sliding.n_positions):
        T = stepper.step(T, dt, at(s_old), at(s), key=int(s))
        ledger.add_step(dt, power(s), loss(T, s))
        out_of_slider, into_rod = sliding.heat_flow(T, s)
        nodal = sliding.operator(s).conductance @ T  # heat leaving each node through the contact
        assert out_of_slider > 0.5  # the slider is the hotter side
        assert into_rod == pytest.approx(out_of_slider, rel=1e-10)
        assert nodal[slider_nodes].sum() == pytest.approx(out_of_slider, rel=1e-10)
        assert -np.delete(nodal, slider_nodes).sum() == pytest.approx(out_of_slider, rel=1e-10)
        worst = max(worst, abs(into_rod - out_of_slider) / out_of_slider)
        s_old = s
    assert stepper.factorisations == sliding.n_positions  # one per position, reused afterwards
    balance = ledger.error(stored_heat(basis, rho_c, T, T_AIR))
    print(f"sliding contact (theta={theta}): {steps} steps of {dt:g} s over {sliding.n_positions} positions, "
          f"{mesh.nvertices} nodes; last contact flow {out_of_slider:.4f} W, worst |out - in|/out {worst:.1e}; "
          f"heat in {ledger.heat_in:.1f} J, lost {ledger.heat_lost:.1f} J, energy balance {balance:.1e}; "
          f"{time.perf_counter() - start:.2f} s")
    assert balance < 1e-3


def test_positions_outside_the_track_are_refused():
    geo = rod_and_slider(LAYER, 10, 4, WIDTH, slider_height=0.01)
    sliding = SlidingInterface(
        layered_surface(geo.mesh, geo.rod_top, 0, LAYER), layered_surface(geo.mesh, geo.slider_bottom, 0, LAYER), R_CONTACT
    )
    with pytest.raises(IndexError):
        sliding.operator(7)
