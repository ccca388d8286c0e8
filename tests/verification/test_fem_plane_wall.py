"""A plane wall with a held face and a convecting face: case ``cases/plane_wall.toml``.

Wall L = 50 mm, k = 15 W/(m·K), sides insulated; the face x = 0 held at 100 °C by a penalty
film h_p = 1e7 W/(m²·K), the face x = L cooled by h = 300 W/(m²·K) to 20 °C. In series:

    q = (T_1 − T∞) / (1/h_p + L/k + 1/h) = 80 / (1e-7 + 3.3333e-3 + 3.3333e-3) = 11,999.82 W/m²,
    T(L) = T∞ + q/h = 59.9994 °C,  T(L/2) = T_1 − q·(1/h_p + L/(2k)) = 79.9994 °C.

The profile is linear and the wall's faces are flat (a box), so linear elements hold it
exactly: the old tolerance (1e-10) is kept, at every density.
"""

import numpy as np
import pytest
from fem_cases import load_case, solve_steady

from feedtherm.constants import KELVIN_OFFSET

T_HELD, T_AIR, L, K, H, H_PENALTY, AREA = 100.0, 20.0, 0.05, 15.0, 300.0, 1e7, 0.02 * 0.02
Q = (T_HELD - T_AIR) / (1 / H_PENALTY + L / K + 1 / H)


@pytest.mark.parametrize("mesh", ["coarse", "fine"])
def test_wall_with_convection_is_exact(mesh):
    steady = solve_steady(load_case("plane_wall"), "held", mesh)
    nodes, areas = steady.model.surface_exposure("cooled", 0)
    T = steady.state - KELVIN_OFFSET
    assert areas.sum() == pytest.approx(AREA, rel=1e-12)
    np.testing.assert_allclose(T[nodes], T_AIR + Q / H, rtol=1e-10)
    face, middle = steady.model.probe(steady.state, 0)[:2] - KELVIN_OFFSET
    assert face == pytest.approx(T_AIR + Q / H, rel=1e-10)
    assert middle == pytest.approx(T_HELD - Q * (1 / H_PENALTY + L / (2 * K)), rel=1e-10)
    assert steady.surface_heat("cooled") == pytest.approx(Q * AREA, rel=1e-10)
    assert -steady.surface_heat("held") == pytest.approx(Q * AREA, rel=1e-10)
