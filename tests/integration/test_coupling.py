"""The nonlinear coupling: coefficients and heats that follow the simulated temperatures.

A variant of the paper bench with ``temperatures.coupling = "nonlinear"`` and its bearings on an
ISO VG 100 oil (so their heat depends on temperature too).  What must hold: the energy balance
closes on every run, a long transient ends at the coupled steady state, the steady state is a
fixed point of the coupling, the coupling tolerance converges, and the coupled values move the
way the laws say (natural convection grows with the surface's rise, oil thins as it warms).
"""

from __future__ import annotations

import numpy as np
import pytest

from feedtherm.boundary import boundary_conditions
from feedtherm.models import integrator as integrator_module
from feedtherm.models.options import ModelOptions
from feedtherm.simulate import simulate, steady_solve
from feedtherm.system.load import parse_toml, read_text, validate_data

SENSORS = ["T1", "T2", "T3", "T4", "T5"]


def variant(coupling):
    text, origin = read_text("paper")
    data = parse_toml(text, origin)
    data["temperatures"]["coupling"] = coupling
    for source in data["sources"].values():
        if source.get("model") == "bearing" and source.get("friction_model") != "constant":  # the others' oil
            source.pop("lubricant_viscosity", None)
            source["lubricant"] = {"grade": "ISO VG 100", "viscosity_100C": "11 mm^2/s"}
    return validate_data(data, f"paper ({coupling})")


@pytest.fixture(scope="module")
def coupled():
    return variant("nonlinear")


@pytest.fixture(scope="module")
def frozen():
    return variant("frozen")


@pytest.mark.parametrize("condition, motion", [("I", "resolved"), ("V", "averaged")])
def test_a_coupled_run_closes_its_energy_balance(coupled, condition, motion):
    run = simulate(coupled, condition=condition, motion=motion)
    assert run.info["coupling"] == "nonlinear"
    assert run.info["coupling_updates"] > 5  # the coefficients did move with the temperatures
    assert abs(run.energy.relative_error) < 1e-4


def test_a_coupled_duty_cycle_re_evaluates_each_segment_and_closes_its_balance(coupled):
    """Motion, then standstill: each segment starts from its own evaluation (its operating point)."""
    run = simulate(coupled, cycle="I_then_standstill", motion="averaged")
    assert run.info["coupling_updates"] > len(coupled.system.duty_cycles["I_then_standstill"].segments)
    assert abs(run.energy.relative_error) < 1e-4
    assert run.info["heat_W"]["screw_motor"] == 0.0  # the last segment stands still


def test_a_long_coupled_transient_ends_at_the_coupled_steady_state(coupled):
    steady = steady_solve(coupled, "V").values()
    run = simulate(coupled, condition="V", motion="averaged", duration=40 * 3600.0, sample_interval=600.0)
    for name in SENSORS:
        assert run.final[name] == pytest.approx(steady[name], abs=0.1), name
    assert run.final["D"] == pytest.approx(steady["D"], abs=0.5e-6)
    # the run's own steady value is the coupled one
    assert run.steady["T4"] == pytest.approx(steady["T4"], abs=1e-3)


def test_the_coupled_steady_state_is_a_fixed_point(coupled):
    solved = steady_solve(coupled, "III")
    integrator = solved.integrator
    bc = integrator.steady_boundary_conditions(0, solved.segment.bc, solved.state)
    # solving once more with the boundary conditions evaluated at the solution changes nothing
    loads = integrator.loads(0, bc, solved.k)
    again = integrator.steady(0, bc, solved.k, rhs=loads.heat + loads.ambient.source)
    assert np.max(np.abs(again - solved.state)) < 1e-3
    # the coefficients are those of the surfaces' own temperatures, not the frozen 10 K rise
    frozen = boundary_conditions(coupled.system, "III")
    reading = integrator.readout(solved.state)
    hot, cool = max(reading.surfaces, key=reading.surfaces.get), min(reading.surfaces, key=reading.surfaces.get)
    assert reading.surfaces[hot] - 293.15 > 10.0 > reading.surfaces[cool] - 293.15
    for name in ("rear_bearing", "nut_bearing"):  # the front pair's catalogue drag has no viscosity
        warm = reading.sources[name] > 303.15
        nu, nu_frozen = (b.heats[name].details["lubricant_viscosity_m2_per_s"] for b in (bc, frozen))
        assert (nu < nu_frozen) == warm, name


def test_link_changes_kept_on_the_right_hand_side_give_the_refactorised_answer(coupled, monkeypatch):
    """A step keeps its factorised matrix while the links moved by less than LINK_REFACTOR of
    themselves or LINK_RATE_REFACTOR times the capacity, taking the change explicitly; the
    answer is that of refactorising at every re-evaluation."""
    kept = simulate(coupled, condition="I")
    monkeypatch.setattr(integrator_module, "LINK_REFACTOR", 0.0)
    monkeypatch.setattr(integrator_module, "LINK_RATE_REFACTOR", 0.0)
    every = simulate(coupled, condition="I")
    assert every.info["coupling_updates"] == kept.info["coupling_updates"] > 5
    for name in SENSORS:
        assert np.max(np.abs(kept.sensors[name] - every.sensors[name])) < 2e-3, name
    assert np.max(np.abs(kept.elongation - every.elongation)) < 0.01e-6


def test_refreshing_only_the_readings_that_moved_gives_the_answer_of_refreshing_all(coupled, monkeypatch,
                                                                                       surface_evaluations):
    """A transient's re-evaluation moves the readings beyond REFRESH_SHARE of the tolerance and keeps the
    others (and their surfaces' coefficients) as last evaluated: each reading still lags by at most the
    tolerance, and the answer is that of refreshing every reading at every re-evaluation."""
    computed = surface_evaluations
    kept = simulate(coupled, condition="I")
    kept_count = len(computed)
    monkeypatch.setattr(integrator_module, "REFRESH_SHARE", 0.0)  # every reading that moved at all
    computed.clear()
    every = simulate(coupled, condition="I")
    assert len(computed) > 1.5 * kept_count  # the surfaces that had hardly moved were not recomputed
    assert kept.info["coupling_updates"] > 5
    for name in SENSORS:  # measured: 2.1e-3 K and 8e-3 µm at most over condition I's 3 h
        assert np.max(np.abs(kept.sensors[name] - every.sensors[name])) < 5e-3, name
    assert np.max(np.abs(kept.elongation - every.elongation)) < 0.02e-6


def test_the_coupling_tolerance_converges(coupled):
    runs = {tol: simulate(coupled, condition="III", motion="averaged", options=ModelOptions(coupling_tolerance=tol))
            for tol in (0.5, 0.05)}
    for name in SENSORS:
        assert runs[0.5].final[name] == pytest.approx(runs[0.05].final[name], abs=0.05), name
    assert runs[0.5].final["D"] == pytest.approx(runs[0.05].final["D"], abs=0.2e-6)
    assert runs[0.05].info["coupling_updates"] > runs[0.5].info["coupling_updates"]


def test_coupling_changes_the_answer_the_way_the_laws_say(coupled, frozen):
    """At III, against the frozen values (every surface and winding 10 K above the ambient): a naturally
    cooled surface warmer than that gets a larger film coefficient (h grows as ΔT^(1/4)), a cooler one a
    smaller; a motor winding warmer than that a larger resistance (copper). Which way the sensors then
    move is the balance of these, and of the heats they change, on the bench as declared."""
    solved = steady_solve(coupled, "III")
    bc = solved.integrator.steady_boundary_conditions(0, solved.segment.bc, solved.state)
    still = boundary_conditions(coupled.system, "III")
    reading = solved.integrator.readout(solved.state)
    frozen_at = 293.15 + 10.0
    natural = [n for n, s in coupled.system.surfaces.items() if s.convection.kind == "natural"]
    checked = 0
    for name in natural:
        if abs(reading.surfaces[name] - frozen_at) > 0.5:
            warmer = reading.surfaces[name] > frozen_at
            assert (bc.surfaces[name].convection > still.surfaces[name].convection) == warmer, name
            checked += 1
    assert checked >= 3
    for motor in ("screw_motor", "nut_motor"):
        warmer = reading.sources[motor] > frozen_at
        resistance = [b.heats[motor].details["terminal_resistance_ohm"] for b in (bc, still)]
        assert (resistance[0] > resistance[1]) == warmer, motor
    hot = {c: steady_solve(c_, "III").values() for c, c_ in (("coupled", coupled), ("frozen", frozen))}
    assert hot["coupled"]["T4"] != pytest.approx(hot["frozen"]["T4"], abs=0.05)  # the coupling acts


@pytest.fixture(scope="module")
def fe_cache(tmp_path_factory):
    pytest.importorskip("gmsh")
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("FEEDTHERM_CACHE", str(tmp_path_factory.mktemp("feedtherm-cache")))
        yield


@pytest.mark.parametrize("condition", ["I", "V"])
def test_the_coupled_fe_model_agrees_with_the_coupled_fast_model(coupled, fe_cache, condition):
    """The FE acceptance (|ΔT| < 1 K at T1–T5, |ΔD| < 2 µm, medium mesh), with the coupling on in both."""
    fem = steady_solve(coupled, condition, model="fem", mesh="medium").values()
    fast = steady_solve(coupled, condition).values()
    diff = {n: fem[n] - fast[n] for n in [*SENSORS, "D"]}
    assert all(abs(diff[n]) < 1.0 for n in SENSORS), diff
    assert abs(diff["D"]) < 2e-6, diff


def test_a_coupled_fe_run_closes_its_energy_balance(coupled, fe_cache):
    run = simulate(coupled, condition="V", model="fem", mesh="coarse", motion="averaged", duration=3600.0)
    assert run.info["coupling_updates"] > 5
    assert abs(run.energy.relative_error) < 1e-4


def strongly_coupled(coupled, preload=700.0):
    """Copper windings whose resistance follows their temperature (IEC 60034-1) under a thread
    preload of ``preload`` [N]: the circulating torque makes hundreds of watts that grow by
    1/(235 + θ) per kelvin of the windings."""
    from feedtherm.system.sources import MotorSource
    from feedtherm.system.variants import with_values

    changes = {"sources.screw_nut.preload": preload}
    for name in ("screw_motor", "nut_motor"):
        motor = coupled.system.sources[name]
        changes[f"sources.{name}"] = MotorSource.model_validate({
            "model": "motor", "shaft": motor.shaft, "into": dict(motor.into),
            "losses": {"model": "datasheet", "torque_constant": "0.39 N*m/A", "terminal_resistance": "5.70 ohm",
                       "resistance_temperature": "20 degC", "friction_torque": "0.02 N*m",
                       "viscous_damping": "2e-5 N*m*s/rad"}})
    return with_values(coupled, changes)


def test_a_strong_coupling_converges_to_its_fixed_point(coupled):
    solved = steady_solve(strongly_coupled(coupled), "I")
    integrator = solved.integrator
    bc = integrator.steady_boundary_conditions(0, solved.segment.bc, solved.state)
    loads = integrator.loads(0, bc, solved.k)
    again = integrator.steady(0, bc, solved.k, rhs=loads.heat + loads.ambient.source)
    assert np.max(np.abs(again - solved.state)) < 1e-2  # a fixed point, to the iteration's tolerance
    assert bc.heats["screw_motor"].details["terminal_resistance_ohm"] > 5.70 * 1.2  # hot windings


def test_a_runaway_beyond_the_accepted_temperatures_is_reported_in_one_line(coupled):
    """At 3000 N the iterates pass 1000 degC, where the air's and the oils' properties end:
    reported as the runaway it is, naming the hot source, not as a correlation's refusal."""
    from feedtherm.errors import ModelError

    with pytest.raises(ModelError, match=r"^temperatures.coupling = nonlinear: \w+ reaches [\d.]+ degC, outside "
                                         r"-150 to 1000 degC .*thermal runaway") as caught:
        steady_solve(strongly_coupled(coupled, preload=3000.0), "I")
    assert "\n" not in str(caught.value)


def test_a_diverging_steady_iteration_is_reported(coupled, monkeypatch):
    """Plain Picard steps at 1500 N oscillate with a growing amplitude: the iteration's own
    detector stops it after two growing changes, in one line, never iterating forever (the
    range guard, which would stop it first, is widened to let the detector act)."""
    from feedtherm.errors import ModelError
    from feedtherm.system.quantities import Limit
    import feedtherm.models.integrator as integrator

    monkeypatch.setattr(integrator, "TEMPERATURE_LIMIT", Limit(0.0, 1e5, "K", "degC", "widened"))
    monkeypatch.setattr(integrator, "MIN_RELAXATION", 1.0)
    monkeypatch.setattr(integrator, "RUNAWAY_ITERATIONS", 2)
    with pytest.raises(ModelError, match="the steady iteration diverges"):
        steady_solve(strongly_coupled(coupled, preload=1500.0), "I")
