r"""The pin fin through the FE model's steady solve: case ``cases/pin_fin.toml``.

A cylindrical pin, D = 10 mm, L = 0.1 m, k = 200 W/(m·K), base at 100 °C, convection
h = 25 W/(m²·K) to 20 °C on its side and its tip. The 1-D fin solution (Incropera,
Fundamentals of Heat and Mass Transfer, Table 3.4, case A), for any uniform cross-section of
perimeter P and area A:

.. math::

    \frac{θ(x)}{θ_0} = \frac{\cosh m(L-x) + (h/mk) \sinh m(L-x)}{\cosh mL + (h/mk) \sinh mL},\qquad
    q_f = \sqrt{hPkA}\,θ_0\,\frac{\sinh mL + (h/mk) \cosh mL}{\cosh mL + (h/mk) \sinh mL},\qquad
    m = \sqrt{\frac{hP}{kA}}.

Its Biot number h·(D/4)/k = 3e-4 makes it an accurate reference for the 3-D pin.

**Base.** Held by a penalty, h_p = 1e7 W/(m²·K) to a sink at θ_b = 80 K above the air. In
series with the fin's conductance G_f = q_f/θ_0 the film gives the base excess
θ_0 = θ_b·G_p/(G_p + G_f), G_p = h_p·A: 8.8e-5 below θ_b. The reference uses θ_0 (exact for
the penalty), so the penalty is no part of the measured error.

Checked at every density, with the old tolerances (1 % of the tip's excess, of the heat
flow, and of θ_b for the profile of section means, each section's exact mean by 5-point
Gauss): all three meshes are within 0.6 %. The heat flow is what the cooled surface gives to
the air, ``∑ h·a·(T − T∞)`` over its nodes, and equals the heat that enters through the base
to round-off (a steady state). The orders come from the pin's element sizes (mean edge
lengths 2.13, 1.31, 0.82 mm): 2.16 and 2.14 for the tip and the profile, 2.0 and 1.8 for
the heat flow (the faceted circle's perimeter and area enter it). They are held to 2 ± 0.4:
gmsh's meshes at the three densities are not nested, and a change of the error constant by
20 % between two of them moves a pairwise order by ln 1.2 / ln 1.6 = 0.4.
"""

import math
import time
from itertools import pairwise

import numpy as np
import pytest
from fem_cases import element_size, load_case, observed_order, section_means, solve_steady

from feedtherm.constants import KELVIN_OFFSET

K, H, T_BASE, T_AIR, L, D = 200.0, 25.0, 100.0, 20.0, 0.1, 0.01
H_PENALTY = 1e7
MESHES = ("coarse", "medium", "fine")
#: The fin's profile is read as the means over 200 sections of 0.5 mm along it.
SECTIONS = np.linspace(0.0, 0.1, 201)


def fin(x):
    """Incropera Table 3.4 case A: θ(x)/θ_0 and q_f/θ_0 [W/K] of the pin."""
    P, A = math.pi * D, math.pi * D * D / 4
    m = math.sqrt(H * P / (K * A))
    r = H / (m * K)
    den = math.cosh(m * L) + r * math.sinh(m * L)
    ratio = (np.cosh(m * (L - x)) + r * np.sinh(m * (L - x))) / den
    return ratio, math.sqrt(H * P * K * A) * (math.sinh(m * L) + r * math.cosh(m * L)) / den


def base_excess() -> float:
    """θ_0 [K]: the held 80 K less the drop over the penalty film (the two in series)."""
    _, g_fin = fin(0.0)
    g_penalty = H_PENALTY * math.pi * D * D / 4
    return (T_BASE - T_AIR) * g_penalty / (g_penalty + g_fin)


@pytest.fixture(scope="module")
def results():
    out = {}
    theta0 = base_excess()
    g, wg = np.polynomial.legendre.leggauss(5)
    for mesh in MESHES:
        started = time.perf_counter()
        steady = solve_steady(load_case("pin_fin"), "still_air", mesh)
        model = steady.model
        edges = SECTIONS
        sections = section_means(model.field_mesh(), steady.state, "pin", edges) - KELVIN_OFFSET
        exact = np.array([T_AIR + theta0 * 0.5 * np.sum(wg * fin(0.5 * (a + b) + 0.5 * (b - a) * g)[0])
                          for a, b in pairwise(edges)])
        out[mesh] = {
            "size": element_size(model.field_mesh(), "pin"), "nodes": model.n_nodes,
            "tip": (sections[-1] - exact[-1]) / (exact[-1] - T_AIR),
            "profile": np.max(np.abs(sections - exact)) / (T_BASE - T_AIR),
            "heat": steady.surface_heat("cooled") / (fin(0.0)[1] * theta0) - 1.0,
            "heat_in": -steady.surface_heat("base"), "heat_out": steady.surface_heat("cooled"),
            "seconds": time.perf_counter() - started,
        }
    return out


def test_penalty_film_is_small():
    assert 0 < 1 - base_excess() / (T_BASE - T_AIR) < 1e-4


@pytest.mark.parametrize("mesh", MESHES)
def test_pin_fin_tip_profile_and_heat_flow(results, mesh):
    r = results[mesh]
    print(f"pin fin ({mesh}, h = {r['size'] * 1e3:g} mm, {r['nodes']} nodes): tip {100 * r['tip']:+.3f} % of its "
          f"excess, heat {100 * r['heat']:+.3f} %, profile max dev {100 * r['profile']:.3f} % of θ_b; "
          f"heat in {r['heat_in']:.5f} W, out {r['heat_out']:.5f} W; {r['seconds']:.1f} s")
    assert abs(r["tip"]) < 0.01
    assert abs(r["heat"]) < 0.01
    assert r["profile"] < 0.01
    assert r["heat_out"] == pytest.approx(r["heat_in"], rel=1e-9)


def test_second_order_in_the_element_size(results):
    sizes = [results[m]["size"] for m in MESHES]
    assert sizes[0] > sizes[1] > sizes[2]
    for quantity in ("tip", "profile", "heat"):
        orders = observed_order([results[m][quantity] for m in MESHES], sizes)
        print(f"pin fin {quantity}: observed orders {[f'{o:.2f}' for o in orders]} at h = {[h * 1e3 for h in sizes]} mm")
        assert all(1.6 < order < 2.4 for order in orders), quantity
