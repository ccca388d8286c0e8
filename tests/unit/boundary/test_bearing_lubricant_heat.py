"""A bearing whose lubricant is an ISO VG grade: its viscosity is taken at the frozen temperature.

The frozen temperature is the one the frozen CHTCs use: the condition's ambient plus
temperatures.convection_delta_t (paper bench: 20 degC + 10 K = 303.15 K at condition I).
"""

from __future__ import annotations

import pytest

from feedtherm.boundary import operating_point
from feedtherm.boundary.heat import source_heats
from feedtherm.system.sources import Lubricant
from feedtherm.system.variants import with_values


def rear_bearing_with(loaded, **lubricant):
    return with_values(loaded, {f"sources.rear_bearing.{key}": value for key, value in lubricant.items()}).system


def test_grade_viscosity_is_walther_at_ambient_plus_convection_delta_t(paper):
    # VG 100 with a stated nu100 = 11 mm²/s (a hand-made example, not from a data sheet) at
    # condition I (303.15 K), Walther / ASTM D341 by hand:
    # loglog 100.7 = log 2.0030295 = 0.3016873, loglog 11.7 = log 1.0681859 = 0.0286468,
    # log 313.15 = 2.4957524, log 373.15 = 2.5718834:
    # B = 0.2730405/0.0761310 = 3.586455, A = 0.3016873 + 3.586455·2.4957524 = 9.252591;
    # log 303.15 = 2.4816576, A − B·2.4816576 = 9.252591 − 8.900353 = 0.352238,
    # 10^0.352238 = 2.250287, 10^2.250287 = 177.9454, nu = 177.9454 − 0.7 = 177.2454 mm²/s.
    grade = Lubricant(grade="ISO VG 100", viscosity_100C="11 mm^2/s")
    system = rear_bearing_with(paper, lubricant_viscosity=None, lubricant=grade)
    point = operating_point(system, system.conditions["I"])
    heat = source_heats(system, point)["rear_bearing"]
    assert heat.details["lubricant_viscosity_m2_per_s"] == pytest.approx(177.2454e-6, rel=1e-6)

    # The same bearing with that viscosity declared as a fixed value makes the same heat.
    fixed = rear_bearing_with(paper, lubricant_viscosity=177.2454e-6)
    same = source_heats(fixed, point)["rear_bearing"]
    assert heat.power == pytest.approx(same.power, rel=1e-5)


def test_grade_viscosity_follows_the_ambient(paper):
    # Condition V is at 25 degC: 308.15 K; the oil is thinner there than at condition I (303.15 K).
    grade = Lubricant(grade="ISO VG 100", viscosity_100C="11 mm^2/s")
    system = rear_bearing_with(paper, lubricant_viscosity=None, lubricant=grade)
    nu = {
        c: source_heats(system, operating_point(system, system.conditions[c]))["rear_bearing"].details["lubricant_viscosity_m2_per_s"]
        for c in ("I", "V")
    }
    assert nu["V"] < nu["I"]
    assert nu["V"] == pytest.approx(grade.viscosity_at(308.15), rel=1e-12)


def test_a_fixed_viscosity_is_used_as_declared(paper_equations):
    # The paper's equation models declare 100 mm²/s: their bearings use exactly that value.
    point = operating_point(paper_equations.system, paper_equations.system.conditions["III"])
    heats = source_heats(paper_equations.system, point)
    for name in ("front_bearing", "rear_bearing", "nut_bearing"):
        assert heats[name].details["lubricant_viscosity_m2_per_s"] == pytest.approx(100e-6, rel=1e-12)
