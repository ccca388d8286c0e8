"""Inverse heat estimation from measured time series: the transient response is the model's own
run (superposition of 1 W per group), each sample is weighted by its declared uncertainty, and a
heat changed in the model that made the series is recovered within its interval.

The bench is ballscrew_example with its condition v10 cut to 20 min (frozen coefficients, so the
runs are linear in the heats).
"""

import numpy as np
import pytest

from feedtherm.analysis.inverse import Noise, infer_conditions, parse_groups, transient_transfer
from feedtherm.system.measurements import read_measurements
from feedtherm.benches import bench
from feedtherm.boundary import boundary_conditions
from feedtherm.errors import FeedthermError
from feedtherm.models.options import ModelOptions
from feedtherm.simulate import simulate
from feedtherm.system.load import load_system
from feedtherm.system.paths import get_path
from feedtherm.system.variants import with_values

STEP = ModelOptions(motion="averaged", averaged_step=10.0, max_step=10.0)
TIMES = np.arange(0.0, 1201.0, 120.0)
DRAG = "sources.ball_nut.torque"


#: v10's duration in the bench's description, the line that a 20-min copy shortens.
V10_DURATION = 'duration = "8 h"\ndescription = "10 m/min"\n'


@pytest.fixture(scope="module")
def short(tmp_path_factory):
    text = (bench("ballscrew_example").folder / "description.toml").read_text(encoding="utf-8")
    assert V10_DURATION in text
    path = tmp_path_factory.mktemp("inverse") / "short.toml"
    path.write_text(text.replace(V10_DURATION, V10_DURATION.replace('"8 h"', '"20 min"'), 1), encoding="utf-8")
    loaded = load_system(str(path))
    assert loaded.system.temperatures.coupling == "frozen"
    return loaded


def test_the_loss_models_heats_give_the_models_own_run(short):
    """Superposition: baseline(t) + R(t)·q_prior is the run at the loss models' heats, to round-off."""
    groups = parse_groups(None, list(short.system.sources))
    response = transient_transfer(short, "v10", groups, {"T3": TIMES, "D": TIMES[1:]})
    run = simulate(short, condition="v10", motion="averaged", options=STEP, sample_interval=10.0)
    predicted = response.predict(response.prior)
    n = len(TIMES)
    np.testing.assert_allclose(predicted[:n], np.interp(TIMES, run.times, run.sensors["T3"]), rtol=1e-10)
    np.testing.assert_allclose(predicted[n:], np.interp(TIMES[1:], run.times, run.elongation), rtol=1e-8, atol=1e-13)
    assert response.observations == ["T3"] * n + ["D"] * (n - 1)
    assert predicted[n:].max() > 40e-6  # the elongation grew: a response, not zeros


def test_a_changed_heat_is_recovered_from_the_series_each_sample_weighted_by_its_own_uncertainty(short, tmp_path):
    drag = float(get_path(short.system, DRAG))
    truth = with_values(short, {DRAG: 1.5 * drag})  # the series' machine: half as much nut drag again
    run = simulate(truth, condition="v10", motion="averaged", options=STEP, sample_interval=10.0)
    rng = np.random.default_rng(11)
    lines = ["condition,time [min],quantity,value,unit,uncertainty"]
    for name in ("T1", "T3", "T4"):  # temperatures with their own 0.1 K
        values = np.interp(TIMES, run.times, run.sensors_celsius()[name]) + rng.normal(0.0, 0.1, len(TIMES))
        lines += [f"v10,{t / 60:g},{name},{v:.4f},degC,0.1" for t, v in zip(TIMES, values)]
    d_um = np.interp(TIMES, run.times, run.elongation_um) + rng.normal(0.0, 0.5, len(TIMES))
    lines += [f"v10,{t / 60:g},D,{v:.4f},um," for t, v in zip(TIMES, d_um)]  # none declared: --sigma-elongation
    (tmp_path / "series.csv").write_text("\n".join(lines) + "\n")
    data = read_measurements(str(tmp_path / "series.csv"), sensors=list(short.system.sensors))

    noise = Noise(temperature=0.5, elongation=0.5e-6)
    [result] = infer_conditions(short, data, ["v10"], noise=noise)
    assert result.transient and len(result.observations) == 4 * len(TIMES)
    elongation = np.array([n == "D" for n in result.observations])
    np.testing.assert_allclose(result.sigma[~elongation], 0.1)  # the file's, not the 0.5 K of --sigma-temperature
    np.testing.assert_allclose(result.sigma[elongation], 0.5e-6)
    assert result.declared[~elongation].all() and not result.declared[elongation].any()
    residual = (result.measured - result.fitted) / np.where(elongation, 0.5e-6, 0.1)
    assert result.chi2 == pytest.approx(float(residual @ residual), rel=1e-9)

    # the series' heats: the nut's drag half as much again, and the motor that turns against it
    # a little more (its copper losses follow its torque)
    heats = boundary_conditions(truth.system, "v10").heats
    nut = next(e for e in result.estimates if e.group == "ball_nut")
    assert heats["ball_nut"].power == pytest.approx(1.5 * nut.loss_model, rel=1e-9)
    assert nut.low <= heats["ball_nut"].power <= nut.high, nut
    assert nut.high - nut.low < 0.1 * heats["ball_nut"].power and nut.resolution > 0.95
    for e in result.estimates:  # the others the data resolve are found too
        if e.resolution > 0.5:
            assert e.low <= heats[e.group].power <= e.high, e


def test_a_zero_uncertainty_fails_in_one_line_before_any_run(short, tmp_path, monkeypatch):
    def no_runs(*args, **kwargs):
        raise AssertionError("a run started")

    monkeypatch.setattr("feedtherm.analysis.inverse.transient_transfer", no_runs)
    monkeypatch.setattr("feedtherm.analysis.inverse.transfer", no_runs)
    path = tmp_path / "zero.csv"
    path.write_text("condition,time [min],quantity,value,unit,uncertainty\nv10,0,T1,20.0,degC,0.1\n"
                    "v10,10,T1,21.0,degC,0\nv5,0,T1,20.0,degC,0.1\n")
    data = read_measurements(str(path), sensors=list(short.system.sensors))
    with pytest.raises(FeedthermError) as failure:
        infer_conditions(short, data, ["v5", "v10"], noise=Noise(0.5, 2e-6))
    message = str(failure.value)
    assert "\n" not in message and str(path) in message and "v10 T1" in message and "600 s is 0" in message
