"""`feedtherm uncertainty`'s files from a synthetic study: written as a set, their exact contents,
the JSON read back, the console summary and the report section."""

from __future__ import annotations

import csv
import dataclasses
import io
import json

import numpy as np
import pytest
from rich.console import Console

from feedtherm.errors import FeedthermError
from feedtherm.outputs import uncertainty_files
from feedtherm.outputs.files import json_text
from feedtherm.outputs.report.html import PNG_MAGIC
from feedtherm.outputs.report.uncertainty import uncertainty_section
from feedtherm.outputs.uncertainty_files import (
    UNCERTAINTY_FILES,
    compact_json,
    print_uncertainty,
    read_uncertainty_summary,
    summary,
    write_uncertainty,
)

# The synthetic study lives in tests/ (pytest puts the directory of tests/conftest.py on sys.path).
from uncertainty_study import (
    CONDITIONS,
    HALF_WIDTH,
    HALF_WIDTH_RATIO,
    MEASURED,
    PARAMETER_NAMES,
    QUANTITIES,
    TIMES,
    expected_inside,
    make_study,
    measured,
    nominal,
)

ALL_FILES = sorted(["uncertainty.json", "bands.csv", "finals.csv", "sobol.csv", "bands_over_time.png", "finals.png",
                    "sobol.png", "uncertainty.html"])


@pytest.fixture(scope="module")
def study():
    return make_study()


@pytest.fixture(scope="module")
def written(study, tmp_path_factory):
    out = tmp_path_factory.mktemp("unc") / "study"
    return out, write_uncertainty(study, out)


def rows(path):
    with open(path, newline="", encoding="utf-8") as handle:
        return list(csv.DictReader(handle))


# --------------------------------------------------------------------------- the set


def test_the_set_is_every_file_and_nothing_else(written):
    out, paths = written
    assert sorted(p.name for p in paths) == ALL_FILES
    assert sorted(p.name for p in out.parent.iterdir()) == ["study"]  # no staging folder left beside it
    for name in ("bands_over_time.png", "finals.png", "sobol.png"):
        assert (out / name).read_bytes().startswith(PNG_MAGIC), name


def test_a_failure_midway_leaves_the_old_set_untouched(study, tmp_path, monkeypatch):
    out = tmp_path / "study"
    write_uncertainty(make_study(calibrated=False), out)
    (out / "notes.txt").write_text("mine")
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    original = uncertainty_files._write_csv

    def failing(path, header, rows):
        if path.name == "sobol.csv":
            raise OSError(28, "No space left on device")
        original(path, header, rows)

    monkeypatch.setattr(uncertainty_files, "_write_csv", failing)
    with pytest.raises(FeedthermError, match="cannot write the outputs .No space left on device"):
        write_uncertainty(study, out)
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["study"]


def test_a_new_set_drops_the_old_sets_files_and_keeps_a_users(study, tmp_path):
    out = tmp_path / "study"
    write_uncertainty(study, out)
    (out / "notes.txt").write_text("mine")
    paths = write_uncertainty(make_study(calibrated=False, sobol=False), out)
    names = sorted(p.name for p in out.iterdir())
    assert "sobol.png" not in names and sorted(p.name for p in paths) == [n for n in ALL_FILES if n != "sobol.png"]
    assert (out / "notes.txt").read_text() == "mine"
    assert rows(out / "sobol.csv") == []  # the header only
    assert {r["set"] for r in rows(out / "finals.csv")} == {"prior"}


# --------------------------------------------------------------------------- the CSVs


def test_bands_csv_holds_every_time_of_every_quantity_with_the_bands_values(written):
    out, _ = written
    table = rows(out / "bands.csv")
    assert list(table[0]) == ["set", "condition", "quantity", "unit", "time_s", "p05", "p50", "p95", "nominal"]
    assert len(table) == 2 * len(CONDITIONS) * len(QUANTITIES) * TIMES.size == 2 * 5 * 7 * 181
    row = next(r for r in table if (r["set"], r["condition"], r["quantity"], r["time_s"]) == ("calibrated", "III", "D_um", "3600"))
    k = 60  # 3600 s
    middle = nominal("III", "D_um")[k]
    half = HALF_WIDTH_RATIO * HALF_WIDTH["um"] * (1 - np.exp(-3600 / 2400))
    assert row["unit"] == "um"
    assert row["p05"] == f"{middle - half:.4f}" and row["p95"] == f"{middle + half:.4f}"
    assert row["p50"] == f"{middle + 0.1 * half:.4f}" and row["nominal"] == f"{middle:.4f}"
    assert [r["time_s"] for r in table[:3]] == ["0", "60", "120"]
    assert [r["quantity"] for r in table[::TIMES.size][:7]] == list(QUANTITIES)


def test_finals_csv_puts_each_band_beside_its_measurement(written):
    out, _ = written
    table = rows(out / "finals.csv")
    assert list(table[0]) == ["set", "condition", "quantity", "unit", "p05", "p50", "p95", "nominal", "measured",
                              "inside", "flag"]
    assert len(table) == 2 * 5 * 7
    prior = [r for r in table if r["set"] == "prior"]
    assert sum(r["inside"] == "true" for r in prior) == expected_inside(1.0) == 15
    assert sum(r["inside"] == "true" for r in table if r["set"] == "calibrated") == expected_inside(HALF_WIDTH_RATIO) == 5
    t6 = [r for r in prior if r["quantity"] == "T6"]
    assert all(r["measured"] == "" and r["inside"] == "" for r in t6)
    row = next(r for r in prior if (r["condition"], r["quantity"]) == ("I", "T1"))
    final = nominal("I", "T1")[-1]
    half = HALF_WIDTH["C"] * (1 - np.exp(-10800 / 2400))
    assert row["measured"] == f"{measured('I', 'T1'):g}" == "21"  # 1.5 half-widths below: outside
    assert row["inside"] == "false" and row["p05"] == f"{final - half:.4f}" and row["nominal"] == f"{final:.4f}"
    flagged = [r for r in table if r["flag"]]
    assert {(r["condition"], r["quantity"]) for r in flagged} == {("V", "D_um")}


def test_sobol_csv_lists_the_priors_indices_at_condition_I(written, study):
    out, _ = written
    table = rows(out / "sobol.csv")
    assert list(table[0]) == ["set", "condition", "quantity", "parameter", "S1", "S1_conf", "ST", "ST_conf"]
    assert len(table) == len(QUANTITIES) * len(PARAMETER_NAMES)
    assert {(r["set"], r["condition"]) for r in table} == {("prior", "I")}
    row = next(r for r in table if (r["quantity"], r["parameter"]) == ("T4", "tcr_scale"))
    # (p_index + q_index) % 8 == (5 + 3) % 8 == 0: S1 = 0.5
    assert (row["S1"], row["S1_conf"], row["ST"], row["ST_conf"]) == ("0.5000", "0.0100", "0.5500", "0.0200")


# --------------------------------------------------------------------------- the JSON


def test_the_summary_counts_and_widths(study):
    document = summary(study)
    prior, calibrated = document["sets"]
    assert prior["coverage"] == {"inside": 15, "total": 30} and calibrated["coverage"] == {"inside": 5, "total": 30}
    shape_end = 1 - np.exp(-10800 / 2400)
    assert prior["mean_width"]["C"] == pytest.approx(2 * HALF_WIDTH["C"] * shape_end, abs=1e-4)
    assert calibrated["mean_width"]["um"] == pytest.approx(2 * HALF_WIDTH_RATIO * HALF_WIDTH["um"] * shape_end, abs=1e-4)
    assert [p["name"] for p in document["parameters"]] == list(PARAMETER_NAMES)
    assert document["parameters"][0]["reason"] == "recalled <screw_nut_preload> from a catalogue"
    assert calibrated["parameters"][0]["distribution"] == "normal" and calibrated["parameters"][0]["sigma"] == 35.0
    assert calibrated["calibration"]["fit_conditions"] == ["I", "III"] and prior["calibration"] is None
    assert prior["sobol_condition"] == "I" and len(prior["sobol"]) == 56 and calibrated["sobol"] == []
    bands = prior["bands"]["II"]
    assert bands["time_s"][:2] == [0.0, 60.0] and len(bands["time_s"]) == 181
    assert list(bands["quantities"]) == list(QUANTITIES)
    assert bands["quantities"]["T2"]["nominal"][-1] == round(float(nominal("II", "T2")[-1]), 4)
    assert {f["inside"] for f in prior["finals"] if f["quantity"] == "T6"} == {None}


def test_the_json_is_compact_and_reads_back_as_written(written, study):
    out, _ = written
    text = (out / "uncertainty.json").read_text(encoding="utf-8")
    assert text.count("\n") < 5000  # one number per line would be over 50,000 lines (the bands alone)
    assert json.loads(text) == json.loads(json_text(summary(study)))
    read = read_uncertainty_summary(out)
    assert read["summary"] == json.loads(text)
    assert sorted(read["figures"]) == ["bands_over_time.png", "finals.png", "sobol.png"]
    assert read["figures"]["finals.png"] == (out / "finals.png").read_bytes()


def test_compact_json_keeps_strings_that_look_like_lists():
    document = {"a": [1, -2.5, None, 3e-07], "b": ["[1,", "2]"], "c": [[1, 2], [3]], "d": []}
    text = compact_json(document)
    assert json.loads(text) == document
    assert '"a": [1, -2.5, null, 3e-07]' in text and '"c": [\n    [1, 2],\n    [3]\n  ]' in text


@pytest.mark.parametrize("content, fragment", [
    (None, "uncertainty.json not found (give the output folder of `feedtherm uncertainty`)"),
    ("{not json", "is not readable JSON"),
    ('{"settings": {}}', "lacks parameters, sets; is it a uncertainty.json?"),
    ('{"settings": {}, "parameters": [], "sets": 3}', "sets is not a list of sets"),
    ('{"settings": {}, "parameters": [], "sets": [{"label": "prior", "parameters": [], "finals": [{"condition": "I"}]}]}',
     "sets[0].finals[0] lacks quantity, unit, p05, p95, measured, inside"),
    ('{"settings": {}, "parameters": [], "sets": [{"label": "prior", "parameters": [], "finals": []}]}',
     "sets[0] lacks runs, coverage, mean_width"),
])
def test_a_bad_folder_is_one_line_naming_the_option(tmp_path, content, fragment):
    if content is not None:
        (tmp_path / "uncertainty.json").write_text(content)
    with pytest.raises(FeedthermError) as error:
        read_uncertainty_summary(tmp_path)
    message = str(error.value)
    assert message.startswith("--uncertainty: ") and fragment in message and "\n" not in message


# --------------------------------------------------------------------------- console and report


def test_the_console_gives_coverage_widths_sobol_and_where(study, tmp_path):
    console = Console(file=io.StringIO(), width=140)
    print_uncertainty(study, tmp_path / "out", console=console)
    text = console.file.getvalue()
    assert "prior: 15 of 30 measured values inside the 5–95 % band" in text
    assert "calibrated: 5 of 30 measured values inside the 5–95 % band" in text
    assert "3.96" in text and "1.58" in text  # mean widths of the temperatures [K]
    # ST on T4 = S1 + 0.05, S1 = 0.5 / (1 + (p + 3) % 8): tcr_scale (p 5), motor_loss_scale (p 6), ambient_drift (p 7)
    assert "Sobol ST at I, T4: tcr_scale 0.55, motor_loss_scale 0.30, ambient_drift 0.22" in text
    assert "T6:" not in text
    assert f"wrote {tmp_path / 'out'}/uncertainty.json" in text


def test_the_section_gives_the_counts_the_reasons_escaped_and_the_figures(written):
    out, _ = written
    read = read_uncertainty_summary(out)
    html = uncertainty_section(read["summary"], read["figures"])
    assert html.startswith('<section id="uncertainty">')
    assert "15 of 30 measured values lie inside the prior 5–95 % band" in html
    assert "5 of 30 measured values lie inside the calibrated 5–95 % band" in html
    assert "temperatures 40 %, elongation 40 %" in html  # the calibrated bands' mean width against the prior's
    assert "recalled &lt;screw_nut_preload&gt; from a catalogue" in html and "<screw_nut_preload>" not in html
    assert "triangular 200 … 400 N (declared 300 N)" in html and "uniform 0.8 … 1.25 × declared" in html
    assert "normal σ 35 within 200 … 800 N (declared 410 N)" in html  # the calibrated posterior's table
    assert html.count("data:image/png;base64") == 3
    assert "fitted on conditions I, III" in html
    assert "How to read the indices" in html and "0.55 (0.50)" in html
    finals = html[html.index("<caption>the measured final values"):]
    finals = finals[:finals.index("</table>")]
    assert finals.count("<tr>") == 1 + len(CONDITIONS) * len(MEASURED)  # the header and the 30 measured values
    assert finals.count('<td class="dev-0">yes</td>') == 15 + 5
    assert "<td>D (flagged)</td><td>65.3 µm</td>" in finals


def test_the_section_without_a_calibration_or_figures(study):
    prior_only = make_study(calibrated=False)
    html = uncertainty_section(summary(prior_only), {})
    assert "15 of 30 measured values lie inside the prior 5–95 % band" in html
    assert "calibrated" not in html and "<img" not in html


def test_a_study_without_measurements_writes_and_says_so(tmp_path):
    study = make_study()
    for uset in study.sets:
        uset.finals = [dataclasses.replace(f, measured=None, flag="") for f in uset.finals]
    paths = write_uncertainty(study, tmp_path / "out")
    assert len(paths) == len(ALL_FILES)
    assert {r["measured"] for r in rows(tmp_path / "out" / "finals.csv")} == {""}
    html = (tmp_path / "out" / "uncertainty.html").read_text(encoding="utf-8")
    assert "No measured values to set against the bands." in html
    assert summary(study)["sets"][0]["coverage"] == {"inside": 0, "total": 0}


def test_mean_widths_count_only_the_measured_values():
    from dataclasses import replace

    from feedtherm.analysis.uncertainty.types import FinalBand
    from feedtherm.outputs.uncertainty_files import mean_widths

    uset = make_study(calibrated=False).sets[0]
    # The ambient's band is zero wide and has no measurement: 2 K and 4 K measured -> 3 K, not 2 K.
    uset.finals = [FinalBand("I", "T1", "C", 20.0, 21.0, 22.0, 21.0, measured=21.5),
                   FinalBand("I", "T2", "C", 20.0, 22.0, 24.0, 22.0, measured=25.0),
                   FinalBand("I", "T6", "C", 20.0, 20.0, 20.0, 20.0)]
    assert mean_widths(uset) == {"C": 3.0}
    # Without any measurement every final value counts.
    uset.finals = [replace(f, measured=None) for f in uset.finals]
    assert mean_widths(uset) == {"C": 2.0}


def test_a_predictive_set_without_bands_over_time_is_written_beside_the_others(tmp_path):
    """The set a Bayesian update adds: finals only, no runs of its own; every file still written."""
    from feedtherm.analysis.uncertainty.types import UncertaintySet

    study = make_study()
    calibrated = study.sets[1]
    wider = [dataclasses.replace(f, p05=f.p05 - 1.0, p95=f.p95 + 1.0) for f in calibrated.finals]
    study.sets.append(UncertaintySet("predictive", calibrated.parameters, {}, wider, 0,
                                     model_error={"noise_scale_s2": 4.0, "sd": {"T1": 1.0}}))
    out = tmp_path / "out"
    assert sorted(p.name for p in write_uncertainty(study, out)) == ALL_FILES
    assert "predictive" not in {r["set"] for r in rows(out / "bands.csv")}
    finals = [r for r in rows(out / "finals.csv") if r["set"] == "predictive"]
    assert len(finals) == 5 * 7 and float(finals[0]["p95"]) - float(finals[0]["p05"]) == pytest.approx(
        calibrated.finals[0].p95 - calibrated.finals[0].p05 + 2.0, abs=1e-3)
    document = read_uncertainty_summary(out)
    assert document["summary"]["sets"][2]["model_error"] == {"noise_scale_s2": 4.0, "sd": {"T1": 1.0}}
    html = (out / "uncertainty.html").read_text(encoding="utf-8")
    assert "Mean width of the predictive bands against the prior ones" in html
    assert html.count("sampled in the") == 1  # the predictive set's parameters are the calibrated set's
    console = io.StringIO()
    print_uncertainty(study, out, Console(file=console, width=160))
    line = next(l for l in console.getvalue().splitlines() if l.lstrip("│ ").startswith("predictive"))
    assert line.split("│")[2].strip() == "—"  # no runs of its own
