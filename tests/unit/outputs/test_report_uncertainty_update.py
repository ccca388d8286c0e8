"""The report's sampling paragraph names a Bayesian update as such, and a calibration folder as before."""

from feedtherm.outputs.report.uncertainty import _sampling_text


def summary(calibration):
    return {"settings": {"seed": 0}, "parameters": [{}] * 3, "system": "bundled:paper",
            "sets": [{"label": "prior", "runs": 5}, {"label": "calibrated", "runs": 5, "calibration": calibration}]}


def test_an_update_is_described_as_the_priors_updated_with_measurements():
    text = _sampling_text(summary({"method": "Bayesian update of the declared priors, Laplace approximation",
                                   "fit_conditions": ["I", "II", "IV"], "noise_scale_s2": 4.0}), "5–95 %")
    assert "every declared prior updated with the measured final values of conditions I, II, IV" in text
    assert "noise scale s² 4" in text


def test_a_calibration_folder_is_described_as_before():
    text = _sampling_text(summary({"fit_conditions": ["I", "II"]}), "5–95 %")
    assert "samples the posterior of the calibration fitted on conditions I, II." in text


def test_the_predictive_set_is_described_with_its_model_error():
    document = summary({"method": "Bayesian update of the declared priors, Laplace approximation",
                        "fit_conditions": ["I"], "noise_scale_s2": 4.0})
    document["sets"].append({"label": "predictive", "runs": 0,
                             "model_error": {"noise_scale_s2": 4.0, "sd": {"T1": 1.0, "T2": 1.0, "D_um": 4.0}}})
    text = _sampling_text(document, "5–95 %")
    assert "5 runs for the calibrated set" in text and "runs for the predictive set" not in text
    assert "s·σ T1, T2 1.00 K; D 4.00 µm" in text and "posterior predictive" in text
