"""`feedtherm uncertainty` outputs: the bands, the final values beside the measurements, the Sobol
indices, the figures and the report section as a page.

Files (all in one directory, replaced as a set):

- ``uncertainty.json``: settings, the declared uncertainties, and per set (the priors, then the
  calibrated posterior if there is one, then the predictive set after a Bayesian update): runs,
  how many measured values lie inside their band, the final values' bands, their mean width per
  unit, the Sobol indices, the calibration it came from, the predictive set's model error, and
  every condition's bands over time (numbers rounded to ``DECIMALS``);
- ``bands.csv``: one row per set, condition, quantity and time;
- ``finals.csv``: one row per set, condition and quantity: the final value's band beside its measurement;
- ``sobol.csv``: one row per set, quantity and parameter;
- ``bands_over_time.png`` (the Sobol condition, else the first), ``finals.png``, ``sobol.png``
  (if a set has indices) and ``uncertainty.html`` (the report's section).

:func:`read_uncertainty_summary` reads a folder back for ``feedtherm validate --uncertainty``.
"""

from __future__ import annotations

import csv
import re
import sys
from dataclasses import asdict
from pathlib import Path

import numpy as np
from rich.console import Console
from rich.table import Table

from ..analysis.uncertainty.types import BAND, UncertainParameter, UncertaintySet, UncertaintyStudy
from . import uncertainty_plots as plots
from ..errors import FeedthermError
from .files import json_text, read_study_summary, staged_directory
from .report.html import page
from .report.uncertainty import uncertainty_section

UNCERTAINTY_JSON = "uncertainty.json"
FIGURES = ("bands_over_time.png", "finals.png", "sobol.png")
UNCERTAINTY_FILES = (UNCERTAINTY_JSON, "bands.csv", "finals.csv", "sobol.csv", *FIGURES, "uncertainty.html")
BANDS_HEADER = ["set", "condition", "quantity", "unit", "time_s", "p05", "p50", "p95", "nominal"]
FINALS_HEADER = ["set", "condition", "quantity", "unit", "p05", "p50", "p95", "nominal", "measured", "inside", "flag"]
SOBOL_HEADER = ["set", "condition", "quantity", "parameter", "S1", "S1_conf", "ST", "ST_conf"]
#: Decimals of every band value written (°C and µm: 0.1 mK and 0.1 nm, far below any band's width).
DECIMALS = 4
#: Decimals of the Sobol indices and their confidence half-widths (shares of a variance).
INDEX_DECIMALS = 4


# --------------------------------------------------------------------------- the summary


def parameter_entry(parameter: UncertainParameter) -> dict:
    entry = asdict(parameter)
    entry["paths"] = list(parameter.paths)
    return entry


def mean_widths(uset: UncertaintySet) -> dict[str, float]:
    """Unit -> the mean width (p95 − p05) of the bands of the measured final values.

    Only the values a measurement is judged against count: the ambient sensor's band (zero
    wide, it is the condition's input) would otherwise pull the temperatures' mean down.  A
    study without measurements averages every final value.
    """
    widths: dict[str, list[float]] = {}
    measured = [final for final in uset.finals if final.measured is not None]
    for final in measured or uset.finals:
        widths.setdefault(final.unit, []).append(final.p95 - final.p05)
    return {unit: round(float(np.mean(values)), DECIMALS) for unit, values in widths.items()}


def _final_entry(final) -> dict:
    return {"condition": final.condition, "quantity": final.quantity, "unit": final.unit,
            **{key: round(float(getattr(final, key)), DECIMALS) for key in ("p05", "p50", "p95", "nominal")},
            "measured": final.measured, "inside": final.inside, "flag": final.flag}


def _rounded(values) -> list:
    return np.round(np.asarray(values, dtype=float), DECIMALS).tolist()


def _bands_entry(uset: UncertaintySet) -> dict:
    out = {}
    for condition, band in uset.bands.items():
        quantities = {}
        for quantity in plots.quantity_order(band.quantiles):
            q = np.asarray(band.quantiles[quantity], dtype=float)
            quantities[quantity] = {"p05": _rounded(q[0]), "p50": _rounded(q[1]), "p95": _rounded(q[2]),
                                    "nominal": _rounded(band.nominal[quantity])}
        out[condition] = {"time_s": np.round(np.asarray(band.time_s, dtype=float), 3).tolist(),
                          "quantities": quantities}
    return out


def _set_entry(uset: UncertaintySet) -> dict:
    inside, total = uset.coverage
    return {
        "label": uset.label,
        "runs": uset.runs,
        "parameters": [parameter_entry(p) for p in uset.parameters],
        "coverage": {"inside": inside, "total": total},
        "mean_width": mean_widths(uset),
        "finals": [_final_entry(f) for f in uset.finals],
        "sobol_condition": uset.sobol_condition,
        "sobol": [{"quantity": i.quantity, "parameter": i.parameter,
                   **{key: round(float(getattr(i, key)), INDEX_DECIMALS) for key in ("S1", "S1_conf", "ST", "ST_conf")}}
                  for i in uset.sobol],
        "calibration": uset.calibration,
        "model_error": uset.model_error,
        "bands": _bands_entry(uset),
    }


def summary(study: UncertaintyStudy) -> dict:
    """The study as a JSON-able document (see the module's notes)."""
    return {
        "system": study.system,
        "settings": study.settings,
        "band": list(BAND),
        "parameters": [parameter_entry(p) for p in study.sets[0].parameters] if study.sets else [],
        "sets": [_set_entry(s) for s in study.sets],
    }


# --------------------------------------------------------------------------- the files


def figures(study: UncertaintyStudy) -> dict[str, bytes]:
    """The study's figures, name -> PNG bytes (``sobol.png`` only if a set has indices)."""
    out = {"bands_over_time.png": plots.bands_over_time(study, figure_condition(study)),
           "finals.png": plots.finals_against_measurements(study)}
    with_indices = [s for s in study.sets if s.sobol]
    if with_indices:
        out["sobol.png"] = plots.sobol_indices(with_indices[0])
    return out


def figure_condition(study: UncertaintyStudy) -> str:
    """The condition the bands figure shows: the Sobol indices', else the first with bands."""
    first = study.sets[0]
    if first.sobol_condition and first.sobol_condition in first.bands:
        return first.sobol_condition
    return next(iter(first.bands))


def write_uncertainty(study: UncertaintyStudy, out_dir: Path) -> list[Path]:
    """Write the study's files (see the module's notes) into ``out_dir`` as one set; return their paths."""
    document = summary(study)
    pictures = figures(study)
    html = page(f"feedtherm: uncertainty, {study.system}", uncertainty_section(document, pictures))
    with staged_directory(out_dir, replaces=UNCERTAINTY_FILES) as stage:
        (stage / UNCERTAINTY_JSON).write_text(compact_json(document) + "\n", encoding="utf-8")
        _write_csv(stage / "bands.csv", BANDS_HEADER, _band_rows(study))
        _write_csv(stage / "finals.csv", FINALS_HEADER, _final_rows(study))
        _write_csv(stage / "sobol.csv", SOBOL_HEADER, _sobol_rows(study))
        for name, png in pictures.items():
            (stage / name).write_bytes(png)
        (stage / "uncertainty.html").write_text(html, encoding="utf-8")
        names = sorted(p.name for p in stage.iterdir())
    return [Path(out_dir) / name for name in names]


# A list of numbers only, as json_text indents it: one number per line.
_NUMBER = r"-?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?|null"
_NUMBER_LIST = re.compile(rf"\[\n\s*((?:{_NUMBER})(?:,\n\s*(?:{_NUMBER}))*)\n\s*\]")


def compact_json(document) -> str:
    """:func:`~feedtherm.outputs.files.json_text`, but a list of numbers on one line: the bands'
    thousands of values stay a file one can read."""
    return _NUMBER_LIST.sub(lambda m: "[" + ", ".join(re.split(r",\n\s*", m[1])) + "]", json_text(document))


def _value(x: float) -> str:
    return f"{x:.{DECIMALS}f}"


def _band_rows(study: UncertaintyStudy):
    for uset in study.sets:
        for condition, band in uset.bands.items():
            units = {f.quantity: f.unit for f in uset.finals if f.condition == condition}
            for quantity in plots.quantity_order(band.quantiles):
                q = np.asarray(band.quantiles[quantity], dtype=float)
                unit = units.get(quantity, "um" if quantity == "D_um" else "C")
                for k, t in enumerate(np.asarray(band.time_s, dtype=float)):
                    yield [uset.label, condition, quantity, unit, f"{t:.10g}", _value(q[0, k]), _value(q[1, k]),
                           _value(q[2, k]), _value(band.nominal[quantity][k])]


def _final_rows(study: UncertaintyStudy):
    for uset in study.sets:
        for f in uset.finals:
            inside = "" if f.inside is None else str(f.inside).lower()
            yield [uset.label, f.condition, f.quantity, f.unit, _value(f.p05), _value(f.p50), _value(f.p95),
                   _value(f.nominal), "" if f.measured is None else f"{f.measured:.10g}", inside, f.flag]


def _sobol_rows(study: UncertaintyStudy):
    for uset in study.sets:
        for i in uset.sobol:
            yield [uset.label, uset.sobol_condition or "", i.quantity, i.parameter,
                   *(f"{getattr(i, key):.{INDEX_DECIMALS}f}" for key in ("S1", "S1_conf", "ST", "ST_conf"))]


def _write_csv(path: Path, header: list[str], rows) -> None:
    with open(path, "w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle, lineterminator="\n")
        writer.writerow(header)
        writer.writerows(rows)


# --------------------------------------------------------------------------- the console


def print_uncertainty(study: UncertaintyStudy, out_dir: Path, console: Console | None = None) -> None:
    """Coverage and mean band widths per set, the leading Sobol parameters, where the files are."""
    console = console or Console(width=None if sys.stdout.isatty() else 120)
    low, high = (round(100 * b) for b in BAND)
    table = Table(title=f"{study.system}: {low}–{high} % prediction bands of the final values", title_justify="left")
    for column in ("set", "runs", "measured inside", "mean width T [K]", "mean width D [µm]"):
        table.add_column(column, justify="left" if column == "set" else "right")
    for uset in study.sets:
        inside, total = uset.coverage
        widths = mean_widths(uset)
        table.add_row(uset.label, str(uset.runs) if uset.runs else "—", f"{inside} of {total}", _width(widths.get("C")),
                      _width(widths.get("um")))
    console.print(table)
    for uset in study.sets:
        inside, total = uset.coverage
        if total:
            console.print(f"{uset.label}: {inside} of {total} measured values inside the {low}–{high} % band")
    for uset in (s for s in study.sets if s.sobol):
        for quantity in plots.quantity_order(i.quantity for i in uset.sobol):
            if quantity == study.settings.get("ambient_sensor"):
                continue  # the ambient: its indices say which input sets the ambient, nothing more
            top = sorted((i for i in uset.sobol if i.quantity == quantity), key=lambda i: -i.ST)[:3]
            console.print(f"Sobol ST at {uset.sobol_condition}, {quantity}: "
                          + ", ".join(f"{i.parameter} {i.ST:.2f}" for i in top))
    console.print(f"wrote {out_dir}/uncertainty.json, bands.csv, finals.csv, sobol.csv, figures, uncertainty.html")


def _width(value: float | None) -> str:
    return "—" if value is None else f"{value:.2f}"


# --------------------------------------------------------------------------- reading back


def read_uncertainty_summary(folder: Path) -> dict:
    """``{"summary": uncertainty.json, "figures": {name: PNG bytes}}`` of a study's folder;
    one-line errors naming what is wrong (``feedtherm validate --uncertainty DIR``)."""
    document = read_study_summary(folder, UNCERTAINTY_JSON, "--uncertainty", "uncertainty",
                                  ("settings", "parameters", "sets"))
    problem = _shape_problem(document)
    if problem:
        raise FeedthermError(f"--uncertainty: {Path(folder) / UNCERTAINTY_JSON}: {problem}; is it an {UNCERTAINTY_JSON}?")
    pictures = {name: (Path(folder) / name).read_bytes() for name in FIGURES if (Path(folder) / name).is_file()}
    return {"summary": document, "figures": pictures}


#: What the report section reads of each set, and of each final value and parameter in it.
_SET_KEYS = ("label", "runs", "parameters", "coverage", "mean_width", "finals")
_FINAL_KEYS = ("condition", "quantity", "unit", "p05", "p95", "measured", "inside")
_PARAMETER_KEYS = ("name", "description", "kind", "declared", "distribution", "reason")


def _shape_problem(document: dict) -> str:
    """What keeps the report section from reading ``document`` ("" if nothing)."""
    sets = document["sets"]
    if not isinstance(sets, list) or not sets or not all(isinstance(s, dict) for s in sets):
        return "sets is not a list of sets"
    for name, entries, keys in [("parameters", document["parameters"], _PARAMETER_KEYS)] + [
            (f"sets[{k}].{part}", s.get(part), keys) for k, s in enumerate(sets)
            for part, keys in (("parameters", _PARAMETER_KEYS), ("finals", _FINAL_KEYS))]:
        if not isinstance(entries, list) or not all(isinstance(e, dict) for e in entries):
            return f"{name} is not a list of entries"
        for index, entry in enumerate(entries):
            missing = [key for key in keys if key not in entry]
            if missing:
                return f"{name}[{index}] lacks {', '.join(missing)}"
    for k, s in enumerate(sets):
        missing = [key for key in _SET_KEYS if key not in s]
        if missing:
            return f"sets[{k}] lacks {', '.join(missing)}"
        if not isinstance(s["coverage"], dict) or not {"inside", "total"} <= set(s["coverage"]):
            return f"sets[{k}].coverage is not {{inside, total}}"
    return ""
