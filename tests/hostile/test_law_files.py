"""Law files (``law*.json``) handed to ``feedtherm correct`` and to the Python API: every hand-edited,
truncated or foreign document is refused in one line naming the file, the key and the reason, exit 2,
nothing written (analysis/compensation/law_files.py, law_schema.py, kalman_schema.py)."""

from __future__ import annotations

import copy
import json
from pathlib import Path

import pytest
from law_documents import LOG, every_document  # tests/: the writers' documents

from feedtherm import cli
from feedtherm.analysis.compensation import law_files
from feedtherm.analysis.compensation.evaluator import CompensationLaw
from feedtherm.analysis.compensation.kalman import KalmanLaw
from feedtherm.errors import FeedthermError

FORMAT = "feedtherm-compensation-law"
#: D = b + w T1 + v L(T1), one lag of 600 s (the hand law of tests/integration/test_cli_correct.py).
HAND = {"format": FORMAT, "version": 1, "kind": "linear_regression", "inputs": [{"name": "T1"}],
        "lags_s": [600.0], "bias_m": -6.0e-3, "weights_m_per_K": [[1.0e-5, 1.0e-5]]}
DOCUMENTS = every_document()


def _with(document: dict, path: str, value) -> dict:
    """``document`` with the value at the dotted ``path`` (``weights_m_per_K.0.1``) replaced; ``value``
    ``DROP`` deletes the key."""
    out = copy.deepcopy(document)
    *parents, last = [int(p) if p.isdigit() else p for p in path.split(".")]
    node = out
    for p in parents:
        node = node[p]
    if value is DROP:
        del node[last]
    else:
        node[last] = value
    return out


DROP = object()


def _text(document: dict, replace: tuple[str, str] | None = None) -> str:
    text = json.dumps(document)
    if replace is not None:
        assert replace[0] in text, replace
        text = text.replace(*replace)
    return text


def _write(folder: Path, law: str | bytes, log: str = LOG) -> None:
    (folder / "law.json").write_bytes(law if isinstance(law, bytes) else law.encode("utf-8"))
    (folder / "log.csv").write_text(log)


# --------------------------------------------------------------------------- the audit's cases

# The bias -6e-3 m is written "-0.006" by json.dumps, the weights 1e-05.
AUDIT = {
    "a lag of 0 s divides by zero": (_text(_with(HAND, "lags_s.0", 0)), ("law.json: lags_s[0]: 0 s must be above 0",)),
    "weights nested 100,000 deep": ('{"weights_m_per_K": ' + "[" * 100_000 + "]" * 100_000 + "}",
                                    ("law.json: objects or lists nest deeper than 16 levels",)),
    "a NaN weight": (_text(HAND, ("1e-05]]", "NaN]]")),
                     ("law.json: weights_m_per_K[0][1]: NaN is not a finite number",)),
    "an Infinity bias": (_text(HAND, ("-0.006", "Infinity")), ("law.json: bias_m: Infinity is not a finite number",)),
    "coefficients of 1e308": (_text(_with(HAND, "weights_m_per_K", [[1e308, 1e308]])),
                              ("law.json: weights_m_per_K[0][0]: 1e+308 m/K lies beyond ±0.01 m/K",)),
    "a negative lag": (_text(_with(HAND, "lags_s.0", -600.0)), ("law.json: lags_s[0]: -600 s must be above 0",)),
    "true as a weight": (_text(_with(HAND, "weights_m_per_K.0.0", True)),
                         ("law.json: weights_m_per_K[0][0]: true is a boolean, not a number",)),
    "a bias given as text": (_text(_with(HAND, "bias_m", "-6e-3")),
                             ("law.json: bias_m: '-6e-3' is text, not a number; write the number without quotes",)),
    "inputs [T1, T1]": (_text({**HAND, "inputs": [{"name": "T1"}, {"name": "T1"}],
                               "weights_m_per_K": [[1e-5, 1e-5], [1e-5, 1e-5]]}),
                        ("law.json: inputs[1]: 'T1' is inputs[0] already",)),
    "an input named T1 and a newline": (_text(_with(HAND, "inputs.0.name", "T1\n")),
                                        ("law.json: inputs[0].name: 'T1\\n' is not a sensor name",)),
    "a JSON list": ("[1, 2]", ("law.json: a law document is a JSON object", "not a list")),
    "a law with no inputs": (_text({**HAND, "inputs": [], "weights_m_per_K": []}), ("law.json: inputs: must not be empty",)),
}


@pytest.mark.parametrize("case", list(AUDIT))
def test_the_audits_hand_edited_laws_are_refused(tmp_path, refused, case):
    text, says = AUDIT[case]
    _write(tmp_path, text)
    refused("correct", "law.json", "log.csv", says=says)


# --------------------------------------------------------------------------- what the schema adds

SCHEMA = {
    "1e400, beyond a float": (_text(HAND, ("-0.006", "1e400")), ("law.json: bias_m: 1e400 is not a finite number",)),
    "-Infinity as a lag": (_text(HAND, ("600.0", "-Infinity")), ("law.json: lags_s[0]: -Infinity is not a finite",)),
    "an integer of 5,000 digits": (_text(HAND, ("-0.006", "1" + "0" * 5000)),
                                   ("law.json: bias_m:", "(5001 digits) is not a finite number")),
    "a key given twice": ('{"format": "' + FORMAT + '", "bias_m": 1, "bias_m": 2}',
                          ("law.json: the key 'bias_m' appears twice in one object",)),
    "a misspelt key": (_text({**HAND, "weigths_m_per_K": [[1e-5, 1e-5]]}),
                       ("law.json: unknown key 'weigths_m_per_K'; did you mean 'weights_m_per_K'?",)),
    "an unknown key with a newline": (_text({**HAND, "a\nb": 1}), ("law.json: unknown key 'a\\nb'",)),
    "a missing bias": (_text(_with(HAND, "bias_m", DROP)), ("law.json: bias_m: missing (required)",)),
    "a foreign format": (_text(_with(HAND, "format", "other")),
                         ("law.json: not a law feedtherm can evaluate: not a feedtherm-compensation-law document",)),
    "a version of true": (_text(_with(HAND, "version", True)), ("law.json: version: true is a boolean, not a whole number",)),
    "a version of 1.0": (_text(_with(HAND, "version", 1.0)), ("law.json: version: 1.0 is not a whole number",)),
    "a law of D that says it gives E": (_text(_with(DOCUMENTS["law"], "output.name", "E")),
                                        ("law.json: output.name: 'E', but a law of this kind gives 'D'",)),
    "an unknown kind": (_text(_with(HAND, "kind", "neural")), ("law.json: kind: 'neural' is not allowed",)),
    "a stroke law of version 1": (_text({**DOCUMENTS["law_stroke"], "version": 1}),
                                  ("law.json: version: 1 is not allowed; allowed values: 2",)),
    "a row of weights too many": (_text(_with(HAND, "weights_m_per_K", [[1e-5, 1e-5], [1e-5, 1e-5]])),
                                  ("law.json: weights_m_per_K: 2 entries, expected 1 (one row per input)",)),
    "a weight missing for the lag": (_text(_with(HAND, "weights_m_per_K", [[1e-5]])),
                                     ("law.json: weights_m_per_K[0]: 1 entry, expected 2 (the reading and its lag)",)),
    "a weight of 2 cm/K": (_text(_with(HAND, "weights_m_per_K.0.0", 0.02)),
                           ("law.json: weights_m_per_K[0][0]: 0.02 m/K lies beyond ±0.01 m/K",)),
    "a bias of 20 m": (_text(_with(HAND, "bias_m", 20.0)), ("law.json: bias_m: 20 m lies beyond ±10 m",)),
    "a lag of 1e8 s": (_text(_with(HAND, "lags_s.0", 1e8)), ("law.json: lags_s[0]: 1e+08 s lies above 1e+07 s",)),
    "an input in degC": (_text(_with(HAND, "inputs.0.unit", "degC")),
                         ("law.json: inputs[0].unit: 'degC' is not allowed; allowed values: 'K'",)),
    "an input named with a space": (_text(_with(HAND, "inputs.0.name", "T 1")),
                                    ("law.json: inputs[0].name: 'T 1' is not a sensor name",)),
    "an input named by a number": (_text(_with(HAND, "inputs.0.name", 1)), ("law.json: inputs[0].name: 1 is not text",)),
    "an input that is a string": (_text(_with(HAND, "inputs.0", "T1")),
                                  ("law.json: inputs[0]: must be an object {...}, not text ('T1')",)),
    "null": ("null", ("law.json: a law document is a JSON object", "not null")),
    "an empty file": ("", ("law.json: not JSON: Expecting value at line 1, column 1",)),
    "a truncated file": (_text(HAND)[:40], ("law.json: not JSON:",)),
    "not UTF-8": (b"\xff\xfe{", ("law.json: is not UTF-8 text",)),
    # the blocks compensate writes
    "a reference at 5 K": (_text(_with(DOCUMENTS["law"], "reference.temperature_K", 5.0)),
                           ("law.json: reference.temperature_K: 5 K lies outside",)),
    "a list as a law of D's reference output": (_text(_with(DOCUMENTS["law"], "reference.output_m", [0.0, 0.0])),
                                                ("law.json: reference.output_m: a law of D gives one number",)),
    "an envelope without an input": (_text(_with(DOCUMENTS["law"], "envelope.inputs.T2", DROP)),
                                     ("law.json: envelope.inputs: no entry for the input 'T2'",)),
    "an envelope of another input": (_text(_with(DOCUMENTS["law"], "envelope.inputs.T9",
                                                 DOCUMENTS["law"]["envelope"]["inputs"]["T1"])),
                                     ("law.json: envelope.inputs: 'T9' is not an input of the law",)),
    "an envelope upside down": (_text(_with(DOCUMENTS["law"], "envelope.inputs.T1.min_K", 400.0)),
                                ("law.json: envelope.inputs.T1: min_K (400 K) lies above max_K",)),
    "a posterior centre too short": (_text(_with(DOCUMENTS["law_adapted"], "posterior.centre_K", [293.15])),
                                     ("law.json: posterior.centre_K: 1 entry, expected 6",)),
    "a posterior covariance not square": (
        _text(_with(DOCUMENTS["law_adapted"], "posterior.covariance.3", [0.0])),
        ("law.json: posterior.covariance[3]: 1 entry, expected 7 (a square matrix)",)),
    "a posterior covariance not symmetric": (
        _text(_with(DOCUMENTS["law_adapted"], "posterior.covariance.2.1", 1e-9)),
        ("law.json: posterior.covariance[2][1]: 1e-09, but [1][2] is", "a covariance is symmetric")),
    "a negative variance": (_text(_with(DOCUMENTS["law_adapted"], "posterior.covariance.0.0", -1e-12)),
                            ("law.json: posterior.covariance[0][0]: -1e-12 is a negative variance",)),
    "a standard deviation of 2 m": (_text(_with(DOCUMENTS["law_adapted"], "posterior.covariance.0.0", 4.0)),
                                    ("law.json: posterior.covariance[0][0]: a standard deviation of 2 m",)),
    "a negative noise": (_text(_with(DOCUMENTS["law_adapted"], "posterior.noise_sigma_m", -1e-6)),
                         ("law.json: posterior.noise_sigma_m: -1e-06 m must not be negative",)),
    "a stroke law of order 11": (_text(_with(DOCUMENTS["law_stroke"], "basis.order", 11)),
                                 ("law.json: basis.order: 11 must not be above 10",)),
    "a stroke law's bias too short": (_text(_with(DOCUMENTS["law_stroke"], "bias_m", [0.0, 0.0])),
                                      ("law.json: bias_m: 2 entries, expected 3 (one per Legendre order 0..2)",)),
    "a stroke law's weights of another order": (
        _text(_with(DOCUMENTS["law_stroke"], "weights_m_per_K.1.2", [0.0])),
        ("law.json: weights_m_per_K[1][2]: 1 entry, expected 3 (one per Legendre order 0..2)",)),
    "a stroke backwards": (_text(_with(DOCUMENTS["law_stroke"], "position.x_max_m", 0.05)),
                           ("law.json: position: x_max_m (0.05 m) must lie at least 1 µm above x_min_m (0.1 m)",)),
    "a stroke 1 km long": (_text(_with(DOCUMENTS["law_stroke"], "position.x_max_m", 1000.0)),
                           ("law.json: position.x_max_m: 1000 m lies beyond ±100 m",)),
    "a basis of another kind": (_text(_with(DOCUMENTS["law_stroke"], "basis.kind", "chebyshev")),
                                ("law.json: basis.kind: 'chebyshev' is not allowed; allowed values: 'legendre'",)),
}


@pytest.mark.parametrize("case", list(SCHEMA))
def test_what_the_schema_refuses(tmp_path, refused, case):
    text, says = SCHEMA[case]
    _write(tmp_path, text)
    argv = ["correct", "law.json", "log.csv"] + (["--x", "150 mm"] if '"linear_regression_stroke"' in str(text) else [])
    refused(*argv, says=says)


def test_a_directory_a_missing_file_and_a_too_large_file(tmp_path, refused, monkeypatch):
    (tmp_path / "log.csv").write_text(LOG)
    (tmp_path / "law.json").mkdir()
    refused("correct", "law.json", "log.csv", says=("law.json: is a directory, not a file",))
    refused("correct", "nothing.json", "log.csv", says=("nothing.json: no such law file",))
    (tmp_path / "law.json").rmdir()
    (tmp_path / "law.json").write_text(json.dumps(HAND))
    monkeypatch.setattr(law_files, "MAX_LAW_BYTES", 100)
    refused("correct", "law.json", "log.csv", says=("law.json: is larger than the 0 MB a law may have",))


def test_a_kalman_estimator_is_not_run_by_correct(tmp_path, refused):
    _write(tmp_path, json.dumps(DOCUMENTS["law_kalman"]))
    refused("correct", "law.json", "log.csv", says=("law.json: a Kalman estimator needs the motor speeds",))


# --------------------------------------------------------------------------- possible but suspect


def test_a_reference_output_the_law_does_not_give_is_a_warning(tmp_path, warned):
    # D at 293.15 K = -6e-3 + 2e-5 x 293.15 = -137 µm; the file says 0
    _write(tmp_path, json.dumps({**HAND, "reference": {"temperature_K": 293.15, "output_m": 0.0}}))
    warned("correct", "law.json", "log.csv", says=("warning: law.json: reference.output_m: the file says 0 µm at "
                                                   "293.15 K, but the law gives -137 µm there",))
    stroke = _with(DOCUMENTS["law_stroke"], "reference.output_m.1", 1e-6)
    _write(tmp_path, json.dumps(stroke))
    warned("correct", "law.json", "log.csv", "--x", "150 mm", "--out", "out2",
           says=("warning: law.json: reference.output_m[1]: the file says 1 µm",))


@pytest.mark.parametrize("name", ["law", "law_static", "law_adapted", "law_stroke"])
def test_the_writers_laws_run_without_a_warning(tmp_path, name, capsys):
    """The starting points of the cases above are valid."""
    _write(tmp_path, json.dumps(DOCUMENTS[name]))
    x = ["--x", "150 mm"] if name == "law_stroke" else []
    code = cli.main(["correct", str(tmp_path / "law.json"), str(tmp_path / "log.csv"), "--out", str(tmp_path / "out"), *x])
    out, err = capsys.readouterr()
    assert code == 0 and "warning" not in out + err, out + err


# --------------------------------------------------------------------------- the Python API reads the same way


def test_the_api_refuses_in_the_same_line(tmp_path):
    _write(tmp_path, _text(_with(HAND, "lags_s.0", 0)))
    with pytest.raises(FeedthermError) as caught:
        CompensationLaw.from_file(tmp_path / "law.json")
    assert str(caught.value) == f"{tmp_path / 'law.json'}: lags_s[0]: 0 s must be above 0 (a lag's time constant: " \
                                "0 divides by zero, a negative one grows without bound, and no machine takes 116 days " \
                                "to follow its hall)"


def test_a_non_finite_result_at_the_reference_state_is_refused():
    """The last guard (the schema's bounds leave nothing to it): the law evaluated at its reference state."""
    document = _with(HAND, "weights_m_per_K", [[1e308, 1e308]])
    with pytest.raises(FeedthermError, match=r"^law.json: the law gives inf m with every input and lag at 293.15 K"):
        law_files._probe_regression(document, "law.json")


KALMAN = {
    "an asymmetric model": ("model.A0.0.1", 1e-3, "model.A0[0][1]: 0.001, but [1][0] is 0; the reduced model is symmetric"),
    "an unstable model": ("model.A0", [[1e-3, 0.0], [0.0, -1e-3]],
                          "table.h_stopped_W_per_m2K: the reduced model is not stable there"),
    "a sensor of no uncertainty": ("inputs.0.sigma_K", 0.0, "inputs[0].sigma_K: sigma_K 0 K"),
    "no ambient": ("inputs.1.role", DROP, "inputs: 0 inputs have the role 'ambient (model input)'"),
    "a sensor the model does not output": ("inputs.0.name", "T7", "inputs[0]: 'T7' is not among model.outputs"),
    "speeds going back": ("table.screw_rpm", [1000.0, 0.0], "table.screw_rpm[1]: 0 does not lie above"),
    "a matrix of another order": ("model.Cy.1", [1e-5], "model.Cy[1]: 1 entry, expected 2 (the model's order)"),
    "a negative coefficient": ("table.h_W_per_m2K.0.0.0", -5.0, "table.h_W_per_m2K[0][0][0]: -5.0 must not be below 0"),
    "an initial uncertainty of 1e300 K": ("noise.initial_K", 1e300, "noise.initial_K: 1e+300 K lies above 100 K"),
    "D not an output": ("model.outputs.1", "T2", "model.outputs: no 'D'; the estimator's output is D"),
    "the stroke positions backwards": ("stroke.x_m", [0.3, 0.1], "stroke.x_m[1]: 0.1 does not lie above"),
}


@pytest.mark.parametrize("case", list(KALMAN))
def test_a_kalman_document_is_checked_when_the_api_reads_it(tmp_path, case):
    path, value, says = KALMAN[case]
    (tmp_path / "law_kalman.json").write_text(json.dumps(_with(DOCUMENTS["law_kalman"], path, value)))
    with pytest.raises(FeedthermError) as caught:
        KalmanLaw.from_file(tmp_path / "law_kalman.json")
    line = str(caught.value)
    assert line.startswith(f"{tmp_path / 'law_kalman.json'}: ") and says in line and "\n" not in line, line
    with pytest.raises(FeedthermError, match="^the Kalman law document: "):
        KalmanLaw.from_document(_with(DOCUMENTS["law_kalman"], path, value))


def test_a_valid_kalman_document_reads_and_a_regression_law_is_not_one(tmp_path):
    (tmp_path / "law_kalman.json").write_text(json.dumps(DOCUMENTS["law_kalman"]))
    estimator = KalmanLaw.from_file(tmp_path / "law_kalman.json").estimator()
    d, sd = estimator.update(0.0, {"T1": 293.15, "ambient": 293.15}, 0.0, 0.0)
    assert abs(d) < 1e-12 and sd > 0
    with pytest.raises(FeedthermError, match="not a feedtherm Kalman law document"):
        KalmanLaw.from_document(HAND)
