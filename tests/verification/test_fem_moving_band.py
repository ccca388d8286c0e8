r"""A heat band moving along a rod with lateral convection, against its quasi-steady solution.

A square steel rod (10 × 10 mm, k = 50 W/(m·K), ρc = 3.6e6 J/(m³·K)) loses heat by
convection (h = 100 W/(m²·K)) on its four sides. A band of width b = 10 mm heats its
surface with Q = 5 W in total and moves at v = 0.2 mm/s. In the band's frame
(ξ = x - x_band(t), ξ > 0 ahead) the cross-section mean θ = T - T∞ becomes steady
(the 1D fin equation, Bi = h·(w/2)/k = 0.01):

.. math::

    k A θ'' + ρc A v θ' - h P θ = -q'(ξ)

For a point source Q the solution decaying both ways is (Rosenthal-type, 1D)

.. math::

    θ(ξ) = \frac{Q}{2kAλ} e^{-βξ - λ|ξ|},  β = \frac{v}{2a},  λ = \sqrt{β^2 + \frac{hP}{kA}},

(the jump of kAθ' at ξ = 0 equals -Q). The band, Q/b per unit length over |ξ| ≤ b/2, is
its convolution with the box, done in closed form below; layer means compare with the
analytic one averaged over each layer (6-point Gauss).

The band is applied to the rod's surface layers (``LayeredSurface.load``) and moved one
layer per step (Crank–Nicolson, dt = layer/v): the same index-shift machinery as the
sliding interface. The band's position at the end of a step is the reference point (with
Crank–Nicolson the band sits on average half a layer behind it over the step, which is the
position the continuous band had half a step earlier).
"""

import math
import time

import numpy as np
import pytest

from feedtherm.models.fem.energy import ConvectiveLoss, EnergyLedger, stored_heat, surface_power
from feedtherm.models.fem.fields import section_means
from feedtherm.models.fem.heat import HeatOperator, ThetaStepper, capacity_matrix, cell_basis, conduction_matrix, convection
from feedtherm.models.fem.layers import layered_surface
from feedtherm.models.fem.meshes import bar

K, RHO_C, H, W = 50.0, 3.6e6, 100.0, 0.01
SPEED, POWER, BAND = 0.2e-3, 5.0, 0.01
LENGTH, LAYER, START, DURATION = 0.4, 1e-3, 0.05, 900.0


def band_rise(xi, width=BAND):
    """Quasi-steady θ of a uniform band of ``width`` centred at ξ = 0 [K]."""
    area, perimeter = W * W, 4 * W
    beta = SPEED * RHO_C / (2 * K)
    lam = math.sqrt(beta**2 + H * perimeter / (K * area))

    def behind(u):  # primitive of exp((λ-β)u) for u ≤ 0
        return np.exp((lam - beta) * np.minimum(u, 0.0)) / (lam - beta)

    def ahead(u):  # primitive of exp(-(β+λ)u) for u ≥ 0
        return -np.exp(-(beta + lam) * np.maximum(u, 0.0)) / (beta + lam)

    u1, u2 = xi - width / 2, xi + width / 2  # ξ - s over the band
    integral = (behind(u2) - behind(u1)) + (ahead(u2) - ahead(u1))
    return POWER / width * integral / (2 * K * area * lam)


def test_band_formula_against_quadrature():
    """The closed-form convolution against a direct quadrature of the point-source kernel."""
    from scipy.integrate import quad

    area, perimeter = W * W, 4 * W
    beta = SPEED * RHO_C / (2 * K)
    lam = math.sqrt(beta**2 + H * perimeter / (K * area))
    kernel = lambda u: POWER / BAND * math.exp(-beta * u - lam * abs(u)) / (2 * K * area * lam)  # noqa: E731
    for xi in (-0.05, -0.004, 0.0, 0.003, 0.02):
        direct = quad(kernel, xi - BAND / 2, xi + BAND / 2, points=[0.0] if abs(xi) < BAND / 2 else None)[0]
        assert band_rise(np.array(xi)) == pytest.approx(direct, rel=1e-9)


def test_moving_band_matches_the_quasi_steady_solution():
    start = time.perf_counter()
    layers = round(LENGTH / LAYER)
    mesh = bar(LENGTH, W, W, layers, 2, 2)
    basis = cell_basis(mesh)
    sides = np.concatenate([mesh.boundaries[name] for name in ("y0", "y1", "z0", "z1")])
    surface = layered_surface(mesh, sides, axis=0, spacing=LAYER)
    fixed_part = HeatOperator.conduction(conduction_matrix(basis, K)) + convection(mesh, sides, H, 0.0)
    band_layers = round(BAND / LAYER)
    flux = POWER / (4 * W * BAND)

    def at(k):
        return fixed_part + HeatOperator.source(surface.load(range(k, k + band_layers), flux))

    def band_power(k):  # from the band's definition, apart from the assembled loads
        return surface_power(mesh, surface.layer_facets(range(k, k + band_layers)), flux)

    stepper = ThetaStepper(capacity_matrix(basis, RHO_C), theta=0.5)
    loss = ConvectiveLoss(mesh, sides, H, 0.0)
    dt = LAYER / SPEED
    k0 = round(START / LAYER)
    T = np.zeros(mesh.nvertices)
    ledger = EnergyLedger(power=band_power(k0), loss=loss(T), theta=0.5)
    old = at(k0)
    steps = round(DURATION / dt)
    for j in range(1, steps + 1):
        new = at(k0 + j)
        T_new = stepper.step(T, dt, old, new, key="rod")  # the conductances never change here
        ledger.add_step(dt, band_power(k0 + j), loss(T_new))
        T, old = T_new, new
    assert stepper.factorisations == 1

    edges = np.arange(layers + 1) * LAYER
    means = section_means(mesh, T, 0, edges)
    centre = (k0 + steps) * LAYER + BAND / 2
    g, wg = np.polynomial.legendre.leggauss(6)
    mid = 0.5 * (edges[:-1] + edges[1:])
    exact = np.array([0.5 * np.sum(wg * band_rise(c + 0.5 * LAYER * g - centre)) for c in mid])
    window = np.abs(mid - centre) < 0.1
    deviation = np.abs(means - exact)[window].max() / exact.max()
    balance = ledger.error(stored_heat(basis, RHO_C, T, 0.0))
    print(f"moving band: peak layer mean {means.max():.3f} K vs {exact.max():.3f} K, max deviation over ±100 mm "
          f"{100 * deviation:.3f} % of the peak rise; {layers} layers of {1e3 * LAYER:g} mm, 2×2 cross-section "
          f"({mesh.nvertices} nodes), Crank–Nicolson dt = {dt:g} s, {steps} steps, energy balance {balance:.1e}, "
          f"{time.perf_counter() - start:.2f} s")
    assert deviation < 0.01
    assert balance < 1e-3
