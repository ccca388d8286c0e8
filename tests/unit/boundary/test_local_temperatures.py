"""Boundary conditions evaluated at the surfaces' and sources' own temperatures (nonlinear coupling).

Each temperature-dependent value is checked against its law at the given temperature, by hand
where the number is simple; a name left out of the reading keeps the frozen temperature
(ambient + temperatures.convection_delta_t).
"""

from __future__ import annotations

import pytest

from feedtherm.boundary import EvaluationMemo, LocalTemperatures, boundary_conditions_at, operating_point, surface_transfer
from feedtherm.boundary.heat import source_heats
from feedtherm.errors import DescriptionError
from feedtherm.system.load import parse_toml, read_text, validate_data
from feedtherm.system.sources import Lubricant, MotorSource
from feedtherm.system.variants import with_values

VG100 = Lubricant(grade="ISO VG 100", viscosity_100C="11 mm^2/s")


def point_of(system, condition="III"):
    return operating_point(system, system.conditions[condition])


def test_a_bearing_takes_its_lubricant_at_its_own_temperature(paper_equations):
    system = with_values(paper_equations, {"sources.front_bearing.lubricant_viscosity": None,
                                 "sources.front_bearing.lubricant": VG100}).system
    point = point_of(system)
    # At 40 °C (313.15 K) an ISO VG 100 oil has its grade's midpoint: 100 mm²/s exactly (ISO 3448).
    heat = source_heats(system, point, {"front_bearing": 313.15})["front_bearing"]
    assert heat.details["lubricant_viscosity_m2_per_s"] == pytest.approx(100e-6, rel=1e-9)
    # Left out of the reading: the frozen temperature, 20 °C + 10 K at condition III.
    frozen = source_heats(system, point, {"nut_bearing": 350.0})["front_bearing"]
    assert frozen.details["lubricant_viscosity_m2_per_s"] == pytest.approx(VG100.viscosity_at(303.15), rel=1e-12)
    # A warmer bearing has thinner oil and less viscous torque.
    assert heat.details["viscous_torque_Nm"] < frozen.details["viscous_torque_Nm"]


def test_a_surface_takes_its_coefficients_at_its_own_temperature(paper):
    system = paper.system
    point = point_of(system)
    reading = LocalTemperatures(surfaces={"worktable": 310.0, "screw_shaft": 330.0})
    bc = boundary_conditions_at(system, point, temperatures=reading)
    for name, t_surface in reading.surfaces.items():
        expected = surface_transfer(system, name, point, t_surface, with_radiation=True)
        assert bc.surfaces[name].convection == pytest.approx(expected.convection, rel=1e-12)
        assert bc.surfaces[name].radiation == pytest.approx(expected.radiation, rel=1e-12)
    frozen = surface_transfer(system, "base_top", point, point.ambient + 10.0, with_radiation=True)
    assert bc.surfaces["base_top"].total == pytest.approx(frozen.total, rel=1e-12)
    assert bc.temperatures is reading


def test_a_motor_winding_resistance_follows_its_temperature(paper):
    losses = {"model": "datasheet", "torque_constant": "0.39 N*m/A", "terminal_resistance": "5.70 ohm",
              "resistance_temperature": "20 degC", "friction_torque": "0 N*m", "viscous_damping": "0 N*m*s/rad"}
    motor = paper.system.sources["screw_motor"]
    source = MotorSource.model_validate({"model": "motor", "shaft": motor.shaft, "into": dict(motor.into),
                                         "losses": losses})
    system = with_values(paper, {"sources.screw_motor": source}).system
    point = point_of(system, "I")
    heat = source_heats(system, point, {"screw_motor": 333.15})["screw_motor"]
    # 60 °C: R = 5.70·(235 + 60)/(235 + 20) = 6.594118 Ω; copper 1.5 (M/k_T)² R, no drag declared.
    assert heat.details["terminal_resistance_ohm"] == pytest.approx(5.70 * 295 / 255, rel=1e-12)
    torque = heat.details["torque_Nm"]
    assert heat.power == pytest.approx(1.5 * (torque / 0.39) ** 2 * 5.70 * 295 / 255, rel=1e-12)


def test_the_thread_grease_thins_with_the_thread_temperature(paper):
    system = with_values(paper, {"sources.screw_nut.grease_viscosity": None, "sources.screw_nut.grease": VG100,
                                 "sources.screw_nut.grease_density": 880.0}).system
    point = point_of(system)
    # η = ρ ν = 880 kg/m³ · 100e-6 m²/s = 0.088 Pa·s at 40 °C.
    hot = source_heats(system, point, {"screw_nut": 313.15})["screw_nut"]
    assert hot.details["grease_viscosity_Pa_s"] == pytest.approx(0.088, rel=1e-9)
    cold = source_heats(system, point, {"screw_nut": 298.15})["screw_nut"]
    assert cold.details["grease_torque_Nm"] > hot.details["grease_torque_Nm"]
    # the grease torque is linear in η (physics.screw_nut): the ratio of torques is the ratio of viscosities
    assert cold.details["grease_torque_Nm"] / hot.details["grease_torque_Nm"] == pytest.approx(
        cold.details["grease_viscosity_Pa_s"] / 0.088, rel=1e-9)


GREASE = {"grade": "ISO VG 100", "viscosity_100C": "11 mm^2/s"}


def paper_data():
    text, origin = read_text("paper")
    return parse_toml(text, origin)


@pytest.mark.parametrize("changes, message", [
    ({"grease": GREASE, "grease_density": "880 kg/m^3"}, "grease_viscosity or grease: give one"),
    ({"grease_viscosity": None}, "grease_viscosity or grease: give one"),
    ({"grease_density": "880 kg/m^3"}, "grease_density: give it with grease"),
])
def test_the_grease_is_declared_one_way(changes, message):
    data = paper_data()
    thread = data["sources"]["screw_nut"]
    for key, value in changes.items():
        if value is None:
            del thread[key]
        else:
            thread[key] = value
    with pytest.raises(DescriptionError, match=message):
        validate_data(data, "variant")


def test_a_coupling_not_named_is_refused():
    data = paper_data()
    data["temperatures"]["coupling"] = "sometimes"
    with pytest.raises(DescriptionError, match="coupling"):
        validate_data(data, "variant")


def test_a_lagging_reading_moves_only_the_values_beyond_the_tolerance():
    evaluated = LocalTemperatures(surfaces={"a": 300.0, "b": 300.0}, sources={"m": 310.0})
    now = LocalTemperatures(surfaces={"a": 300.09, "b": 299.8}, sources={"m": 310.25})
    lagging = now.lagging(evaluated, 0.1)
    # a moved by 0.09 K (within 0.1 K): kept at 300; b by 0.2 K and m by 0.25 K: moved
    assert lagging.surfaces == {"a": 300.0, "b": 299.8}
    assert lagging.sources == {"m": 310.25}
    assert lagging.largest_change(now) <= 0.1


def test_a_memo_recomputes_only_the_surfaces_whose_temperature_or_point_changed(paper, surface_evaluations):
    system = paper.system
    point = point_of(system)
    reading = {name: 300.0 + 0.1 * i for i, name in enumerate(system.surfaces)}
    plain = boundary_conditions_at(system, point, temperatures=LocalTemperatures(surfaces=reading))
    memo = EvaluationMemo()
    first = boundary_conditions_at(system, point, temperatures=LocalTemperatures(surfaces=reading), memo=memo)
    computed = surface_evaluations
    computed.clear()  # what the second evaluation computes
    moved = dict(reading, worktable=reading["worktable"] + 1.0)
    second = boundary_conditions_at(system, point, temperatures=LocalTemperatures(surfaces=moved), memo=memo)
    assert computed == ["worktable"]
    assert all(second.surfaces[n] is first.surfaces[n] for n in system.surfaces if n != "worktable")
    assert second.surfaces["worktable"].convection > first.surfaces["worktable"].convection  # warmer: larger h
    # the values and the labelled range warnings are those of an evaluation without the memo
    assert first.surfaces == plain.surfaces and first.warnings == plain.warnings
    assert second.warnings == boundary_conditions_at(system, point,
                                                     temperatures=LocalTemperatures(surfaces=moved)).warnings
    # another operating point recomputes every surface
    computed.clear()
    boundary_conditions_at(system, point_of(system, "I"), temperatures=LocalTemperatures(surfaces=moved), memo=memo)
    assert sorted(computed) == sorted(system.surfaces)


@pytest.fixture
def source_evaluations(monkeypatch):
    """The names of the sources whose heat the boundary conditions compute, in order, from now on."""
    from feedtherm.boundary import heat

    computed = []
    for function in ("_guideway", "_sliding_screw", "_bearing", "_motor"):
        def counted(name, *args, original=getattr(heat, function)):
            computed.append(name)
            return original(name, *args)
        monkeypatch.setattr(heat, function, counted)
    return computed


def test_a_memo_recomputes_only_the_sources_whose_inputs_changed(paper, source_evaluations):
    system = paper.system
    point = point_of(system, "I")  # both shafts turn
    # at 500 K the bearings' oil is thinner than Walther's equation holds for: their heats come with warnings
    hot = {name: 500.0 for name in system.sources}
    memo = EvaluationMemo()
    first = boundary_conditions_at(system, point, temperatures=LocalTemperatures(sources=hot), memo=memo)
    assert sorted(source_evaluations) == sorted(system.sources)
    assert any(w.startswith("sources: kinematic_viscosity_Walther") for w in first.warnings)
    source_evaluations.clear()
    warmer = dict(hot, rear_bearing=501.0)
    second = boundary_conditions_at(system, point, temperatures=LocalTemperatures(sources=warmer), memo=memo)
    # the bearing, and the motor whose shaft it loads; the nut's side and the thread as last evaluated
    assert source_evaluations == ["rear_bearing", "screw_motor"]
    assert second.heats["nut_motor"] is first.heats["nut_motor"]
    assert second.heats["rear_bearing"].power < first.heats["rear_bearing"].power  # thinner oil, less drag
    # the heats, to the last digit, and the labelled range warnings are those of an evaluation without the memo
    fresh = boundary_conditions_at(system, point, temperatures=LocalTemperatures(sources=warmer))
    assert second.heats == fresh.heats
    assert second.warnings == fresh.warnings
    # a memo needs the record of the warnings its sources replay
    with pytest.raises(TypeError, match="memo and records"):
        source_heats(system, point, warmer, memo={})
    # another operating point recomputes every source
    source_evaluations.clear()
    boundary_conditions_at(system, point_of(system, "III"), temperatures=LocalTemperatures(sources=warmer), memo=memo)
    assert sorted(source_evaluations) == sorted(system.sources)


def test_a_memo_takes_an_overlays_reference_condition_once(paper, monkeypatch):
    from feedtherm import boundary
    from feedtherm.plan import with_mode

    loaded = with_mode(paper, "paper")  # the printed values over the physics, scaled by its ratio to condition I
    system, overlay = loaded.system, loaded.overlay
    point = point_of(system, "II")
    evaluated = []
    physics = boundary._physics

    def counted(system, point, **options):
        evaluated.append(point)
        return physics(system, point, **options)

    monkeypatch.setattr(boundary, "_physics", counted)
    memo = EvaluationMemo()
    readings = [LocalTemperatures({n: t for n in system.surfaces}, {n: t + 1.0 for n in system.sources})
                for t in (301.0, 302.0)]
    first = boundary_conditions_at(system, point, overlay, temperatures=readings[0], memo=memo)
    second = boundary_conditions_at(system, point, overlay, temperatures=readings[1], memo=memo)
    reference = point_of(system, overlay.reference_condition)
    # condition II at each reading, and the reference condition once: its physics is at the frozen temperatures
    assert evaluated == [point, reference, point]
    for kept, reading in zip((first, second), readings):
        fresh = boundary_conditions_at(system, point, overlay, temperatures=reading)
        assert kept.heats == fresh.heats and kept.surfaces == fresh.surfaces and kept.warnings == fresh.warnings
