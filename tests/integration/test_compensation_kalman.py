"""The model-based estimator (issue 16): it tracks a simulated run whose sensors carry noise within
its own predicted uncertainty, learns a heat error, and its exported document gives the same D."""

import json

import numpy as np
import pytest

from feedtherm.analysis.compensation.kalman import KalmanEstimator, KalmanLaw, run_filter
from feedtherm.analysis.compensation.operating_table import build_table
from feedtherm.analysis.compensation.state_space import coefficients, reduce_model
from feedtherm.boundary import boundary_conditions_at
from feedtherm.boundary.operating import OperatingPoint
from feedtherm.simulate import simulate
from feedtherm.system.load import load_system
from feedtherm.system.variants import with_values

SENSORS = ["T1", "T2", "T3", "T4", "T5"]
NOISE_K = 0.1
#: The filter's RMS error along the stroke this test accepts [m]: its first run gave 0.093 µm
#: (0.34 µm at most) against E of 22.5 µm RMS, 18.5 µm from one end of the stroke to the other at 2 h
STROKE_RMS_M = 0.3e-6


@pytest.fixture(scope="module")
def frozen():
    """The bench at frozen coefficients: the linear model the filter's model reduces."""
    return with_values(load_system("paper"), {"temperatures.coupling": "frozen"})


@pytest.fixture(scope="module")
def law(frozen):
    model = reduce_model(frozen, [*SENSORS, "D"], OperatingPoint(1116.0, 1080.0, 293.15, 0.010))
    table = build_table(frozen.system, model.surfaces, model.sources, 293.15)
    return KalmanLaw(model, table, tuple(SENSORS), (NOISE_K,) * len(SENSORS))


@pytest.fixture(scope="module")
def run(frozen):
    """Condition II's speeds for 2 h on another machine: front bearing +15 %, thread -15 %; noisy sensors."""
    machine = with_values(frozen, {"sources.front_bearing.heat_factor": 1.15, "sources.screw_nut.heat_factor": 0.85})
    solution = simulate(machine, condition="II", duration=7200.0, motion="averaged", sample_interval=60.0)
    rng = np.random.default_rng(0)
    names = [*SENSORS, "T6"]
    readings = np.column_stack([solution.sensors[n] for n in names])
    readings[:, :len(SENSORS)] += rng.normal(0.0, NOISE_K, (len(readings), len(SENSORS)))
    return solution, names, readings


def test_the_filter_tracks_a_noisy_run_within_its_own_uncertainty(law, run):
    solution, names, readings = run
    estimator = law.estimator()
    speeds = np.full(len(readings), 1116.0), np.full(len(readings), 1080.0)
    d, sd = run_filter(estimator, solution.times, readings, names, *speeds)
    error = d - solution.elongation
    # within 0.8 µm RMS: the 1.5 % of D's 54 µm rise this test asked before issue 32 gave the front
    # support its catalogue drag (the rise is now 40 µm, the filter's error the same 0.63 µm); the
    # 0.5 µm of 35 µm it asked when D was a read point on the screw
    assert np.sqrt(np.mean(error ** 2)) < 0.8e-6
    assert np.mean(np.abs(error) <= 2 * sd) >= 0.9
    z = np.sqrt(np.mean((error / sd) ** 2))
    assert 0.3 < z < 1.5, z  # neither overconfident nor uselessly wide
    learned = dict(zip(law.model.sources, estimator.heat_errors))
    assert learned["front_bearing"] == pytest.approx(0.15, abs=0.05)


def test_the_exported_document_gives_the_same_estimates(law, run):
    solution, names, readings = run
    again = KalmanLaw.from_document(json.loads(json.dumps(law.document())))
    speeds = np.full(len(readings), 1116.0), np.full(len(readings), 1080.0)
    first = run_filter(law.estimator(), solution.times, readings, names, *speeds)
    second = run_filter(again.estimator(), solution.times, readings, names, *speeds)
    np.testing.assert_allclose(second[0], first[0], rtol=0, atol=1e-12)
    np.testing.assert_allclose(second[1], first[1], rtol=0, atol=1e-12)


def test_the_reduced_model_is_stable_and_holds_a_machine_at_the_ambient(law):
    model = law.model
    for h in (law.table.h_stopped, law.table.h[0, 0], law.table.h[-1, -1]):
        A, f = model.matrices(h)
        assert np.linalg.eigvalsh((A + A.T) / 2).max() < 0
        # at 25 °C throughout, without heat, nothing moves: A ζ + T∞ f = 0
        np.testing.assert_allclose(A @ (model.uniform * 298.15) + 298.15 * f, 0.0, atol=1e-9 * np.abs(f).max() * 298)


def test_the_table_interpolates_heats_and_coefficients_within_one_percent(frozen, law):
    table = law.table
    screw, relative = (table.screw_rpm[1] + table.screw_rpm[2]) / 2, (table.relative_rpm[1] + table.relative_rpm[2]) / 2
    h, q = table.at(screw, screw - relative)
    bc = boundary_conditions_at(frozen.system, OperatingPoint(screw, screw - relative, table.ambient, 0.010))
    h_true, q_true = coefficients(bc, law.model.surfaces, law.model.sources)
    np.testing.assert_allclose(q, q_true, rtol=0.01)
    np.testing.assert_allclose(h, h_true, rtol=0.01)
    h0, q0 = table.at(0.0, 0.0)
    assert np.all(q0 == 0.0) and np.all(h0 > 0.0)  # a standstill: no heat, natural convection


def test_the_filter_state_read_along_the_stroke_tracks_the_positioning_error(law, run):
    """Issue 34, item 3: the reduced state read under the nut at the study's 9 table positions
    follows the run's E(x, t) (the full model's, on another machine, noisy sensors)."""
    from types import SimpleNamespace

    from feedtherm.analysis.compensation.data import stroke_error_at, stroke_positions

    solution, names, readings = run
    positions = stroke_positions(solution.table_x)
    np.testing.assert_allclose(law.model.stroke_x, positions, rtol=0, atol=1e-12)
    record = SimpleNamespace(times=solution.times, sensors=readings, positions=positions,
                             screw_rpm=np.full(len(readings), 1116.0), nut_rpm=np.full(len(readings), 1080.0))
    predicted = law.predict_stroke_record(record, names)
    truth = stroke_error_at(solution, positions)
    error = predicted - truth
    assert predicted.shape == (len(solution.times), 9)
    assert np.sqrt(np.mean(error ** 2)) < STROKE_RMS_M, np.sqrt(np.mean(error ** 2))
    assert np.ptp(truth[-1]) > 5e-6  # E does change along the stroke: the test is not of a constant


def test_the_exported_document_gives_the_same_error_along_the_stroke_and_refuses_a_bad_x(law, run):
    solution, names, readings = run
    document = json.loads(json.dumps(law.document()))
    assert len(document["stroke"]["x_m"]) == 9 and document["stroke"]["multiply_adds_per_sample"] == 2 * law.model.order + 1
    first, second = law.estimator(), KalmanLaw.from_document(document).estimator()
    lo, hi = document["stroke"]["x_m"][0], document["stroke"]["x_m"][-1]
    xs = [lo, lo + 0.3 * (hi - lo), (lo + hi) / 2, document["stroke"]["x_m"][5], hi]
    columns = {n: names.index(n) for n in (*SENSORS, "T6")}
    for n, t in enumerate(solution.times[:30]):
        values = {name: readings[n, j] for name, j in columns.items()}
        first.update(t, values, 1116.0, 1080.0)
        second.update(t, values, 1116.0, 1080.0)
        for x in xs:
            assert second.stroke_error(x) == pytest.approx(first.stroke_error(x), abs=1e-12)
    record = type("Record", (), {"times": solution.times[:30], "sensors": readings[:30], "positions": np.array(xs),
                                 "screw_rpm": np.full(30, 1116.0), "nut_rpm": np.full(30, 1080.0)})()
    np.testing.assert_allclose(law.predict_stroke_record(record, names)[-1], [first.stroke_error(x) for x in xs],
                               rtol=0, atol=1e-12)
    for bad, words in ((hi + 0.01, "outside the stroke"), (float("nan"), "not a finite"), ("far", "not a table position")):
        with pytest.raises(ValueError, match=f"^x: .*{words}"):
            second.stroke_error(bad)


def test_cycles_filtered_side_by_side_equal_the_filter_run_one_by_one(law, run):
    from types import SimpleNamespace

    solution, names, readings = run
    n = len(readings)
    rng = np.random.default_rng(3)
    records = []
    for screw, nut in ((1116.0, 1080.0), (396.0, 360.0), (2214.0, 2160.0)):  # three speed schedules
        switch = np.where(np.arange(n) < n // 2, 1.0, 0.5)  # the speeds halve half-way
        records.append(SimpleNamespace(times=np.asarray(solution.times, float),
                                       sensors=readings + rng.normal(0.0, 0.05, readings.shape),
                                       screw_rpm=screw * switch, nut_rpm=nut * switch, positions=None))
    one_by_one = [run_filter(law.estimator(), r.times, r.sensors, names, r.screw_rpm, r.nut_rpm)[0] for r in records]
    batch = KalmanLaw(law.model, law.table, law.sensors, law.sigma, law.noise)
    batch.filter_records(records, names)
    for record, expected in zip(records, one_by_one):
        np.testing.assert_allclose(batch.predict_record(record, names), expected, rtol=0, atol=1e-12)


def test_a_law_keeps_the_states_of_its_last_records_only(law, run, monkeypatch):
    from types import SimpleNamespace

    from feedtherm.analysis.compensation import kalman

    monkeypatch.setattr(kalman, "KEPT_RECORDS", 2)
    solution, names, readings = run
    speeds = np.full(len(readings), 1116.0), np.full(len(readings), 1080.0)
    records = [SimpleNamespace(times=np.asarray(solution.times, float), sensors=readings + k * 0.1,
                               screw_rpm=speeds[0], nut_rpm=speeds[1], positions=None) for k in range(3)]
    fresh = KalmanLaw(law.model, law.table, law.sensors, law.sigma, law.noise)
    first = [fresh.predict_record(r, names) for r in records]
    assert [entry[0] for entry in fresh._runs.values()] == records[1:]  # the oldest dropped
    np.testing.assert_array_equal(fresh.predict_record(records[0], names), first[0])  # filtered again, the same
