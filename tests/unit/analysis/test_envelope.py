"""A law's training envelope and the samples outside it (analysis/compensation/envelope.py), by hand."""

import warnings

import numpy as np
import pytest

from feedtherm.analysis.compensation.envelope import envelope_flags, training_envelope, windowed_rates
from feedtherm.analysis.compensation.law_files import check_law
from feedtherm.errors import FeedthermError


def _law_with(envelope, inputs=("A",)) -> dict:
    """A law of D on ``inputs`` carrying ``envelope`` (the law's file validates it, :mod:`.law_schema`)."""
    return {"format": "feedtherm-compensation-law", "version": 1, "kind": "linear_regression",
            "inputs": [{"name": n} for n in inputs], "lags_s": [], "bias_m": 0.0,
            "weights_m_per_K": [[1e-6] for _ in inputs], "envelope": envelope}


def test_rates_over_the_window_by_hand():
    # samples every 30 s, a 60 s window: each rate is the change since the sample 60 s before
    times = np.array([0.0, 30.0, 60.0, 90.0, 120.0])
    values = np.array([[290.0], [290.3], [290.6], [291.5], [292.4]])
    rates = windowed_rates(times, values, 60.0)[:, 0]
    # 0 s, 30 s: no sample 60 s before -> 0; 60 s: (290.6 - 290.0)/60 = 0.01 K/s;
    # 90 s: (291.5 - 290.3)/60 = 0.02 K/s; 120 s: (292.4 - 290.6)/60 = 0.03 K/s
    assert rates == pytest.approx([0.0, 0.0, 0.01, 0.02, 0.03])


def test_a_window_below_the_times_rounding_takes_the_rate_since_the_previous_sample():
    # 60 - 5e-324 == 60 in floating point: a sample must not pair with itself (0 / 0)
    times = np.array([0.0, 30.0, 60.0])
    values = np.array([[290.0], [290.3], [290.9]])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        rates = windowed_rates(times, values, 5e-324)[:, 0]
    assert rates == pytest.approx([0.0, 0.3 / 30, 0.6 / 30])  # 0 s: no sample before it


def test_the_envelope_of_two_cycles_by_hand():
    cycle1 = (np.array([0.0, 60.0, 120.0]), np.array([[293.0, 290.0], [294.2, 290.0], [294.8, 291.2]]))
    cycle2 = (np.array([0.0, 60.0]), np.array([[292.0, 291.0], [292.3, 291.6]]))
    env = training_envelope([cycle1, cycle2], ["A", "B"])
    # A: min 292.0, max 294.8; rates 1.2/60 = 0.02, 0.6/60 = 0.01, 0.3/60 = 0.005 -> 0.02 K/s
    # B: min 290.0, max 291.6; rates 0, 1.2/60 = 0.02, 0.6/60 = 0.01 -> 0.02 K/s
    assert env["inputs"]["A"] == pytest.approx({"min_K": 292.0, "max_K": 294.8, "max_rate_K_per_s": 0.02})
    assert env["inputs"]["B"] == pytest.approx({"min_K": 290.0, "max_K": 291.6, "max_rate_K_per_s": 0.02})
    assert env["rate_window_s"] == 60.0 and check_law(_law_with(env, ("A", "B")), "law.json") == []


def test_samples_outside_are_flagged_with_the_input_and_by_how_much():
    env = {"inputs": {"A": {"min_K": 292.0, "max_K": 294.8, "max_rate_K_per_s": 0.02}}, "rate_window_s": 60.0}
    times = np.array([0.0, 60.0, 120.0, 180.0])
    flags = envelope_flags(env, times, {"A": np.array([293.0, 291.5, 292.5, 295.3])})
    # 0 s inside; 60 s 0.5 K below, and falling (291.5 - 293.0)/60 = -0.025 K/s = 1.5 K/min, faster than
    # 0.02 K/s = 1.2 K/min; 120 s inside, rate (292.5 - 291.5)/60 = 0.017 <= 0.02;
    # 180 s 0.5 K above, and (295.3 - 292.5)/60 = 0.047 K/s = 2.8 K/min, faster than 1.2 K/min
    assert flags[0] == "" and flags[2] == ""
    assert flags[1] == "A 0.5 K below its training range; A changing at 1.5 K/min, faster than its training's 1.2 K/min"
    assert flags[3] == "A 0.5 K above its training range; A changing at 2.8 K/min, faster than its training's 1.2 K/min"


@pytest.mark.parametrize("envelope, reason", [
    ([], "envelope: must be an object {...}, not a list"),
    ({"inputs": {}, "rate_window_s": 60.0}, "envelope.inputs: no entry for the input 'A'"),
    ({"inputs": {"A": {"min_K": 300.0, "max_K": 290.0, "max_rate_K_per_s": 0.1}}, "rate_window_s": 60.0},
     "envelope.inputs.A: min_K (300 K) lies above max_K (290 K)"),
    ({"inputs": {"A": {"min_K": 290.0, "max_K": 300.0, "max_rate_K_per_s": float("nan")}}, "rate_window_s": 60.0},
     "envelope.inputs.A.max_rate_K_per_s: nan is not a number"),
    ({"inputs": {"A": {"min_K": 290.0, "max_K": 300.0, "max_rate_K_per_s": 0.1}}, "rate_window_s": 0},
     "envelope.rate_window_s: 0 s must be above 0"),
    ({"inputs": {"A": {"min_K": True, "max_K": 300.0, "max_rate_K_per_s": 0.1}}, "rate_window_s": 60},
     "envelope.inputs.A.min_K: true is a boolean, not a number"),
    ({"inputs": {"A": {"min_K": 290.0, "max_K": 300.0, "max_rate_K_per_s": -0.1}}, "rate_window_s": 60},
     "envelope.inputs.A.max_rate_K_per_s: -0.1 must not be below 0"),
])
def test_a_bad_envelope_block_is_refused(envelope, reason):
    with pytest.raises(FeedthermError) as caught:
        check_law(_law_with(envelope), "law.json")
    assert str(caught.value).startswith("law.json: ") and reason in str(caught.value), str(caught.value)
