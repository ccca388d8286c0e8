"""The report's HTML builders and a whole report from synthetic Solutions (no model, no browser)."""

from __future__ import annotations

import base64
import io
import re
from dataclasses import replace
from datetime import datetime, timezone

import pytest

from feedtherm.analysis.validation_types import Comparison, OperatingPointRow, Sensitivity, Validation
from feedtherm.errors import FeedthermError
from feedtherm.outputs import report as report_module
from feedtherm.outputs.report import REPORT_HTML, render_report, write_report
from feedtherm.outputs.report.comparison import condition_table, deviation_cell, summary_text
from feedtherm.outputs.report.data import deviation_band, deviation_bands
from feedtherm.outputs.report.figures import profile_rows
from feedtherm.outputs.report.html import Cell, Raw, bullets, esc, number, page, png_image, section, table

# The synthetic warm-up lives beside this file (pytest puts the directory on sys.path).
from test_run_files import make_solution

PNG_1PX = base64.b64decode(
    "iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mP8z8BQDwAEhQGAhKmMIQAAAABJRU5ErkJggg==")
HOSTILE = '<script>alert("x")</script> & \'quoted\''
DATA_URI = re.compile(r'<img src="data:image/png;base64,([A-Za-z0-9+/=]+)"')


# --------------------------------------------------------------------------- builders


def test_esc_escapes_markup_and_quotes():
    assert esc(HOSTILE) == "&lt;script&gt;alert(&quot;x&quot;)&lt;/script&gt; &amp; &#x27;quoted&#x27;"
    assert esc(3.5) == "3.5"


@pytest.mark.parametrize("value, kwargs, text", [
    (12.345, {}, "12.3"),
    (-1.25, {"decimals": 2}, "\u22121.25"),
    (1.2, {"signed": True}, "+1.2"),
    (-0.04, {"signed": True}, "+0.0"),  # rounds to zero: no "−0.0"
    (None, {}, "—"),
    (float("nan"), {"missing": "n/a"}, "n/a"),
    (2214.0, {"decimals": 0}, "2214"),
])
def test_number_formatting(value, kwargs, text):
    assert number(value, **kwargs) == text


def test_table_escapes_text_keeps_raw_and_classes_cells():
    html = table(["point", "value [°C]"], [[HOSTILE, Cell("+1.0", "dev-1")], ["T2", Raw("<code>x</code>")]],
                 caption="a < b")
    assert "<script>" not in html and "&lt;script&gt;" in html
    assert '<td class="dev-1">+1.0</td>' in html
    assert "<td><code>x</code></td>" in html
    assert '<th scope="col">value [°C]</th>' in html
    assert html.count('<th scope="row">') == 2
    assert "<caption>a &lt; b</caption>" in html


def test_png_image_embeds_the_bytes_as_base64_and_escapes_alt():
    html = png_image(PNG_1PX, 'a "quoted" <alt>', caption="x & y")
    encoded = DATA_URI.search(html).group(1)
    assert base64.b64decode(encoded) == PNG_1PX
    assert 'alt="a &quot;quoted&quot; &lt;alt&gt;"' in html
    assert "<figcaption>x &amp; y</figcaption>" in html
    with pytest.raises(ValueError):
        png_image(b"GIF89a", "not a png")


def test_page_section_and_bullets():
    html = page("T <1>", section("a-b", "Title & more", bullets(["<i>", Raw("<b>ok</b>")])))
    assert html.startswith("<!DOCTYPE html>")
    assert "<title>T &lt;1&gt;</title>" in html and '<meta charset="utf-8">' in html
    assert '<section id="a-b"><h2>Title &amp; more</h2>' in html
    assert "<li>&lt;i&gt;</li><li><b>ok</b></li>" in html
    assert "<script" not in html and "http" not in html


@pytest.mark.parametrize("deviation, unit, band", [
    (0.5, "C", 0), (-1.0, "C", 0), (2.0, "C", 1), (-3.0, "C", 2), (5.1, "C", 3),
    (2.9, "um", 0), (-6.2, "um", 1), (10.0, "um", 2), (45.0, "um", 3),
])
def test_deviation_bands(deviation, unit, band):
    # the middle band is the reference model's own worst: 2.1 K and 6.2 µm on the paper's bench
    limits = {"C": (1.0, 2.1, 5.0), "um": (3.0, 6.2, 15.0)}[unit]
    assert deviation_band(deviation, limits) == band
    assert deviation_cell(deviation, limits).css_class == f"dev-{band}"


def test_the_middle_band_is_the_reference_models_worst_in_sample():
    v = synthetic_validation()
    worst = max(abs(c.paper_simulated - c.measured) for c in v.comparisons if c.unit == "C" and c.paper_simulated)
    assert deviation_bands(v, "C") == (1.0, pytest.approx(worst), 5.0)
    assert deviation_bands(replace(v, comparisons=[replace(c, paper_simulated=None) for c in v.comparisons]),
                           "C") == (1.0, 2.0, 5.0)  # none given: 2 K


def test_condition_table_has_quantities_as_columns_with_units():
    rows = [Comparison("I", "T1", "C", 22.61, 27.1, 28.1), Comparison("I", "D_um", "um", 23.5, 29.9, None)]
    html = condition_table("I", rows, {"C": (1.0, 2.1, 5.0), "um": (3.0, 6.2, 15.0)})
    assert "T1 [°C]" in html and "D [µm]" in html
    assert "22.6" in html and "\u22124.5" in html  # 22.61 − 27.1
    assert '<td class="dev-2">\u22124.5</td>' in html
    assert "<td>—</td>" in html  # no paper value for D


def test_profile_rows_are_distinct_and_end_at_the_last_sample():
    import numpy as np

    times = np.arange(0.0, 1801.0, 10.0)
    rows = profile_rows(times, 5)
    assert rows == sorted(set(rows)) and rows[-1] == times.size - 1 and times[rows[0]] > 0


# --------------------------------------------------------------------------- whole report


def synthetic_validation(**changes) -> Validation:
    runs = {"I": make_solution(), "II": make_solution(equilibrium_time=None)}
    speeds = {"I": OperatingPointRow(396.0, 360.0, 20.0), "II": OperatingPointRow(1116.0, 1080.0, 20.0)}
    comparisons = []
    for condition, solution in runs.items():
        final = solution.summary_values()
        comparisons += [Comparison(condition, q, "C", final[q], final[q] + 1.5, final[q] + 2.5)
                        for q in ("T1", "T2", "T3", "T4", "T5")]
        comparisons.append(Comparison(condition, "D_um", "um", final["D_um"], final["D_um"] - 4.0, None))
    values = dict(
        system_name=HOSTILE, model="fast", comparisons=comparisons, solutions=runs, operating_points=speeds,
        single_drive={"I": make_solution()}, heat_budget={"I": {"front_bearing": 5.0, "screw_nut": 6.0},
                                                          "II": {"front_bearing": 18.6, "screw_nut": 6.0}},
        measured_equilibrium_min={"I": 120.0, "II": 100.0},
        sensitivities=[Sensitivity("sources.screw_nut.mu", "docs/paper-audit.md <§5>", 1.5,
                                   {"T1": 0.1, "T2": 0.2, "T3": -2.0, "T4": 1.0, "T5": 0.3, "D_um": 4.0}),
                       Sensitivity("sources.front_bearing.preload", "catalogue", 0.8,
                                   {"T1": 3.0, "T2": 0.2, "T3": 0.1, "T4": 0.1, "T5": 0.1, "D_um": 1.0}),
                       Sensitivity("joints[6].tcr", "assumed", 1.1,
                                   {"T1": 0.0, "T2": 0.0, "T3": 0.5, "T4": 0.1, "T5": 0.0, "D_um": 0.5},
                                   name="joint <nut>–screw: tcr")],
        sensitivity_condition="I", inconsistencies=["Table 1 < needed & <b>not bold</b>"],
        assumptions=[{"paths": ["parts.screw", "sources.x"], "source": "a <source>", "reason": "because"}],
        provenance={"feedtherm_version": "0.1.0", "description_sha256": "ab" * 32, "mode": "physics"},
        measurement_source="paper Tables 6–7",
    )
    values.update(changes)
    return Validation(**values)


@pytest.fixture(scope="module")
def rendered() -> str:
    return render_report(synthetic_validation(), generated=datetime(2024, 5, 1, tzinfo=timezone.utc))


def test_every_text_from_the_validation_is_escaped(rendered):
    assert "<script" not in rendered and "<b>not bold</b>" not in rendered
    assert "&lt;script&gt;alert(&quot;x&quot;)&lt;/script&gt;" in rendered
    assert "&lt;b&gt;not bold&lt;/b&gt;" in rendered and "a &lt;source&gt;" in rendered


def test_sections_in_order_and_no_external_resources(rendered):
    ids = re.findall(r'<section id="([^"]+)"', rendered)
    # no heats inferred and no consistency check in this Validation: neither section
    assert ids == ["headline", "deviations", "displacement", "sensor-curves", "screw-field", "equilibrium", "trends",
                   "dual-single", "heat-budget", "sensitivity", "inconsistencies", "calibrated", "assumptions"]
    assert "generated 2024-05-01 00:00 UTC" in rendered
    assert not re.search(r"(src|href)\s*=\s*[\"']?(https?:|//)", rendered)


def test_the_contents_list_the_sections_present_and_stay_in_view(rendered):
    nav = re.search(r'<nav class="contents"[^>]*>(.*?)</nav>', rendered, re.S).group(1)
    linked = re.findall(r'<a href="#([^"]+)">([^<]+)</a>', nav)
    sections = re.findall(r'<section id="([^"]+)"><h2>([^<]+)</h2>', rendered)
    assert linked == sections
    css = rendered[rendered.index("<style>"):rendered.index("</style>")]
    assert re.search(r"nav\.contents \{[^}]*position: sticky; top: 0;", css)
    assert rendered.index('<nav class="contents"') < rendered.index("<main>")  # beside the page, not in it


def test_images_are_valid_pngs(rendered):
    from PIL import Image

    encoded = DATA_URI.findall(rendered)
    # the positioning error, 2 sensor-curve figures, the screw field, trends, dual/single, heat budget,
    # sensitivity
    assert len(encoded) == 8
    for data in encoded:
        with Image.open(io.BytesIO(base64.b64decode(data))) as image:
            assert image.format == "PNG" and image.size[0] >= 1000


def test_summary_names_the_largest_deviations(rendered):
    text = summary_text(synthetic_validation())
    assert "largest temperature deviation is \u22121.5 K" in text
    assert "largest elongation deviation is +4.0 µm" in text
    assert "below the measured temperatures (10 of 10 points are below)" in text


def test_equilibrium_not_reached_and_the_stated_times(rendered):
    assert "not reached in the run" in rendered
    assert "<td>120</td>" in rendered and "<td>100</td>" in rendered
    # I and II differ in speed only: the speed paragraph, not the ambient one
    assert "a faster condition need not reach equilibrium sooner" in rendered
    assert "cannot change the equilibrium time" not in rendered


def ambient_validation() -> Validation:
    """I and II as above, and III: I's speeds in a room 10 K warmer, every simulated final 1 K warmer per
    kelvin except D, which falls by 0.4 µm/K; measured D rises by 3 µm/K."""
    base = synthetic_validation()
    runs = dict(base.solutions, III=make_solution(equilibrium_time=5100.0))
    points = dict(base.operating_points, III=OperatingPointRow(396.0, 360.0, 30.0))
    extra = [replace(c, condition="III", simulated=c.simulated + (-4.0 if c.unit == "um" else 10.0),
                     measured=c.measured + (30.0 if c.unit == "um" else 9.0))
             for c in base.comparisons if c.condition == "I"]
    return replace(base, solutions=runs, operating_points=points, comparisons=base.comparisons + extra,
                   measured_equilibrium_min={"I": 120.0, "II": 100.0, "III": 70.0})


def test_an_ambient_series_states_its_own_figures():
    from feedtherm.outputs.report.transients import equilibrium_section

    html = equilibrium_section(ambient_validation())
    assert "cannot change the equilibrium time" in html
    # the radiation coefficient over 20–30 °C: (303.15 / 293.15)³ − 1 = 10.6 %
    assert "over the 10 K of the ambient series" in html and "(∝ T³) by 11 %" in html
    # the runs' own times (75 and 85 min) and the stated ones (120, 70 min)
    assert "The model&#x27;s equilibrium times of I, III: 75, 85 min (10 min apart); the stated ones: 120, 70 min " \
           "(50 min apart)." in html


def test_the_trend_prose_is_the_series_slopes():
    from feedtherm.outputs.report.operating import ambient_trends, trend_text, trends_section

    validation = ambient_validation()
    trends = ambient_trends(validation)
    assert trends.conditions == ["I", "III"]
    assert trends.elongation == pytest.approx(-0.4) and trends.measured_elongation == pytest.approx(3.0)
    assert trends.temperatures == {q: pytest.approx(1.0) for q in ("T1", "T2", "T3", "T4", "T5")}
    assert trends.measured_temperatures == {q: pytest.approx(0.9) for q in ("T1", "T2", "T3", "T4", "T5")}
    text = trend_text(trends)
    assert ("Over the ambient series (I, III), the model's temperatures change by +1.00 K per kelvin of ambient "
            "and the model's D falls by 0.40 µm per kelvin; the measured temperatures change by +0.90 K per kelvin "
            "of ambient and the measured D rises by 3.00 µm per kelvin.") == text
    assert esc(text) in trends_section(validation)
    assert "α·L" not in trends_section(validation)


def test_sensitivities_sorted_by_largest_temperature_effect(rendered):
    first = rendered.index("sources.front_bearing.preload")  # 3.0 K beats 2.0 K
    assert first < rendered.index("sources.screw_nut.mu", rendered.index('id="sensitivity"'))
    assert "condition I" in rendered


def test_a_joint_is_named_by_its_parts_under_its_path(rendered):
    table = rendered[rendered.index('id="sensitivity"'):]
    path = table.index("<code>joints[6].tcr</code>")
    assert table.index("joint &lt;nut&gt;–screw: tcr") > path  # the name, escaped, after the path


def test_no_calibration_is_said_and_a_calibration_is_tabled(rendered):
    assert "None: every value is from the source or a declared assumption" in rendered
    html = render_report(synthetic_validation(calibrated=[
        {"path": "sources.screw_nut.mu", "value": 0.1234567, "conditions": ["I", "III"]}]))
    assert '<th scope="row">sources.screw_nut.mu</th><td>0.1235</td><td>I, III</td>' in html
    # a calibrated description validated: its runs, and every table of them, are the calibrated model's
    assert "runs of the calibrated model" in html and "uncalibrated" not in html
    assert 'data-model="calibrated model"' in html


def test_without_single_drive_sensitivities_or_budget_those_sections_are_left_out():
    html = render_report(synthetic_validation(single_drive={}, sensitivities=[], heat_budget={}))
    for anchor, title in (("dual-single", "Dual drive against single drive"), ("sensitivity", "Sensitivity ranking"),
                          ("heat-budget", "Heat budget per source")):
        assert f'id="{anchor}"' not in html and f'href="#{anchor}"' not in html and title not in html
    assert "No single-drive runs were made." not in html
    assert len(DATA_URI.findall(html)) == 5


def test_write_report_into_a_directory_or_to_a_file(tmp_path, monkeypatch):
    validation = synthetic_validation()
    written = write_report(validation, tmp_path / "out")
    assert written == tmp_path / "out" / REPORT_HTML and written.read_text(encoding="utf-8").startswith("<!DOCTYPE")
    monkeypatch.setattr(report_module, "render_report", lambda validation: "<!DOCTYPE html>")  # same path, faster
    named = write_report(validation, tmp_path / "named.html")
    assert named == tmp_path / "named.html" and named.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["named.html", "out"]
    assert [p.name for p in (tmp_path / "out").iterdir()] == [REPORT_HTML]


def test_a_failed_report_leaves_the_old_file_and_no_partial(tmp_path, monkeypatch):
    target = tmp_path / REPORT_HTML
    target.write_text("old", encoding="utf-8")

    def broken(validation):
        raise RuntimeError("no ink")

    monkeypatch.setattr(report_module, "render_report", broken)
    with pytest.raises(RuntimeError):
        write_report(synthetic_validation(), tmp_path)
    assert target.read_text(encoding="utf-8") == "old" and list(tmp_path.iterdir()) == [target]


def test_an_unwritable_place_is_a_clear_error(tmp_path, monkeypatch):
    monkeypatch.setattr(report_module, "render_report", lambda validation: "<!DOCTYPE html>")
    blocker = tmp_path / "file"
    blocker.write_text("x", encoding="utf-8")
    with pytest.raises(FeedthermError, match="cannot write the report"):
        write_report(synthetic_validation(), blocker / "sub")


def test_a_long_sensitivity_ranking_is_complete_with_its_tail_folded(monkeypatch):
    from feedtherm.outputs.report import context

    monkeypatch.setattr(context.figures, "sensitivity_bars", lambda rows, condition: PNG_1PX)
    rows = [Sensitivity(f"p.{i}", "s", 1.1, {"T1": i / 10, "T2": 0.0, "T3": 0.0, "T4": 0.0, "T5": 0.0, "D_um": 0.0})
            for i in range(35)]
    html = context.sensitivity_section(synthetic_validation(sensitivities=rows))
    shown, folded = html.split("<details>")
    assert shown.count("<code>p.") == context.TABLE_ROWS and folded.count("<code>p.") == 5
    assert "<summary>The other 5 parameters</summary>" in folded
    assert shown.index("<code>p.34</code>") < shown.index("<code>p.33</code>")  # largest first


def test_headline_puts_physics_held_out_leave_one_out_and_the_paper_side_by_side():
    from feedtherm.analysis.consistency import ConsistencyReport, ElongationLaw, Flag
    from feedtherm.outputs.report.fidelity import consistency_section, headline_section

    base = synthetic_validation()
    flagged_d = next(c for c in base.comparisons if c.condition == "II" and c.quantity == "D_um")
    flag = Flag("II", "D_um", "elongation_law", "off the line <by far>", 12.0)
    calibration = {
        "fit_conditions": ["I"],
        "parameters": {"screw_nut_preload": {"fitted": 812.0, "standard_error": 40.0, "at_bound": None}},
        "held_out": [
            {"condition": "II", "quantity": "T3", "unit": "C", "predicted": 40.0, "measured": 38.7, "deviation": 1.3},
            {"condition": "II", "quantity": "D_um", "unit": "um", "predicted": 60.0, "measured": 30.0, "deviation": 30.0,
             "flag": "off the line"},
            {"condition": "II", "quantity": "t_eq", "unit": "min", "predicted": 130.0, "measured": 100.0, "deviation": 30.0},
        ],
        "cross_validation": {
            "largest_temperature_deviation_C": {"condition": "I", "quantity": "T1", "deviation": -2.4},
            "largest_elongation_deviation_um": {"condition": "I", "quantity": "D_um", "deviation": 5.5},
            "largest_equilibrium_deviation_min": {"condition": "II", "quantity": "t_eq", "deviation": -12.0},
        },
    }
    law = ElongationLaw(2.9, -57.0, ["I"], 0.8, ["T1", "T2"])
    validation = synthetic_validation(consistency=ConsistencyReport([flag], law, []), calibration=calibration)
    html = headline_section(validation)
    # the held-out row leaves the flagged elongation out of its maximum: none is left
    assert "calibrated model, fitted to I, predicting II (held out)" in html
    assert "1.3 (II T3)" in html and "30.0 (II t_eq)" in html and "30.0 (II D)" not in html
    assert "2.4 (I T1)" in html and "5.5 (I D)" in html and "12.0 (II t_eq)" in html
    # the reference model's in-sample figures, from the measurements' reference values: 1.0 K, no D
    assert ("<tr><th scope=\"row\">the reference model, in sample (the measurements&#x27; reference values)</th>"
            "<td class=\"num\">1.0</td><td>—</td>") in html
    assert "screw_nut_preload = 812 ± 40" in html
    # the flagged value is listed with its reason (escaped) and this model's deviation
    assert "off the line &lt;by far&gt;" in html and f"{flagged_d.deviation:+.1f} µm" in html
    section = consistency_section(validation)
    assert "D = -57.0 µm + 2.90 µm/K" in section and "elongation_law" in section


def test_headline_without_a_calibration_says_how_to_get_one():
    from feedtherm.outputs.report.fidelity import headline_section

    html = headline_section(synthetic_validation())
    assert "No calibration was given" in html and "--calibration" in html


def test_a_compensation_study_becomes_the_last_section_with_its_numbers_escaped():
    entry = {"law": "regression_lags", "sensors": ["screw_top_x100", "<T1>"], "validation_rms_um": 0.41,
             "test": {"rms_um": 0.49, "max_um": 2.34, "reduction_percent": 98.9}}
    summary = {"settings": {"cycles": 8, "model": "fast", "mode": "physics", "seed": 0, "spread": 0.2},
               "sets": {"test": {"uncompensated_rms_um": 44.7, "uncompensated_max_um": 79.2}},
               "curves": {"regression_lags": [entry]}, "declared": {}, "best": entry,
               "measured": {"regression_lags": {"law": "regression_lags", "sensors": ["T1"], "conditions": [
                   {"condition": "I", "measured_um": 29.9, "predicted_um": 46.1, "deviation_um": 16.2,
                    "paper_deviation_um": 2.9}]}}}
    html = render_report(synthetic_validation(compensation={"summary": summary, "figures": {}}))
    assert html.index('id="compensation"') > html.index('id="assumptions"')  # after the last of the others
    section = html[html.index('id="compensation"'):]
    assert "&lt;T1&gt;" in section and "<T1>" not in section
    assert "0.49" in section and "2.34" in section and "98.9" in section and "+16.2" in section and "+2.9" in section
    assert 'id="compensation"' not in render_report(synthetic_validation())


def test_an_uncertainty_study_becomes_the_section_after_compensation():
    from feedtherm.outputs.uncertainty_files import summary
    from uncertainty_study import make_study

    compensation = {"summary": {"settings": {"cycles": 1, "model": "fast", "mode": "physics", "seed": 0, "spread": 0.2},
                                "sets": {"test": {"uncompensated_rms_um": 1.0, "uncompensated_max_um": 2.0}},
                                "curves": {}, "declared": {},
                                "best": {"law": "kalman", "sensors": ["T1"], "validation_rms_um": 0.1,
                                         "test": {"rms_um": 0.1, "max_um": 0.2, "reduction_percent": 90.0}}},
                    "figures": {}}
    uncertainty = {"summary": summary(make_study(calibrated=False)), "figures": {"finals.png": PNG_1PX}}
    html = render_report(synthetic_validation(compensation=compensation, uncertainty=uncertainty))
    assert html.index('id="uncertainty"') > html.index('id="compensation"')
    section = html[html.index('id="uncertainty"'):]
    assert "15 of 30 measured values lie inside the prior 5–95 % band" in section
    assert section.count("data:image/png;base64") == 1
    assert 'id="uncertainty"' not in render_report(synthetic_validation())


def test_figures_are_palette_pngs_a_third_of_the_rgba_file(monkeypatch):
    """The heat budget figure as matplotlib writes it (RGBA) and as the report embeds it: same pixels in
    size, 256 colours at most, and every pixel within a few levels of the RGBA's (no banding)."""
    import numpy as np
    from PIL import Image

    from feedtherm.outputs.report import figures

    rgba = []
    original = figures.compact_png
    monkeypatch.setattr(figures, "compact_png", lambda png: rgba.append(png) or original(png))
    budget = {"I": {"front_bearing": 5.0, "screw_nut": 6.0, "motor": 9.0}, "II": {"front_bearing": 18.6,
                                                                                  "screw_nut": 6.0, "motor": 12.0}}
    embedded = figures.heat_budget(budget)
    with Image.open(io.BytesIO(rgba[0])) as before, Image.open(io.BytesIO(embedded)) as after:
        assert before.mode == "RGBA" and after.mode == "P" and after.size == before.size
        assert len(after.getcolors(maxcolors=256)) <= figures.PNG_COLOURS
        difference = np.abs(np.asarray(before.convert("RGB"), dtype=int) - np.asarray(after.convert("RGB"), dtype=int))
    assert len(embedded) < len(rgba[0]) / 2
    assert np.percentile(difference, 99) <= 8 and difference.mean() < 1.0
