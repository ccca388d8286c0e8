"""The report's displacement section: the declared loop, D per condition, the gains, the stroke figure."""

from __future__ import annotations

import base64
import re

import numpy as np
import pytest

from feedtherm.analysis.consistency import ConsistencyReport, ElongationLaw, Flag
from feedtherm.analysis.validation_types import Comparison, OperatingPointRow, Validation
from feedtherm.benches import ReportNotes
from feedtherm.outputs.report.displacement import displacement_section, gains

from test_run_files import make_solution

LOOP = {"elongation": {"target": "screw at (450, 0, 0) mm", "mount": "base at (480, 0, -60) mm",
                       "direction": [1.0, 0.0, 0.0], "description": "laser on a stand"},
        "positioning_reference": "base at (0, 0, -60) mm"}
#: A bench's conditions as its description declares them: I-III differ in speed at 20 °C, IV, II, V
#: in ambient at the speeds of II.
POINTS = {"I": OperatingPointRow(396.0, 360.0, 20.0), "II": OperatingPointRow(1116.0, 1080.0, 20.0),
          "III": OperatingPointRow(2214.0, 2160.0, 20.0), "IV": OperatingPointRow(1116.0, 1080.0, 15.0),
          "V": OperatingPointRow(1116.0, 1080.0, 25.0)}
EARLIER = {"with a fitted read point (193 mm)": 1.7, "read at 400 mm, nothing fitted there": 21.0}


def validation(measured_d: dict[str, float], simulated_d: dict[str, float], mean_t: dict[str, float], **changes):
    """Comparisons whose five measured temperatures all equal the condition's mean T̄."""
    runs = {}
    comparisons = []
    for c in measured_d:
        solution = make_solution()
        solution.info["measuring_loop"] = LOOP
        runs[c] = solution
        comparisons += [Comparison(c, q, "C", mean_t[c] + 1.0, mean_t[c], None) for q in ("T1", "T2", "T3", "T4", "T5")]
        comparisons.append(Comparison(c, "D_um", "um", simulated_d[c], measured_d[c], None))
    values = dict(system_name="bench", model="fast", comparisons=comparisons, solutions=runs,
                  single_drive={}, heat_budget={}, measured_equilibrium_min={}, sensitivities=[],
                  sensitivity_condition="I", inconsistencies=[], assumptions=[], operating_points=POINTS,
                  notes=ReportNotes(earlier_held_out_elongation_um=EARLIER))
    values.update(changes)
    return Validation(**values)


def test_the_gains_are_the_slopes_over_the_mean_measured_temperature():
    # hand calculation: simulated D = 4.5 T̄ − 100 and measured D = 2.86 T̄ − 56.6 over three conditions
    t = {"I": 30.0, "II": 32.0, "III": 34.0}
    v = validation({c: 2.86 * x - 56.6 for c, x in t.items()}, {c: 4.5 * x - 100.0 for c, x in t.items()}, t)
    model, bench, names = gains(v)
    assert model == pytest.approx(4.5, rel=1e-12) and bench == pytest.approx(2.86, rel=1e-12)
    assert names == ["I", "II", "III"]


def test_the_gains_use_only_the_conditions_the_elongation_law_holds_for():
    t = {"I": 30.0, "II": 32.0, "V": 36.0}
    measured = {"I": 29.2, "II": 34.9, "V": 71.5}
    simulated = {"I": 29.0, "II": 38.0, "V": 99.0}  # V would pull the model's slope up
    law = ElongationLaw(2.85, -56.3, ["I", "II"], 0.0, ["T1", "T2", "T3", "T4", "T5"])
    flag = Flag("V", "D_um", "elongation_law", "off the line", 20.0)
    v = validation(measured, simulated, t, consistency=ConsistencyReport([flag], law, []))
    model, bench, names = gains(v)
    assert model == pytest.approx((38.0 - 29.0) / 2.0) and bench == 2.85 and names == ["I", "II"]
    html = displacement_section(v)
    assert "71.5 (flagged)" in html
    assert "<td>I, II</td><td>4.50</td><td>2.85</td>" in html


def test_the_series_gains_show_errors_that_cancel_over_all_conditions():
    # hand calculation: against speed (I, II, III at 20 °C) the model gains 11 µm/K where the bench
    # gains 3; against ambient (IV, II) the model loses 0.5 µm/K where the bench gains 2.5
    t = {"I": 30.0, "II": 32.0, "III": 34.0, "IV": 26.0}
    measured = {"I": 30.0, "II": 36.0, "III": 42.0, "IV": 21.0}
    simulated = {"I": 30.0, "II": 52.0, "III": 74.0, "IV": 55.0}
    v = validation(measured, simulated, t)
    assert gains(v, ["I", "II", "III"])[:2] == (pytest.approx(11.0), pytest.approx(3.0))
    assert gains(v, ["IV", "II", "V"]) == (pytest.approx(-0.5), pytest.approx(2.5), ["IV", "II"])
    html = displacement_section(v)
    assert "against speed (ambient 20 °C)</th><td>I, II, III</td><td>11.00</td><td>3.00</td>" in html


def test_the_section_names_the_loop_and_shows_the_stroke_figure():
    t = {"I": 30.0, "II": 32.0}
    html = displacement_section(validation({"I": 29.9, "II": 35.5}, {"I": 29.2, "II": 50.0}, t))
    assert "screw at (450, 0, 0) mm" in html and "base at (480, 0, -60) mm" in html
    assert "relative to base at (0, 0, -60) mm" in html
    png = re.search(r'data:image/png;base64,([A-Za-z0-9+/=]+)', html).group(1)
    assert base64.b64decode(png).startswith(b"\x89PNG")
    assert "+14.5" in html  # II: simulated 50.0 against 35.5 measured


def test_a_calibration_puts_the_held_out_elongation_beside_the_earlier_figures():
    t = {"I": 30.0, "II": 32.0}
    calibration = {"fit_conditions": ["I"], "held_out": [
        {"condition": "II", "quantity": "D_um", "unit": "um", "deviation": -7.25},
        {"condition": "II", "quantity": "T1", "unit": "C", "deviation": 3.0}],
        "cross_validation": {"largest_elongation_deviation_um": {"condition": "IV", "quantity": "D_um",
                                                                 "deviation": 12.0}}}
    html = displacement_section(validation({"I": 29.9, "II": 35.5}, {"I": 29.2, "II": 50.0}, t,
                                           calibration=calibration))
    assert "held out, 7.2 µm (II)" in html or "held out, 7.3 µm (II)" in html
    assert "leave-one-condition-out, 12.0 µm (IV)" in html
    for value in EARLIER.values():
        assert f"{value:.1f} µm" in html
