"""Property-based fuzzing of measurement files (docs/measurements.md): the contract their readers keep.

Each example takes a valid measurement file, the first lines of a bench's own (the ballscrew example's
time series of a condition, its drift test with the air and the deviations E at targets, the paper's
final values) or a log of T1-T3 and D, and edits it as a careless hand or a foreign logger would: a
cell replaced (``nan``, ``inf``, ``1e400``, ``1e308``, an empty cell, text, a unit, another quantity, a
negative time, Arabic digits, a Unicode minus, a NUL), a line dropped, doubled or swapped, a blank or
comment line put in, a header cell changed, a column added or removed, the file cut short, its line
ends CRLF, or the whole file encoded in UTF-16 or Latin-1.

Every example goes through both readers' paths:

- ``validate``'s: :func:`~feedtherm.system.measurements.read_description_measurements` against the
  bench's description (its sensors, runs and their durations, the air, the table's travel, the
  targets its tests visit): a one-line ``DescriptionError``, or a set whose every time and value is
  finite;
- ``feedtherm correct``, in this process, with a law of D on T1 and T2, its adapted form (D and its
  standard deviation) or a stroke law on T1-T3 at three positions: exit 0 and every number
  written finite, or exit 2 with one line and nothing written
  (:func:`test_fuzz_laws.check_outcome`).

Any other exception, a traceback or an example slower than the deadline is a defect.  The suite runs
a fixed-seed budget (``FEEDTHERM_FILE_FUZZ_EXAMPLES``, default 300); ``make fuzz`` runs 1,000.
"""

from __future__ import annotations

import json
import os
import tempfile
from datetime import timedelta
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st
from law_documents import LOG, regression_documents, stroke_document
from test_fuzz_laws import check_outcome, run_correct

from feedtherm.benches import bench
from feedtherm.errors import FeedthermError
from feedtherm.system.load import load_system
from feedtherm.system.measurements import read_description_measurements

EXAMPLES = int(os.environ.get("FEEDTHERM_FILE_FUZZ_EXAMPLES", "300"))
SYSTEMS = {name: load_system(name) for name in ("ballscrew_example", "paper")}
#: The laws the files are run through: of D on T1, T2 with two lags, adapted (with its sd), along the stroke (T1-T3).
LAWS = {**{name: json.dumps(regression_documents()[name]) for name in ("law", "law_adapted")},
        "law_stroke": json.dumps(stroke_document())}
LAW = LAWS["law"]


def _head(path: Path, lines: int) -> str:
    """The comments, header and first ``lines`` data lines of a bench's file."""
    text = path.read_text(encoding="utf-8").splitlines()
    body = [i for i, line in enumerate(text) if line and not line.startswith("#")]
    return "\n".join(text[:body[0] + 1 + lines]) + "\n"


def _drift(path: Path) -> str:
    """The drift test's first 20 minutes: every quantity, the air and E at its first targets."""
    text = path.read_text(encoding="utf-8").splitlines()
    header = next(i for i, line in enumerate(text) if line.startswith("test,"))
    rows = [line for line in text[header + 1:] if line.startswith("drift,") and float(line.split(",")[1]) <= 1200]
    return "\n".join(text[:header + 1] + rows) + "\n"


FILES = {  # name -> (text, the description it belongs to)
    "series": (_head(bench("ballscrew_example").measurements, 36), "ballscrew_example"),
    "drift": (_drift(bench("ballscrew_example").folder / "drift_tests.csv"), "ballscrew_example"),
    "finals": (_head(bench("paper").measurements, 30), "paper"),
    "log": (LOG, "ballscrew_example"),
}

ODD_CELLS = ["nan", "NaN", "inf", "-inf", "1e400", "-1e400", "1e308", "-1e308", "1e-320", "", " ", "abc", "0x10",
             "1_000", "\u0661\u0662", "\u22125", "1,5", '"', "\x00", "-5", "0", "99999999", "-273.15", "-1e6",
             "degC", "K", "degF", "C", "mm", "um", "m", "s", "delta_degC", "coulomb", "kelvin", "dimensionless",
             "T1", "T9", "D", "D_um", "E", "ambient", "v5", "drift", "I", "ghost", "time [min]", "target [mm]",
             "1e5", "0.0001", "2", "150", "(", "m)", "1/", "**", "degC^", "[", "%", "1e400 m", "K K", "um/s"]
HEADER_CELLS = ["time [s]", "time [h]", "time", "time []", "time [parsec]", "time [1/s]", "time [min", "Time [min]",
                "condition", "test", "quantity", "value", "unit", "uncertainty", "target [mm]", "target [K]",
                "measured", "reference_simulated", "extra", "", "time [(]", "time [1/]", "target [m^]",
                "target [\x00]", "time [min]\x00"]


LINE_EDITS = ["cell", "cell", "cell", "header", "drop", "double", "swap", "blank", "comment", "column", "uncolumn"]
FILE_EDITS = ["cut", "crlf", "encoding", "empty"]


def _edit_lines(draw, lines: list[str], kind: str) -> None:
    """One edit of a line (or the header) of ``lines``, in place."""
    data = [i for i, line in enumerate(lines) if line.strip() and not line.lstrip().startswith("#")]
    if len(data) < 2:
        return
    header, rows = data[0], data[1:]
    row = draw(st.sampled_from(rows))
    cells = lines[row].split(",")
    if kind == "cell":
        cells[draw(st.integers(0, len(cells) - 1))] = draw(st.sampled_from(ODD_CELLS))
        lines[row] = ",".join(cells)
    elif kind == "header":
        head = lines[header].split(",")
        head[draw(st.integers(0, len(head) - 1))] = draw(st.sampled_from(HEADER_CELLS))
        lines[header] = ",".join(head)
    elif kind == "drop":
        del lines[draw(st.sampled_from([header, row]))]
    elif kind == "double":
        lines.insert(row, lines[row])
    elif kind == "swap":
        other = draw(st.sampled_from(rows))
        lines[row], lines[other] = lines[other], lines[row]
    elif kind == "blank":
        lines.insert(row, draw(st.sampled_from(["", " ", ",,,,", "\t"])))
    elif kind == "comment":
        lines.insert(row, draw(st.sampled_from(["# a note", " # indented", "#,1,2,3"])))
    elif kind == "column":
        lines[row] += draw(st.sampled_from([",", ",1", ",x"]))
    else:
        lines[row] = ",".join(cells[:-1])


@st.composite
def mutated(draw):
    """A bench's file with one to three edits of its lines, or one edit of the whole file."""
    return (draw(st.sampled_from(sorted(LAWS))), *draw(_edited()))


@st.composite
def _edited(draw):
    name = draw(st.sampled_from(sorted(FILES)))
    text, system = FILES[name]
    if draw(st.integers(0, 4)):  # mostly lines
        lines = text.splitlines()
        kinds = draw(st.lists(st.sampled_from(LINE_EDITS), min_size=1, max_size=3))
        for kind in kinds:
            _edit_lines(draw, lines, kind)
        return name, system, " + ".join(kinds), ("\n".join(lines) + "\n").encode("utf-8")
    kind = draw(st.sampled_from(FILE_EDITS))
    if kind == "cut":
        return name, system, kind, text[:draw(st.integers(0, len(text)))].encode("utf-8")
    if kind == "empty":
        return name, system, kind, draw(st.sampled_from(["", "\n", "# only a comment\n"])).encode("utf-8")
    if kind == "crlf":
        return name, system, kind, text.replace("\n", "\r\n").encode("utf-8")
    coding = draw(st.sampled_from(["utf-16", "latin-1", "utf-8-sig"]))
    return name, system, f"{kind} {coding}", text.replace("degC", "\u00b0C").encode(coding, "replace")


def _validate_path(path: Path, system: str, what: str) -> None:
    """``validate``'s reader against the description: one line, or finite times and values."""
    loaded = SYSTEMS[system]
    try:
        data = read_description_measurements(loaded.system, str(path), loaded.origin)
    except FeedthermError as exc:
        assert str(exc) and "\n" not in str(exc), (what, str(exc))
        event("validate: refused in one line")
        return
    for row in [*data.rows, *data.positioning]:
        assert np.isfinite(row.measured), what
        if row.series is not None:
            assert np.all(np.isfinite(row.series.times)) and np.all(np.isfinite(row.series.values)), what
            assert np.all(np.diff(row.series.times) > 0), what
            if row.series.uncertainties is not None:
                assert np.all(np.isfinite(row.series.uncertainties)), what
    for series in data.air.values():
        assert np.all(np.isfinite(series.values)), what
    event("validate: read finite")


@pytest.mark.filterwarnings("error::RuntimeWarning")  # numpy's overflow or 0/0 on the way is a defect too
@settings(max_examples=EXAMPLES, derandomize=True, deadline=timedelta(seconds=10), database=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(mutated())
def test_a_mutated_measurement_file_is_refused_in_one_line_or_read_finite(example):
    law, name, system, mutation, content = example
    what = f"{name}: {mutation} ({law})"
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        (folder / "measured.csv").write_bytes(content)
        _validate_path(folder / "measured.csv", system, what)
        (folder / "law.json").write_text(LAWS[law], encoding="utf-8")
        x = ["--x", "100 mm,217 mm,300 mm"] if law == "law_stroke" else []
        code, out, err = run_correct(["correct", str(folder / "law.json"), str(folder / "measured.csv"),
                                      "--out", str(folder / "out"), *x])
        check_outcome(code, out, err, folder / "out", what)


@pytest.mark.parametrize("name", sorted(FILES))
def test_the_unmutated_files_are_read(name):
    """The fuzzer's starting points pass the contract's healthy branch."""
    text, system = FILES[name]
    loaded = SYSTEMS[system]
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "measured.csv"
        path.write_text(text, encoding="utf-8")
        if name != "log":  # the log's run1 is no run of the bench
            assert read_description_measurements(loaded.system, str(path), loaded.origin).rows
        (Path(tmp) / "law.json").write_text(LAW, encoding="utf-8")
        code, out, err = run_correct(["correct", str(Path(tmp) / "law.json"), str(path), "--out", str(Path(tmp) / "out")])
        assert code == 0, err


SERIES_HEAD = "condition,time [min],quantity,value,unit\n"
FINALS_HEAD = "condition,quantity,unit,measured\n"


@pytest.mark.parametrize("text, says", [
    # pint's parser ended these in an AssertionError or tokenize's TokenError, a traceback
    (SERIES_HEAD + "run1,0,T1,20,\x00\n", "log.csv: line 2: unknown unit '\\x00'"),
    (SERIES_HEAD + "run1,0,T1,20,(\n", "log.csv: line 2: unknown unit '('"),
    (SERIES_HEAD + "run1,0,T1,20,degC^\n", "log.csv: line 2: unknown unit 'degC^'"),
    ("condition,time [1/],quantity,value,unit\nrun1,0,T1,20,degC\n", "log.csv: line 1: unknown time unit '1/'"),
    # finite, but no reading: correction.csv held inf where a law multiplied them, correction.json an RMS of inf
    (FINALS_HEAD + "I,T1,C,1e308\nI,T2,C,20\nI,D_um,um,30\n",
     "log.csv: line 2: 1e308 C lies outside the accepted range, -150 to 1000 degC"),
    (FINALS_HEAD + "I,T1,C,20\nI,T2,C,20\nI,D_um,um,1e308\n",
     "log.csv: line 4: 1e308 um lies outside the accepted range, |value| <= 100 m (larger than any machine tool)"),
    (SERIES_HEAD + "run1,0,T1,20,degC\nrun1,0,T2,20,degC\nrun1,0,D,-1e300,um\n",
     "log.csv: line 4: -1e300 um lies outside the accepted range, |value| <= 100 m"),
])
def test_what_the_fuzzing_found_is_refused_in_one_line(tmp_path, text, says):
    (tmp_path / "log.csv").write_text(text, encoding="utf-8")
    (tmp_path / "law.json").write_text(LAW, encoding="utf-8")
    code, out, err = run_correct(["correct", str(tmp_path / "law.json"), str(tmp_path / "log.csv"),
                                  "--out", str(tmp_path / "out")])
    assert code == 2 and err.count("\n") == 1 and says in err, err
    assert not (tmp_path / "out").exists()
