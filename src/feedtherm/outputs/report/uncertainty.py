"""The uncertainty section of the HTML report: prediction bands, the measurements against them,
and the Sobol indices.

It reads the summary document of a study (``uncertainty.json``, built by
:func:`feedtherm.outputs.uncertainty_files.summary`) and its figures, so a report can show a
study run earlier without running it again.
"""

from __future__ import annotations

from .html import Cell, number, paragraph, png_image, section, table

UNITS = {"C": "°C", "um": "µm"}
WIDTH_UNITS = {"C": "K", "um": "µm"}
_FIGURES = (("bands_over_time.png", "prediction bands over time"),
            ("finals.png", "final values: the bands beside the measured values"),
            ("sobol.png", "Sobol indices of the final values"))


def uncertainty_section(summary: dict, figures: dict[str, bytes]) -> str:
    """``<section id="uncertainty">`` from a study's summary and its PNG figures (name -> bytes)."""
    sets = summary["sets"]
    low, high = (round(100 * b) for b in summary.get("band", (0.05, 0.95)))
    band = f"{low}–{high} %"
    body = [paragraph(_sampling_text(summary, band))]
    body.append(parameter_table(summary["parameters"], "the declared uncertainties (the prior)"))
    for before, entry in zip(sets, sets[1:]):
        if entry["parameters"] != before["parameters"]:
            body.append(parameter_table(entry["parameters"], f"sampled in the {entry['label']} set"))
    body.append(table(["set", "runs", "measured values inside", "mean width T", "mean width D"],
                      [_coverage_row(entry) for entry in sets], caption=f"the final values' {band} bands"))
    body.append(paragraph(coverage_text(sets, band)))
    for name, alt in _FIGURES:
        if name in figures:
            body.append(png_image(figures[name], alt, caption=alt))
    body.append(_finals_table(sets, band))
    for entry in sets:
        if entry.get("sobol"):
            body.append(sobol_table(entry))
            body.append(paragraph(
                "How to read the indices: S1 is the share of the final value's variance that a parameter causes "
                "alone, ST the share it causes alone and through its interactions with the others. An ST near "
                "zero means the parameter can stay at its declared value without narrowing the band; ST well above "
                "S1 means the parameter matters together with others. The 95 % confidence half-widths are in "
                "sobol.csv; indices smaller than their half-width cannot be told from zero."))
    return section("uncertainty", "Prediction bands and global sensitivity", "".join(body))


def _sampling_text(summary: dict, band: str) -> str:
    s = summary["settings"]
    runs = ", ".join(f"{e['runs']} runs for the {e['label']} set" for e in summary["sets"] if e["runs"])
    how = ", ".join(f"{key} {s[key]}" for key in ("sampler", "seed", "model", "mesh", "mode")
                    if s.get(key) is not None)
    text = (f"{len(summary['parameters'])} declared uncertainties of the description "
            f"{summary.get('system', '')} sampled together ({runs}; {how}). At every time the band runs from the {band.split('–')[0]} to "
            f"the {band.split('–')[1]} quantile of the runs; the nominal run takes every parameter at its declared "
            f"value.")
    calibration = next((e["calibration"] for e in summary["sets"] if e.get("calibration")), None)
    if calibration and calibration.get("method", "").startswith("Bayesian update"):
        fit = calibration.get("fit_conditions") or []
        text += (" The calibrated set samples every declared prior updated with the measured final values of "
                 f"condition{'s' if len(fit) > 1 else ''} {', '.join(fit)} (a Laplace approximation of the "
                 f"posterior, noise scale s² {calibration.get('noise_scale_s2', float('nan')):.3g}).")
        error = next((e["model_error"] for e in summary["sets"] if e.get("model_error")), None)
        if error:
            groups: dict[str, list[str]] = {}  # one entry per distinct s·σ: the quantities that share it
            for q, sd in error["sd"].items():
                groups.setdefault(f"{number(sd, 2)} {WIDTH_UNITS['um' if q == 'D_um' else 'C']}", []).append(_name(q))
            sds = "; ".join(f"{', '.join(names)} {value}" for value, names in groups.items())
            text += (" The predictive set adds to the calibrated set's runs the model error the update measured, "
                     f"N(0, s²σ²) with s·σ {sds}: its band is where a measured value is expected (the posterior "
                     "predictive distribution), the calibrated set's where the model's prediction can go; it has "
                     "no runs of its own and no bands over time (s² is measured on the final values).")
    elif calibration:
        fit = calibration.get("fit_conditions")
        text += (" The calibrated set samples the posterior of the calibration"
                 + (f" fitted on condition{'s' if len(fit) > 1 else ''} {', '.join(fit)}" if fit else "") + ".")
    return text


def parameter_table(parameters: list[dict], caption: str) -> str:
    rows = [[p["name"], p["description"], distribution_text(p), p["reason"], p.get("provenance", "")]
            for p in parameters]
    return table(["parameter", "what", "distribution", "reason", "provenance"], rows, caption=caption)


def distribution_text(p: dict) -> str:
    """``uniform 0.8 … 1.2 × declared``, ``normal σ 12 N (declared 3150 N), within 2000 … 4000``."""
    unit = "× declared" if p["kind"] == "scale" else p.get("unit", "")
    def value(x):
        return f"{x:.4g}"
    parts = [p["distribution"]]
    if p["distribution"] in ("normal", "lognormal") and p.get("sigma") is not None:
        parts.append(f"σ {'of ln x ' if p['distribution'] == 'lognormal' else ''}{value(p['sigma'])}")
        if p.get("low") is not None and p.get("high") is not None:
            parts.append(f"within {value(p['low'])} … {value(p['high'])}")
    elif p.get("low") is not None and p.get("high") is not None:
        parts.append(f"{value(p['low'])} … {value(p['high'])}")
    text = " ".join(parts) + (f" {unit}" if unit else "")
    if p["kind"] != "scale":
        text += f" (declared {value(p['declared'])}{' ' + unit if unit else ''})"
    return text


def _coverage_row(entry: dict) -> list:
    widths = entry.get("mean_width", {})
    coverage = entry["coverage"]
    return [entry["label"], str(entry["runs"]) if entry["runs"] else "—", f"{coverage['inside']} of {coverage['total']}",
            _width(widths.get("C"), "C"), _width(widths.get("um"), "um")]


def _width(value, unit: str) -> str:
    return "—" if value is None else f"{number(value, 2)} {WIDTH_UNITS[unit]}"


def coverage_text(sets: list[dict], band: str) -> str:
    """How many measured values lie inside their band before and after calibration, and how much narrower."""
    if not any(e["coverage"]["total"] for e in sets):
        return "No measured values to set against the bands."
    counts = [f"{e['coverage']['inside']} of {e['coverage']['total']} measured values lie inside the {e['label']} "
              f"{band} band" for e in sets]
    text = "; ".join(counts) + "."
    prior = next((e for e in sets if e["label"] == "prior"), None)
    for later in (e for e in sets if prior and e is not prior):
        ratios = []
        for unit, name in (("C", "temperatures"), ("um", "elongation")):
            before, after = prior["mean_width"].get(unit), later["mean_width"].get(unit)
            if before and after is not None:
                ratios.append(f"{name} {number(100 * after / before, 0)} %")
        if ratios:
            text += f" Mean width of the {later['label']} bands against the prior ones: " + ", ".join(ratios) + "."
    flagged = sorted({(f["condition"], f["quantity"]) for e in sets for f in e["finals"] if f.get("flag")})
    if flagged:
        text += (" Measured values flagged by the consistency check (counted like the others): "
                 + ", ".join(f"{c} {_name(q)}" for c, q in flagged) + ".")
    return text


def _finals_table(sets: list[dict], band: str) -> str:
    keyed = [{(f["condition"], f["quantity"]): f for f in e["finals"]} for e in sets]
    measured = [f for f in sets[0]["finals"] if f.get("measured") is not None]
    headers = ["condition", "quantity", "measured"]
    for e in sets:
        headers += [f"{e['label']} {band}", "inside"]
    rows = []
    for f in measured:
        unit = UNITS.get(f["unit"], f["unit"])
        row = [f["condition"], _name(f["quantity"]) + (" (flagged)" if f.get("flag") else ""),
               f"{number(f['measured'], 1)} {unit}"]
        for lookup in keyed:
            g = lookup.get((f["condition"], f["quantity"]))
            if g is None:
                row += ["—", "—"]
                continue
            row.append(f"{number(g['p05'], 1)} … {number(g['p95'], 1)}")
            row.append(Cell("yes", "dev-0") if g.get("inside") else Cell("no", "dev-3"))
        rows.append(row)
    return table(headers, rows, caption="the measured final values against the bands")


def sobol_table(entry: dict) -> str:
    """Parameters (by total index on D, else the first quantity) × quantities: ``ST (S1)``."""
    indices = entry["sobol"]
    quantities = list(dict.fromkeys(i["quantity"] for i in indices))
    quantities = sorted(quantities, key=lambda q: (q == "D_um", q))
    by = "D_um" if "D_um" in quantities else quantities[0]
    lookup = {(i["parameter"], i["quantity"]): i for i in indices}
    parameters = sorted(dict.fromkeys(i["parameter"] for i in indices),
                        key=lambda p: -(lookup.get((p, by), {}).get("ST") or 0.0))
    rows = []
    for p in parameters:
        cells = [p]
        for q in quantities:
            i = lookup.get((p, q))
            cells.append("—" if i is None else f"{number(i['ST'], 2)} ({number(i['S1'], 2)})")
        rows.append(cells)
    return table(["parameter", *(_name(q) for q in quantities)], rows,
                 caption=f"Sobol indices of the final values at condition {entry.get('sobol_condition') or '—'} "
                         f"({entry['label']} set): ST (S1), ordered by ST on {_name(by)}")


def _name(quantity: str) -> str:
    return "D" if quantity == "D_um" else quantity
