r"""An end face of the screw sits at the screw's end in the fast model, not along its length.

The pin fin of ``tests/verification/cases/pin_fin.toml`` (D = 10 mm, L = 0.1 m, k = 200 W/(m·K),
base held at 100 °C by a penalty on its ``-x`` face, h = 25 W/(m²·K) to 20 °C on its side and its
``+x`` tip) made the screw of a feed drive: a small carriage as its nut, a lead and a stroke, so
that the fast model resolves it as an axial body.  The 1-D fin solution (Incropera, Fundamentals
of Heat and Mass Transfer, Table 3.4, case A; Bi = h·(D/4)/k = 3e-4):

.. math::

    \frac{θ(x)}{θ_0} = \frac{\cosh m(L-x) + (h/mk) \sinh m(L-x)}{\cosh mL + (h/mk) \sinh mL},
    \qquad m = \sqrt{hP/(kA)} = \sqrt{25 · 4 / (200 · 0.01)} = 7.071\ \mathrm{m^{-1}},

so mL = 0.7071, h/(mk) = 0.01768 and the tip's excess θ(L)/θ_0 = 1/(cosh 0.7071 + 0.01768 sinh
0.7071) = 1/(1.2606 + 0.01768 · 0.7675) = 1/1.2742 = 0.7848: 82.8 °C at the tip with θ_0 = 80 K.

With the end faces spread evenly along the screw (before), the base's 1e7 W/(m²·K) reached every
cell and held the whole pin near its base temperature; at its end, the base film acts on the
first cell only and the fast model follows the fin.
"""

import math
from pathlib import Path

import numpy as np
import pytest

from feedtherm.constants import KELVIN_OFFSET
from feedtherm.simulate import steady_solve
from feedtherm.system.load import load_system

CASE = Path(__file__).parents[1] / "verification" / "cases" / "pin_fin.toml"

DRIVE = """
[parts.carriage]
material = "fin"
moving = true
boxes = [{ origin = ["0 m", "0.1 m", "0 m"], size = ["10 mm", "10 mm", "10 mm"] }]

[surfaces.carriage]
part = "carriage"
faces = ["+z"]
convection = { kind = "fixed", coefficient = "10 W/(m^2*K)" }
emissivity = 0

[kinematics]
drive = "single"
screw = "pin"
nut = "carriage"
lead = "10 mm"
stroke = "10 mm"

[[mechanics.supports]]
part = "carriage"
point = ["0 mm", "100 mm", "0 mm"]
fix = ["x", "y", "z"]

[[mechanics.supports]]
part = "carriage"
point = ["10 mm", "100 mm", "0 mm"]
fix = ["y", "z"]

[[mechanics.supports]]
part = "carriage"
point = ["0 mm", "110 mm", "0 mm"]
fix = ["z"]

[mechanics.positioning]
reference = { part = "pin", point = ["0 mm", "0 mm", "0 mm"] }
"""


def test_the_hand_value():
    m = math.sqrt(25.0 * 4.0 / (200.0 * 0.01))
    r = 25.0 / (m * 200.0)
    assert m == pytest.approx(7.0711, abs=1e-4) and r == pytest.approx(0.01768, abs=1e-5)
    tip = 1.0 / (math.cosh(m * 0.1) + r * math.sinh(m * 0.1))
    assert tip == pytest.approx(0.7848, abs=1e-4)


@pytest.fixture(scope="module")
def steady(tmp_path_factory):
    path = tmp_path_factory.mktemp("fin") / "pin_screw.toml"
    case = CASE.read_text(encoding="utf-8")
    assert "[conditions.still_air]\n" in case
    # with a drive, the condition states its screw speed: the fin stands still
    case = case.replace("[conditions.still_air]\n", '[conditions.still_air]\nscrew_speed = "0 rpm"\n', 1)
    path.write_text(case + DRIVE, encoding="utf-8")
    loaded = load_system(str(path))
    assert loaded.system.kinematics.screw == "pin"
    return steady_solve(loaded, "still_air", model="fast")


def test_the_screws_end_faces_are_at_its_ends(steady):
    base = steady.model.surface_exposure("base", 0)
    nodes, areas = base
    screw = steady.model.layout.screw
    assert set(nodes[areas > 0]) <= set(screw.nodes[0])  # the first cell only, every ring
    assert areas.sum() == pytest.approx(math.pi / 4 * 0.01**2, rel=1e-12)
    cooled_nodes, cooled = steady.model.surface_exposure("cooled", 0)
    tip = np.isin(cooled_nodes, screw.nodes[-1]) & ~np.isin(cooled_nodes, screw.nodes[-1, -1])
    assert cooled[tip].sum() > 0.0  # the inner ring of the tip cell has its share of the tip face
    assert cooled.sum() == pytest.approx(math.pi * 0.01 * 0.1 + math.pi / 4 * 0.01**2, rel=1e-12)


def test_the_fast_model_follows_the_fin(steady):
    sections = steady.model.screw_mean(steady.state) - KELVIN_OFFSET
    centres = steady.model.screw_centres
    m, r = math.sqrt(25.0 * 4.0 / (200.0 * 0.01)), 25.0 / (math.sqrt(25.0 * 4.0 / (200.0 * 0.01)) * 200.0)
    exact = 20.0 + 80.0 * (np.cosh(m * (0.1 - centres)) + r * np.sinh(m * (0.1 - centres))) / (
        math.cosh(m * 0.1) + r * math.sinh(m * 0.1))
    # measured: 0.06 K at the tip, 0.08 K at most along the pin (spread along it: 17.2 K at the tip)
    assert sections[-1] == pytest.approx(exact[-1], abs=0.2)  # the tip, 82.8 °C
    assert np.max(np.abs(sections - exact)) < 0.2
