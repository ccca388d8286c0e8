"""Property-based fuzzing of law files: the contract ``feedtherm correct`` and the Python API keep.

Each example takes a valid law document of one kind, as feedtherm's writers write it
(tests/law_documents.py: a law of D with lags, a static one, an adapted one with its posterior, a
stroke law, a Kalman estimator; and a law written by hand), and mutates it: a value replaced (NaN,
±inf, 1e308, a boolean, text, null, a list, an object, a name with a newline), scaled, dropped,
duplicated, renamed or nested deeper; an input duplicated; or the text itself edited (a number
written NaN, Infinity or 1e400, a key given twice, the file cut short, nested 10,000 deep).

The contract, for a regression law run by ``feedtherm correct`` in this process over a measurement
log: exit 0 and every number of ``correction.csv`` and ``correction.json`` finite; or exit 2, one line
on stderr and nothing written.  A Kalman estimator is read by ``KalmanLaw.from_file`` and run over a
few readings: a one-line ``FeedthermError``, or finite estimates.  Any other exception, a traceback,
or an example slower than the deadline is a defect.

The suite runs a fixed-seed budget (``FEEDTHERM_FILE_FUZZ_EXAMPLES``, default 300); ``make fuzz`` runs 1,000.
"""

from __future__ import annotations

import contextlib
import copy
import csv
import io
import json
import math
import os
import tempfile
from datetime import timedelta
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st
from law_documents import LOG, every_document

from feedtherm import cli
from feedtherm.analysis.compensation.kalman import KalmanLaw
from feedtherm.errors import FeedthermError

EXAMPLES = int(os.environ.get("FEEDTHERM_FILE_FUZZ_EXAMPLES", "300"))
HAND = {"format": "feedtherm-compensation-law", "version": 1, "kind": "linear_regression",
        "inputs": [{"name": "T1"}], "lags_s": [600.0], "bias_m": -6.0e-3, "weights_m_per_K": [[1.0e-5, 1.0e-5]]}
DOCUMENTS = {**every_document(), "hand": HAND}

ODD_VALUES = [math.nan, math.inf, -math.inf, 1e308, -1e308, 5e-324, 0, 0.0, -1, -1.0, 1e-3, 1e3, True, False, None,
              "", "abc", "1e-5", "T1\n", "T1", "ambient", "D", [], {}, [[]], [1.0], {"name": "T1"}, 10 ** 30,
              "\u2028", "x" * 300]


def _paths(data, prefix=()):
    """Every path into the document: (keys..., ) for each object entry and list item."""
    out = []
    items = data.items() if isinstance(data, dict) else enumerate(data) if isinstance(data, list) else ()
    for key, value in items:
        out.append((*prefix, key))
        if len(out) < 4000:  # the Kalman matrices: their first entries are as good as all
            out.extend(_paths(value, (*prefix, key))[:200])
    return out


PATHS = {name: [p for p in _paths(d) if p[0] != "provenance"] for name, d in DOCUMENTS.items()}


def _scaled(value, factor):
    if isinstance(value, bool):
        return not value
    if isinstance(value, (int, float)):
        return value * factor
    return value


TEXT_EDITS = ["nan", "infinity", "1e400", "twice", "cut", "deep", "bom", "garbage"]


@st.composite
def mutated(draw):
    name = draw(st.sampled_from(sorted(DOCUMENTS)))
    data = copy.deepcopy(DOCUMENTS[name])
    kind = draw(st.sampled_from(["odd", "odd", "scale", "drop", "duplicate", "rename", "nest", "input", "text"]))
    if kind == "input":  # an input read twice, or one more input than weights
        data["inputs"].append(copy.deepcopy(data["inputs"][draw(st.integers(0, len(data["inputs"]) - 1))]))
        return name, "duplicate input", json.dumps(data)
    if kind == "text":
        edit = draw(st.sampled_from(TEXT_EDITS))
        text = json.dumps(data)
        numbers = [i for i, c in enumerate(text) if c in "0123456789" and text[i - 1] in " [-"]
        at = numbers[draw(st.integers(0, len(numbers) - 1))] if numbers else 0
        end = at
        while end < len(text) and text[end] in "0123456789.e-+":
            end += 1
        replacement = {"nan": "NaN", "infinity": "-Infinity", "1e400": "1e400"}.get(edit)
        if replacement is not None:
            text = text[:at] + replacement + text[end:]
        elif edit == "twice":
            text = text.replace("{", '{"kind": "linear_regression", ', 1)
        elif edit == "cut":
            text = text[:draw(st.integers(0, len(text) - 1))]
        elif edit == "deep":
            text = text[:at] + "[" * 10_000 + "1" + "]" * 10_000 + text[end:]
        elif edit == "bom":
            text = "\ufeff" + text
        else:
            text = text[:at] + "\x00\u00e9" + text[at:]
        return name, f"text {edit}", text
    path = draw(st.sampled_from(PATHS[name]))
    parent = data
    for key in path[:-1]:
        parent = parent[key]
    key = path[-1]
    if kind == "odd":
        parent[key] = copy.deepcopy(draw(st.sampled_from(ODD_VALUES)))
    elif kind == "scale":
        parent[key] = _scaled(parent[key], draw(st.sampled_from([0.0, -1.0, 1e-9, 1e3, 1e9, 1e300, math.nan])))
    elif kind == "drop":
        del parent[key]
    elif kind == "duplicate":
        if isinstance(parent, list):
            parent.append(copy.deepcopy(parent[key]))
        else:
            parent[f"{key}_copy"] = copy.deepcopy(parent[key])
    elif kind == "rename":
        if isinstance(parent, dict):
            parent[f"{key}x"] = parent.pop(key)
        else:
            parent[key] = "ghost"
    else:
        for _ in range(draw(st.sampled_from([1, 3, 40]))):
            parent[key] = [parent[key]]
    return name, f"{kind} {'.'.join(map(str, path))}", json.dumps(data)


def _finite_files(folder: Path) -> None:
    """Every number written by ``correct`` is finite."""
    with open(folder / "correction.csv", newline="", encoding="utf-8") as handle:
        for row in csv.DictReader(handle):
            for key, cell in row.items():
                if key in ("condition", "outside_envelope") or cell == "":
                    continue
                assert math.isfinite(float(cell)), (key, cell)

    def refuse(text):
        raise AssertionError(f"correction.json holds {text}")

    json.loads((folder / "correction.json").read_text(encoding="utf-8"), parse_constant=refuse)


def run_correct(argv: list[str]) -> tuple[int, str, str]:
    """``feedtherm argv`` in this process: its exit code, stdout and stderr."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = cli.main(argv)
    return code, out.getvalue(), err.getvalue()


def check_outcome(code: int, out: str, err: str, folder: Path, what: str) -> None:
    """The contract of the module's notes for one run of ``correct`` writing to ``folder``."""
    assert "Traceback" not in out + err, what
    if code == 0:
        _finite_files(folder)
        event("corrected with finite numbers")
        return
    assert code == 2, (what, code, err)
    lines = [line for line in err.splitlines() if line.strip()]
    assert len(lines) == 1, (what, err)
    assert not folder.exists(), (what, "written although refused")
    event("refused in one line")


def _kalman(text: str, folder: Path, what: str) -> None:
    (folder / "law_kalman.json").write_text(text, encoding="utf-8")
    try:
        law = KalmanLaw.from_file(folder / "law_kalman.json")
    except FeedthermError as exc:
        assert str(exc) and "\n" not in str(exc), (what, str(exc))
        event("Kalman: refused in one line")
        return
    estimator = law.estimator()
    values = []
    for j, t in enumerate(np.arange(0.0, 1800.0, 60.0)):
        values += estimator.update(t, {n: 295.0 + 0.01 * j for n in (*law.sensors, law.model.ambient)}, 800.0, 0.0)
    assert np.all(np.isfinite(values)), what
    event("Kalman: read and ran finite")


@pytest.mark.filterwarnings("error::RuntimeWarning")  # numpy's overflow or 0/0 on the way is a defect too
@settings(max_examples=EXAMPLES, derandomize=True, deadline=timedelta(seconds=10), database=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(mutated())
def test_a_mutated_law_is_refused_in_one_line_or_corrects_with_finite_numbers(example):
    name, mutation, text = example
    what = f"{name}: {mutation}"
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        if name == "law_kalman":
            _kalman(text, folder, what)
            return
        (folder / "law.json").write_text(text, encoding="utf-8")
        (folder / "log.csv").write_text(LOG, encoding="utf-8")
        x = ["--x", "150 mm,300 mm"] if name == "law_stroke" else []
        code, out, err = run_correct(["correct", str(folder / "law.json"), str(folder / "log.csv"),
                                      "--out", str(folder / "out"), *x])
        check_outcome(code, out, err, folder / "out", what)


def test_the_unmutated_laws_correct():
    """The fuzzer's starting points pass the contract's healthy branch."""
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        (folder / "log.csv").write_text(LOG, encoding="utf-8")
        for name, document in DOCUMENTS.items():
            if name == "law_kalman":
                continue
            (folder / "law.json").write_text(json.dumps(document), encoding="utf-8")
            x = ["--x", "150 mm"] if name == "law_stroke" else []
            code, out, err = run_correct(["correct", str(folder / "law.json"), str(folder / "log.csv"),
                                          "--out", str(folder / name), *x])
            assert code == 0, (name, err)
            _finite_files(folder / name)
