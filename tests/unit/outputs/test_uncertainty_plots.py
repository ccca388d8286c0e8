"""What the uncertainty figures plot (their data, not their pixels), and that they are PNGs."""

from __future__ import annotations

import numpy as np
import pytest
from matplotlib.collections import PolyCollection

from feedtherm.outputs import uncertainty_plots as plots
from feedtherm.outputs.report.html import PNG_MAGIC

# The synthetic study lives in tests/ (pytest puts the directory of tests/conftest.py on sys.path).
from uncertainty_study import CONDITIONS, MEASURED, QUANTITIES, TIMES, make_study, measured, nominal


@pytest.fixture(scope="module")
def study():
    return make_study()


def test_quantity_order_puts_temperatures_first_then_d():
    assert plots.quantity_order(["D_um", "T6", "T1", "x", "T1"]) == ["T1", "T6", "x", "D_um"]


def test_band_panels_hold_each_sets_band_and_the_measured_final_value(study):
    panels = plots.band_panels(study, "II")
    assert [p.quantity for p in panels] == list(QUANTITIES)
    d = panels[-1]
    assert d.unit == "um" and d.hours[-1] == 3.0 and d.hours.size == TIMES.size
    assert [layer.label for layer in d.layers] == ["prior", "calibrated"]
    prior, calibrated = d.layers
    np.testing.assert_array_equal(prior.nominal, nominal("II", "D_um"))
    np.testing.assert_array_equal(prior.p05, study.sets[0].bands["II"].quantiles["D_um"][0])
    assert np.all(calibrated.p95 - calibrated.p05 <= prior.p95 - prior.p05)
    assert d.measured == measured("II", "D_um") and d.flag == ""
    assert panels[5].quantity == "T6" and panels[5].measured is None
    with pytest.raises(ValueError, match="no bands for condition 'VI'"):
        plots.band_panels(study, "VI")


def test_finals_panels_are_the_measured_quantities_with_each_sets_counts(study):
    panels = plots.finals_panels(study)
    assert [p.quantity for p in panels] == list(MEASURED)  # T6 is not measured
    for label, uset in zip(("prior", "calibrated"), study.sets):
        assert sum(p.inside[label][0] for p in panels) == uset.coverage[0]
        assert sum(p.inside[label][1] for p in panels) == 30
    d = panels[-1]
    assert d.conditions == list(CONDITIONS)
    assert d.measured == [measured(c, "D_um") for c in CONDITIONS]
    assert [bool(f) for f in d.flags] == [False, False, False, False, True]
    assert [b.condition for b in d.bands["calibrated"]] == list(CONDITIONS)


def test_sobol_matrix_is_ordered_by_the_total_index_on_d(study):
    matrix = plots.sobol_matrix(study.sets[0])
    assert matrix.condition == "I" and matrix.ordered_by == "D_um" and matrix.quantities == list(QUANTITIES)
    d = matrix.quantities.index("D_um")
    assert list(matrix.ST[:, d]) == sorted(matrix.ST[:, d], reverse=True)
    # ST = 0.05 + 0.5 / (1 + (p + 6) % 8): largest for p = 2 (rear_bearing_friction)
    assert matrix.parameters[0] == "rear_bearing_friction" and matrix.ST[0, d] == 0.55
    np.testing.assert_allclose(matrix.ST - matrix.S1, 0.05, atol=1e-9)
    with pytest.raises(ValueError, match="no Sobol indices"):
        plots.sobol_matrix(study.sets[1])


def test_the_bands_figure_shades_two_bands_per_quantity_and_marks_the_measurements(study):
    figure = plots.bands_figure(study, "I")
    drawn = [ax for ax in figure.axes if ax.axison]
    assert len(drawn) == len(QUANTITIES)
    for ax in drawn:
        assert sum(isinstance(c, PolyCollection) for c in ax.collections) == 2  # prior and calibrated band
    assert [ax.get_title() for ax in drawn] == [f"{q} [°C]" for q in QUANTITIES[:-1]] + ["D [µm]"]
    labels = [t.get_text() for t in figure.axes[-1].get_legend().get_texts()]
    assert labels[:3] == ["prior 5–95 %", "prior median", "prior nominal run"] and "measured final value" in labels
    d_marks = [line for line in drawn[-1].lines if line.get_marker() == "D"]
    assert len(d_marks) == 1 and d_marks[0].get_ydata()[0] == measured("I", "D_um")


def test_the_finals_figure_counts_inside_per_quantity_and_in_all(study):
    figure = plots.finals_figure(study)
    assert "prior: 15 of 30; calibrated: 5 of 30" in figure.get_suptitle()
    titles = [ax.get_title() for ax in figure.axes if ax.axison]
    assert len(titles) == len(MEASURED) and titles[-1].startswith("D: measured inside the band\nprior ")
    flagged = [line for ax in figure.axes for line in ax.lines if line.get_marker() == "X"]
    assert len(flagged) == 1 and flagged[0].get_ydata()[0] == measured("V", "D_um")


def test_the_sobol_figure_labels_rows_by_the_ordered_parameters(study):
    figure = plots.sobol_figure(study.sets[0])
    first = figure.axes[0]
    assert [t.get_text() for t in first.get_yticklabels()] == plots.sobol_matrix(study.sets[0]).parameters
    assert [t.get_text() for t in first.get_xticklabels()][-1] == "D"


def test_every_figure_is_a_png(study):
    prior_only = make_study(calibrated=False)
    for png in (plots.bands_over_time(prior_only, "V"), plots.finals_against_measurements(prior_only),
                plots.sobol_indices(study.sets[0])):
        assert png.startswith(PNG_MAGIC) and len(png) > 10_000
