r"""A strong film in series with conduction, by the fast and the FE model (issue 35, item 5).

**Two blocks in series** (``cases/blocks_in_series.toml``).  Blocks a (x 0–0.1 m) and b
(x 0.1–0.2 m), S = 2.5e-3 m² across, k = 50 W/(m·K), joined with R'' = 1e-4 m²·K/W; Q = 50 W
generated evenly in a; the face x = 0.2 m cooled by h = 500 W/(m²·K) to T∞ = 20 °C; every other
face insulated.  One-dimensional, in series (Incropera et al., §3.1.4 and §3.5), worked out here:

* the film: T(0.2) = T∞ + Q/(hS) = 20 + 50/(500 · 2.5e-3) = 20 + 40 = 60 °C;
* block b carries Q: dT/dx = −Q/(kS) = −50/(50 · 2.5e-3) = −400 K/m, so
  T(x) = 60 + 400 (0.2 − x) and T(0.1⁺) = 100 °C;
* the contact: a jump of Q R''/S = 50 · 1e-4 / 2.5e-3 = 2 K, T(0.1⁻) = 102 °C;
* block a, generation q''' = Q/(S L) = 50/2.5e-4 = 2e5 W/m³ with its end x = 0 insulated:
  T(x) = 102 + q'''/(2k) (L² − x²) = 102 + 2000 (0.01 − x²), 122 °C at x = 0.

The fast model's cells are 25 mm, so its last cell's centre is d = 12.5 mm from the film:
h·d/k = 0.125.  Linked straight to that centre, the film left out Q·d/(kS) = 5 K of conduction
and the whole field ran 5 K low (5–8 % of the rise); with the half cell in series it is exact
in block b and within q'''(d)²/(2k) = 0.31 K (the cell-centred scheme's own error at the
contact) in block a.

**The pin fin** (``cases/pin_fin.toml``, the FE model's check in ``test_fem_fin.py``), base
held at 100 °C by a penalty film, h = 25 W/(m²·K) on its side and tip: the tip's excess
θ(L)/θ_0 = 1/(cosh mL + (h/mk) sinh mL) = 0.7848 (mL = 0.7071, h/(mk) = 0.01768), 82.78 °C.
The fast model cuts the pin (a part of no feed drive) into cells; its held base is a penalty
film in series with the half cell.

Both within 1 % of the temperature rise, as issue 35 asks.
"""

import math

import numpy as np
import pytest
from fem_cases import load_case

from feedtherm.constants import KELVIN_OFFSET
from feedtherm.models.interface import film_coefficient
from feedtherm.simulate import steady_solve

T_AIR, Q, S, K, H, R_CONTACT, L = 20.0, 50.0, 2.5e-3, 50.0, 500.0, 1e-4, 0.1


def series_exact(x: float) -> float:
    """The two blocks' steady temperature [°C] at x [m] (worked out in the module's notes)."""
    face = T_AIR + Q / (H * S)
    if x >= L:
        return face + Q / (K * S) * (2 * L - x)
    a_at_contact = face + Q / (K * S) * L + Q * R_CONTACT / S
    return a_at_contact + Q / (S * L) / (2 * K) * (L * L - x * x)


def test_the_worked_out_profile():
    assert [series_exact(x) for x in (0.0, 0.1 - 1e-12, 0.1, 0.15, 0.2)] == pytest.approx([122, 102, 100, 80, 60])


@pytest.mark.parametrize("model, mesh", [("fast", None), ("fem", "coarse")])
def test_two_blocks_in_series_under_a_strong_film(model, mesh):
    loaded = load_case("blocks_in_series")
    steady = steady_solve(loaded, "heated", model=model, mesh=mesh)
    readings = dict(zip(steady.model.probe_names, steady.model.probe(steady.state, 0) - KELVIN_OFFSET))
    for name, sensor in loaded.system.sensors.items():
        exact = series_exact(sensor.position[0])
        assert readings[name] - T_AIR == pytest.approx(exact - T_AIR, rel=0.01), name
    # the heat the film gives to the air is what the heater makes (a steady state)
    basis = steady.model.boundary_basis(0)
    nodes, areas = steady.model.surface_exposure("cooled", 0)
    h = basis.coefficients(steady.segment.bc)[0][basis.surfaces.index("cooled")]
    lost = h * float(areas @ (steady.state[nodes] - KELVIN_OFFSET - T_AIR))
    assert lost == pytest.approx(Q, rel=1e-9)


def test_the_fast_model_is_exact_in_the_linear_block():
    """Every cell of block b on the line, block a within the scheme's 0.31 K at the contact."""
    steady = steady_solve(load_case("blocks_in_series"), "heated", model="fast")
    cells = steady.model.layout.cells
    for part, tolerance in (("block_b", 1e-9), ("block_a", 0.32)):
        centres = cells[part].node_points()[:, 0]
        T = steady.state[cells[part].nodes] - KELVIN_OFFSET
        exact = np.array([series_exact(x) for x in centres])
        np.testing.assert_allclose(T, exact, atol=tolerance, rtol=0)


def test_the_fast_pin_fin_follows_the_fin_solution():
    m_l = math.sqrt(25 * 4 / (200 * 0.01)) * 0.1
    ratio = 25 / (math.sqrt(25 * 4 / (200 * 0.01)) * 200)
    tip = T_AIR + 80 / (math.cosh(m_l) + ratio * math.sinh(m_l))
    assert tip == pytest.approx(82.78, abs=0.01)
    loaded = load_case("pin_fin")
    steady = steady_solve(loaded, next(iter(loaded.system.conditions)), model="fast")
    reading = steady.model.probe(steady.state, 0)[steady.model.probe_names.index("tip")] - KELVIN_OFFSET
    assert reading - T_AIR == pytest.approx(tip - T_AIR, rel=0.01)


def test_film_coefficient_by_hand():
    """h = 500 W/(m²·K) behind 12.5 mm of k = 50 W/(m·K): r = 2.5e-4 m²·K/W,
    1/(1/500 + 2.5e-4) = 1/2.25e-3 = 444.4 W/(m²·K); no resistance leaves h as it is."""
    assert float(film_coefficient(500.0, 0.0125 / 50.0)) == pytest.approx(444.444, rel=1e-5)
    np.testing.assert_array_equal(film_coefficient([0.0, 7.0], [1.0, 0.0]), [0.0, 7.0])
