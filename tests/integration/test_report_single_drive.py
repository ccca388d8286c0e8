"""The validation report of a single-drive axis (ballscrew_example) shows what applies to it.

The Validation is assembled as `feedtherm validate` assembles it (the bench's own operating
points, sensor places and report notes; no single-drive runs on a single drive; the
measurements' finals, which carry no reference model's values), from 30-minute cycle-averaged
runs of the bench's four conditions, so that the report's content is tested without the
8-hour runs.  A calibration summary in calibration.json's form makes the calibrated model's rows.
"""

from __future__ import annotations

import re
from dataclasses import replace

import pytest

from feedtherm.analysis.validation import measurements_of, operating_points, report_notes, sensor_locations
from feedtherm.analysis.validation_types import Comparison, Validation
from feedtherm.outputs.report import render_report
from feedtherm.simulate import simulate
from feedtherm.system.load import load_system

from test_report_renders import unlabelled_tables

NAME = "ballscrew_example"
CONDITIONS = ("v5", "v10", "v20", "v10_warm")
FIT = ["v5", "v10", "v20"]


@pytest.fixture(scope="module")
def validation() -> Validation:
    loaded = load_system(NAME)
    assert loaded.system.kinematics.drive == "single"
    data = measurements_of(loaded, None)
    runs = {c: simulate(loaded, condition=c, duration=1800.0, motion="averaged") for c in CONDITIONS}
    comparisons = [Comparison(c, row.quantity, row.unit, runs[c].summary_values("final")[row.quantity], row.measured,
                              row.reference_simulated) for c in CONDITIONS for row in data.for_condition(c)]
    assert comparisons and all(c.paper_simulated is None for c in comparisons)  # no reference model
    provenance = dict(runs["v10"].info["provenance"])
    assumptions = provenance.pop("assumptions")
    return Validation(
        system_name=loaded.system.meta.name, model="fast", comparisons=comparisons, solutions=runs,
        single_drive={}, heat_budget={}, measured_equilibrium_min=data.equilibrium_min, sensitivities=[],
        sensitivity_condition="v10", inconsistencies=[], assumptions=assumptions, provenance=provenance,
        measurement_source=data.source, operating_points=operating_points(loaded),
        sensor_locations=sensor_locations(loaded), notes=report_notes(loaded))


def calibration_summary(validation: Validation) -> dict:
    """calibration.json's keys: the fit conditions' values (residuals) and the held-out predictions,
    each 0.3 K / 1 µm off the runs here."""
    def entry(c: Comparison, key: str) -> dict:
        value = c.simulated + (0.3 if c.unit == "C" else 1.0)
        return {"condition": c.condition, "quantity": c.quantity, "unit": c.unit, key: value, "measured": c.measured,
                "residual" if key == "simulated" else "deviation": value - c.measured}

    return {"fit_conditions": FIT,
            "parameters": {"ball_nut_torque": {"fitted": 0.34, "standard_error": 0.01, "at_bound": None}},
            "residuals": [entry(c, "simulated") for c in validation.comparisons if c.condition in FIT],
            "excluded": [],
            "held_out": [dict(entry(c, "predicted"), flag=None) for c in validation.comparisons
                         if c.condition not in FIT],
            "model": "fast, cycle-averaged motion"}


@pytest.fixture(scope="module")
def html(validation) -> str:
    return render_report(validation)


@pytest.fixture(scope="module")
def calibrated_html(validation) -> str:
    return render_report(replace(validation, calibration=calibration_summary(validation)))


def sections(html: str) -> list[str]:
    return re.findall(r'<section id="([^"]+)"', html)


def test_no_dual_drive_section_on_a_single_drive(html):
    assert "dual-single" not in sections(html) and 'href="#dual-single"' not in html
    assert "Dual drive against single drive" not in html and "single-drive runs" not in html


def test_no_reference_model_where_the_measurements_carry_none(html, calibrated_html):
    for page in (html, calibrated_html):
        assert "reference model" not in page and "reference values" not in page
        # no row of dashes: every row of every table of model values holds at least one value
        for table in re.findall(r"<table[^>]*data-model=.*?</table>", page, re.S):
            for row in re.findall(r"<tr>(.*?)</tr>", table):
                cells = re.findall(r"<td[^>]*>(.*?)</td>", row)
                assert not cells or any(cell != "—" for cell in cells), row


def test_no_missing_description_and_no_empty_section(html):
    assert "no description" not in html
    for anchor, body in re.findall(r'<section id="([^"]+)"><h2>[^<]*</h2>(.*?)</section>', html, re.S):
        assert re.search(r"<(p|table|figure)\b", body), anchor
    for gone in ("No heat budget was computed", "No sensitivities were computed", "No heats were inferred",
                 "were not checked", "No runs to show"):
        assert gone not in html


def test_the_trends_are_drawn_only_for_the_series_the_conditions_form(validation, monkeypatch):
    """v5, v10, v20 differ in speed and v10, v10_warm in ambient: two columns, each titled by what its
    series holds fixed (no "()"), and the prose names the ambient series' own slopes."""
    from feedtherm.outputs.report import figures, operating

    drawn = []
    monkeypatch.setattr(figures, "_png", lambda figure: drawn.append(figure) or _blank_png())
    section = operating.trends_section(validation)
    [figure] = drawn
    titles = [ax.get_title() for ax in figure.axes]
    assert len(titles) == 4 and all("()" not in t and t for t in titles), titles
    assert "Over the ambient series (v10, v10_warm)" in section
    speed_only = replace(validation, solutions={c: validation.solutions[c] for c in ("v5", "v10", "v20")})
    drawn.clear()
    section = operating.trends_section(speed_only)
    [figure] = drawn
    titles = [ax.get_title() for ax in figure.axes]
    assert len(titles) == 2 and all("against speed" in t for t in titles), titles  # no empty ambient column
    assert "ambient series" not in section


def test_every_table_says_which_model_it_shows(html, calibrated_html):
    assert unlabelled_tables(html) == [] and unlabelled_tables(calibrated_html) == []
    assert 'data-model="calibrated model"' not in html and 'data-model="uncalibrated and calibrated' not in html


def test_with_a_calibration_the_deviation_tables_show_both_models_by_name(validation, calibrated_html):
    deviations = calibrated_html[calibrated_html.index('<section id="deviations">'):]
    deviations = deviations[:deviations.index("</section>")]
    for condition in CONDITIONS:
        caption = f'<caption>Condition {condition} <span class="model">uncalibrated and calibrated model</span>'
        assert caption in deviations
    assert deviations.count('<th scope="row">calibrated model (fitted to it)</th>') == len(FIT)
    assert deviations.count('<th scope="row">calibrated model (held out)</th>') == 1  # v10_warm
    assert deviations.count('<th scope="row">uncalibrated model</th>') == len(CONDITIONS)
    headline = calibrated_html[calibrated_html.index('<section id="headline">'):]
    assert "calibrated model, fitted to v5, v10, v20, predicting v10_warm (held out)" in headline
    held = calibration_summary(validation)["held_out"]
    worst = {unit: max(abs(r["deviation"]) for r in held if r["unit"] == unit) for unit in ("C", "um")}
    assert (f"The calibrated model (fitted to v5, v10, v20) predicts the held-out v10_warm within "
            f"{worst['C']:.1f} K and {worst['um']:.1f} µm.") in calibrated_html


def _blank_png() -> bytes:
    import io

    from PIL import Image

    buffer = io.BytesIO()
    Image.new("RGB", (4, 4), "white").save(buffer, format="PNG")
    return buffer.getvalue()
