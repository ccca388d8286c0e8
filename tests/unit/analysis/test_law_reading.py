"""A law file read through the checked reader (analysis/compensation/law_files.py) evaluates exactly as
the parsed document did before the checks existed: not a bit of any output changes."""

from __future__ import annotations

import json

import numpy as np
import pytest
from law_documents import every_document

from feedtherm.analysis.compensation.apply import read_law
from feedtherm.analysis.compensation.evaluator import CompensationLaw
from feedtherm.analysis.compensation.kalman import KalmanLaw
from feedtherm.analysis.compensation.law_files import nesting_depth, read_law_document

DOCUMENTS = every_document()
TIMES = np.arange(0.0, 7200.0, 37.0)


def _stream(names, seed=8):
    rng = np.random.default_rng(seed)
    drift = np.cumsum(rng.normal(0, 0.05, (len(TIMES), len(names))), axis=0)
    return [{n: 293.15 + 3 * np.sin(t / 900.0 + i) + drift[j, i] for i, n in enumerate(names)}
            for j, t in enumerate(TIMES)]


def _outputs(law: CompensationLaw) -> list[float]:
    out = []
    for t, readings in zip(TIMES, _stream(law.inputs)):
        if law.stroke:
            out.append(law.update(t, readings, 0.2))
            out += [law.at(x) for x in (0.1, 0.1234, 0.3)]
        elif law.posterior is not None:
            out += list(law.update_with_sd(t, readings))
        else:
            out.append(law.update(t, readings))
    return out


@pytest.mark.parametrize("name", ["law", "law_static", "law_adapted", "law_stroke"])
def test_a_written_law_evaluates_to_the_bit_as_before(tmp_path, name):
    path = tmp_path / f"{name}.json"
    path.write_text(json.dumps(DOCUMENTS[name], indent=2))
    before = _outputs(CompensationLaw(json.loads(path.read_text())))  # the reader before the checks
    for law in (CompensationLaw.from_file(path), read_law(path)):
        after = _outputs(law)
        assert np.array_equal(np.array(after), np.array(before))  # exactly, not approximately
        assert np.array(after).tobytes() == np.array(before).tobytes()
    assert read_law_document(path) == (json.loads(path.read_text()), [])  # the document handed on untouched


def test_a_written_kalman_estimator_evaluates_to_the_bit_as_before(tmp_path):
    path = tmp_path / "law_kalman.json"
    path.write_text(json.dumps(DOCUMENTS["law_kalman"]))
    runs = []
    for law in (KalmanLaw.build(json.loads(path.read_text())), KalmanLaw.from_file(path)):
        estimator = law.estimator()
        out = []
        for j, (t, readings) in enumerate(zip(TIMES, _stream(["T1", "ambient"]))):
            out += estimator.update(t, readings, 500.0 * (j % 3), 0.0)
            out.append(estimator.stroke_error(0.17))
        runs.append(np.array(out))
    assert runs[0].tobytes() == runs[1].tobytes()


@pytest.mark.parametrize("text, depth", [
    ("1", 0), ("[]", 1), ('{"a": [[1], {"b": []}]}', 4), ('{"a": "[[[[{{{"}', 1), (r'["\"[[[", [[]]]', 3), ("", 0),
])
def test_nesting_is_counted_on_the_text_with_strings_skipped(text, depth):
    assert nesting_depth(text) == depth
