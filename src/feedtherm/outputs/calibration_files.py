"""`feedtherm calibrate` outputs: the calibrated description, calibration.json, held-out tables.

The calibrated description is the original TOML text with the fitted values replaced (in the
units the original used) and one ``[[provenance]]`` entry per fitted parameter saying that it
was calibrated, on which conditions, from which original value.  It loads like any other.
A declared uncertainty (``[uncertainty.parameters]``) on a fitted value is left out of it: the
fit's posterior replaces that prior (``feedtherm uncertainty --calibration``), and a prior's
range need not contain the fitted value.
"""

from __future__ import annotations

import csv
import sys
from pathlib import Path

import numpy as np
import tomlkit
from rich.console import Console
from rich.table import Table

from ..analysis.calibration import SERIES_STEP_S, CalibrationResult, Prediction
from ..analysis.transient_scores import TransientComparison
from ..benches import bench, bench_name_of
from ..errors import FeedthermError
from ..system.load import LoadedSystem, read_text
from ..system.overlay import overlay_spec
from ..system.paths import expand_path, split_path
from ..system.quantities import registry
from .files import read_study_summary, staged_directory, write_json

PREDICTION_HEADER = ["condition", "quantity", "unit", "predicted", "measured", "deviation", "interval95", "flag"]
#: Every file a calibration can write: crossval.csv only with cross-validation.
CALIBRATION_FILES = ("calibrated.toml", "calibration.json", "heldout.csv", "crossval.csv")


def read_calibration_summary(folder: Path) -> dict:
    """calibration.json of a calibration's output folder; one-line errors naming what is wrong."""
    return read_study_summary(folder, "calibration.json", "--calibration", "calibrate",
                              ("fit_conditions", "parameters", "held_out"))


def calibrated_toml(original: LoadedSystem, result: CalibrationResult) -> str:
    """The original description's text with the fitted values set and their provenance added."""
    text, _ = read_text(original.origin.split(" (")[0].replace("bundled:", "") if original.origin.startswith("bundled:")
                        else original.origin)
    doc = tomlkit.parse(text)
    conditions = ", ".join(result.fit_conditions)
    declared = original.system.calibration.parameters if original.system.calibration else {}
    for parameter, x, se in zip(result.parameters, result.fitted, result.standard_errors):
        # a value the description leaves at its default is written in its bounds' unit
        bound = declared[parameter.name].bounds[0] if parameter.name in declared else None
        template = bound if parameter.kind == "value" and isinstance(bound, str) else None
        for path, value in parameter.values(float(x)).items():
            _set(doc, path, value, template)
        provenance = tomlkit.table()
        provenance["paths"] = parameter.paths
        provenance["origin"] = "assumption"
        provenance["source"] = f"calibrated by feedtherm calibrate on conditions {conditions} ({result.measurement_source})"
        original_text = ", ".join(f"{o:.6g}" for o in parameter.originals[:3]) + (" ..." if len(parameter.originals) > 3 else "")
        kind = "factor" if parameter.kind == "scale" else "value"
        provenance["reason"] = (f"parameter {parameter.name} ({kind}) fitted to {x:.6g} +- {se:.3g} (1 standard error) "
                                f"within [{parameter.lower:g}, {parameter.upper:g}]; original SI value(s): {original_text}")
        doc.setdefault("provenance", tomlkit.aot()).append(provenance)
    _drop_fitted_uncertainties(doc, original, result)
    meta = doc["meta"]
    meta["name"] = f"{meta['name']}_calibrated"
    meta["description"] = f"{meta.get('description', '')} Calibrated on conditions {conditions}.".strip()
    if "measurements" in meta and not str(meta["measurements"]).startswith("bundled:") and not original.origin.startswith("bundled:"):
        meta["measurements"] = str(Path(original.origin).parent / str(meta["measurements"]))
    for name, test in (doc.get("tests") or {}).items():  # a test's own file, where the original finds it
        if test.get("measurements"):
            test["measurements"] = _beside_original(str(test["measurements"]), original)
    overlay = overlay_spec(original)  # the calibrated machine can run in the original's modes
    if overlay is not None:
        meta["overlay"] = overlay if overlay.startswith("bundled:") or Path(overlay).is_absolute() \
            else str(Path(original.origin).parent / overlay)
    return tomlkit.dumps(doc)


def _beside_original(spec: str, original: LoadedSystem) -> str:
    """A file the original description names relative to itself (or its bench's folder), as a path the
    calibrated description, written elsewhere, finds too."""
    if spec.startswith("bundled:") or Path(spec).is_absolute():
        return spec
    name = bench_name_of(original.origin)
    folder = bench(name).folder if name is not None else Path(original.origin.split(" (")[0]).parent
    return str((Path(folder) / spec).resolve())


def _drop_fitted_uncertainties(doc, original: LoadedSystem, result: CalibrationResult) -> None:
    """Remove the declared uncertainties on values the calibration fitted (their prior is superseded)."""
    declared = original.system.uncertainty
    if declared is None or "uncertainty" not in doc:
        return
    fitted = {p for parameter in result.parameters for p in parameter.paths}
    table = doc["uncertainty"]["parameters"]
    for name, spec in declared.parameters.items():
        if fitted & {p for path in spec.paths for p in expand_path(original.system, path)}:
            del table[name]
    if not table:
        del doc["uncertainty"]


def _set(doc, path: str, value: float, template: str | None = None) -> None:
    """Set ``path`` in the TOML document, creating the tables a default left out."""
    keys = split_path(path)
    node = doc
    for key in keys[:-1]:
        if isinstance(key, str) and key not in node:
            node[key] = tomlkit.table()
        node = node[key]
    last = keys[-1]
    old = node.get(last) if hasattr(node, "get") else None
    node[last] = _formatted(old if old is not None else template, value)


def _formatted(old, value: float):
    """``value`` (SI) written in the unit the original string used, or as a bare number."""
    if isinstance(old, str):
        unit = old.strip().split(" ", 1)[1] if " " in old.strip() else ""
        if unit:
            scale = registry().Quantity(1.0, unit).to_base_units().magnitude
            return f"{value / scale:.6g} {unit}"
    return float(f"{value:.6g}")


def write_predictions(rows: list[Prediction], path: Path, first_column: str | None = None) -> None:
    with open(path, "w", newline="") as handle:
        writer = csv.writer(handle, lineterminator="\n")
        writer.writerow(([first_column] if first_column else []) + PREDICTION_HEADER)
        for row, label in rows:
            writer.writerow(([label] if first_column else []) + [row.condition, row.quantity, row.unit,
                            f"{row.predicted:.4f}", f"{row.measured:.4g}", f"{row.deviation:.4f}",
                            "" if row.interval is None else f"{row.interval:.4f}", row.flag])


def calibration_summary(result: CalibrationResult) -> dict:
    names = [p.name for p in result.parameters]
    return {
        "fit_conditions": result.fit_conditions,
        "parameters": {
            p.name: {"kind": p.kind, "fitted": x, "standard_error": se, "bounds": [p.lower, p.upper],
                     "original": p.originals[0] if p.kind == "value" else 1.0, "paths": p.paths,
                     "identifiable": not why, "note": why, "at_bound": bound or None}
            for p, x, se, why, bound in zip(result.parameters, result.fitted, result.standard_errors,
                                            result.identifiable, result.at_bound)
        },
        "correlation": {"parameters": names, "matrix": np.round(result.correlation, 4).tolist()},
        "residuals": [{"condition": r.condition, "quantity": r.quantity, "unit": r.unit, "simulated": r.predicted,
                       "measured": r.measured, "residual": r.deviation, "interval95": r.interval} for r in result.residuals],
        "excluded": [{"condition": r.condition, "quantity": r.quantity, "unit": r.unit, "simulated": r.predicted,
                      "measured": r.measured, "deviation": r.deviation, "reason": r.flag} for r in result.excluded],
        "held_out": [{"condition": r.condition, "quantity": r.quantity, "unit": r.unit, "predicted": r.predicted,
                      "measured": r.measured, "deviation": r.deviation, "interval95": r.interval, "flag": r.flag or None}
                     for r in result.held_out],
        "motor_duty": {"torque_to_continuous": result.motor_duty,
                       "overloads": [{"condition": c, "motor": m, "torque_to_continuous": r} for c, m, r in result.overloads()]},
        "cost": result.cost,
        "model_runs": result.model_runs,
        "wall_time_s": result.wall_time_s,
        "optimizer_status": result.status,
        "measurements": result.measurement_source,
        "model": f"{result.model}, cycle-averaged motion",
        "mesh": result.mesh,  # the FE mesh of a model that takes one, else null
        **({"series": series_summary(result)} if result.series_fit or result.series_held_out else {}),
    }


#: How a series' samples were weighted in the fit, as calibration.json says it.
WEIGHTS = {True: "declared uncertainties", False: "calibration sigma of the description"}


def _series_entry(s: TransientComparison) -> dict:
    return {"condition": s.condition, "quantity": s.quantity, "unit": s.unit, "samples": len(s.times),
            "start_s": float(s.times[0]), "end_s": float(s.times[-1]), "weights": WEIGHTS[s.uncertainty is not None],
            "rms_deviation": s.rms, "max_abs_deviation": s.max_abs, "time_of_max_s": s.time_of_max,
            "mean_deviation": s.mean, "inside_two_sigma": s.inside_two_sigma}


def series_summary(result: CalibrationResult) -> dict:
    """The measured series: those fitted sample by sample and those of held-out conditions, each
    scored against its run (deviations in K or µm, simulated − measured)."""
    return {
        "fitted_conditions": result.series_conditions,
        "step_s": SERIES_STEP_S,
        "fitted": [_series_entry(s) for s in result.series_fit],
        "held_out": [_series_entry(s) for s in result.series_held_out],
    }


def write_calibration(original: LoadedSystem, result: CalibrationResult, out_dir: Path,
                      cross: list[tuple[str, CalibrationResult]] | None = None) -> list[Path]:
    """Write calibrated.toml, calibration.json, heldout.csv (and crossval.csv), all or none.

    The set replaces an earlier calibration's files in ``out_dir`` whole: a crossval.csv it
    does not write is removed with them.
    """
    with staged_directory(out_dir, replaces=CALIBRATION_FILES) as stage:
        (stage / "calibrated.toml").write_text(calibrated_toml(original, result), encoding="utf-8")
        summary = calibration_summary(result)
        if cross is not None:
            summary["cross_validation"] = cross_summary(cross)
            write_predictions([(r, left) for left, res in cross for r in res.held_out], stage / "crossval.csv",
                              first_column="left_out")
        write_json(stage / "calibration.json", summary)
        write_predictions([(r, None) for r in result.held_out], stage / "heldout.csv")
        names = sorted(p.name for p in stage.iterdir())
    return [Path(out_dir) / n for n in names]


def worst(rows: list[Prediction], unit: str, flagged: bool = False) -> Prediction | None:
    """The largest |deviation| among ``rows`` of ``unit``; flagged values only if ``flagged``."""
    return max((r for r in rows if r.unit == unit and bool(r.flag) == flagged), key=lambda r: abs(r.deviation),
               default=None)


def _worst_entry(row: Prediction | None) -> dict | None:
    if row is None:
        return None
    return {"condition": row.condition, "quantity": row.quantity, "deviation": row.deviation,
            "interval95": row.interval, **({"flag": row.flag} if row.flag else {})}


def cross_summary(cross: list[tuple[str, CalibrationResult]]) -> dict:
    rows = [r for _, res in cross for r in res.held_out]
    return {
        "largest_temperature_deviation_C": _worst_entry(worst(rows, "C")),
        "largest_elongation_deviation_um": _worst_entry(worst(rows, "um")),
        "largest_equilibrium_deviation_min": _worst_entry(worst(rows, "min")),
        "flagged": [_worst_entry(r) for r in rows if r.flag],
        **({"held_out_series": [{"left_out": left, **_series_entry(s)} for left, res in cross
                                 for s in res.series_held_out]}
           if any(res.series_held_out for _, res in cross) else {}),
        "fits": {left: {p.name: x for p, x in zip(res.parameters, res.fitted)} for left, res in cross},
        "at_bound": {left: {p.name: b for p, b in zip(res.parameters, res.at_bound) if b} for left, res in cross},
        "model_runs": sum(res.model_runs for _, res in cross),
        "wall_time_s": sum(res.wall_time_s for _, res in cross),
    }


#: The symbol a deviation of each measured unit is written in.
UNIT_SYMBOLS = {"C": "K", "um": "µm", "min": "min"}


def _largest(rows: list[Prediction]) -> str:
    """Largest |deviation| per kind; a flagged value's apart, with the word flagged."""
    parts = []
    for unit, label in (("C", "ΔT"), ("um", "ΔD"), ("min", "Δt_eq")):
        row = worst(rows, unit)
        if row is not None:
            parts.append(f"largest |{label}| {abs(row.deviation):.1f} {UNIT_SYMBOLS[unit]} ({row.condition} {row.quantity})")
        flagged = worst(rows, unit, flagged=True)
        if flagged is not None:
            parts.append(f"flagged {flagged.condition} {flagged.quantity} {flagged.deviation:+.1f} {UNIT_SYMBOLS[unit]}")
    return ", ".join(parts)


def _prediction_table(rows: list[Prediction], title: str) -> Table:
    table = Table(title=title, title_justify="left")
    for column in ("condition", "quantity", "predicted", "measured", "deviation", "95 % interval", "flag"):
        table.add_column(column)
    for r in rows:
        unit = UNIT_SYMBOLS[r.unit] if r.unit != "C" else "°C"
        interval = "" if r.interval is None else f"±{r.interval:.1f}"
        table.add_row(r.condition, r.quantity, f"{r.predicted:.1f} {unit}", f"{r.measured:.1f}", f"{r.deviation:+.1f}",
                      interval, "flagged" if r.flag else "")
    return table


def _series_table(rows: list[TransientComparison], title: str) -> Table:
    table = Table(title=title, title_justify="left")
    for column in ("condition", "quantity", "samples", "weights", "RMS", "max |dev|", "at", "mean"):
        table.add_column(column)
    for s in rows:
        unit = UNIT_SYMBOLS[s.unit]
        table.add_row(s.condition, s.quantity, str(len(s.times)), "own σ" if s.uncertainty is not None else "description's σ",
                      f"{s.rms:.2f} {unit}", f"{s.max_abs:.2f} {unit}", f"{s.time_of_max / 60:.0f} min",
                      f"{s.mean:+.2f}")
    return table


def print_calibration(result: CalibrationResult, out_dir: Path, cross=None, console: Console | None = None) -> None:
    console = console or Console(width=None if sys.stdout.isatty() else 120)
    table = Table(title=f"fitted on {', '.join(result.fit_conditions)} ({result.model_runs} model runs, {result.wall_time_s:.0f} s)",
                  title_justify="left")
    for column in ("parameter", "fitted", "std. error", "original", "bounds", "note"):
        table.add_column(column)
    for p, x, se, why, bound in zip(result.parameters, result.fitted, result.standard_errors, result.identifiable,
                                    result.at_bound):
        original = p.originals[0] if p.kind == "value" else 1.0
        note = "; ".join(n for n in (why, f"at the {bound} bound: the data push past the declared range" if bound else "") if n)
        table.add_row(p.name, f"{x:.4g}", f"{se:.2g}", f"{original:.4g}", f"[{p.lower:g}, {p.upper:g}]", note)
    console.print(table)
    for condition, motor, ratio in result.overloads():
        console.print(f"implausible: at the fitted values {motor} needs {100 * ratio:.0f} % of its continuous torque "
                      f"at condition {condition}; the motor could not run there")
    for title, rows in (("fit residuals", result.residuals), ("held-out predictions", result.held_out)):
        if rows:
            console.print(f"{title}: " + _largest(rows))
    if result.series_fit:
        console.print(f"fitted as series (every sample a residual over its own σ, else the description's): "
                      f"{', '.join(result.series_conditions)}")
        console.print(_series_table(result.series_fit, "fitted series: calibrated run − measured"))
    if result.series_held_out:
        console.print(_series_table(result.series_held_out, "held-out series: prediction − measured"))
    if result.held_out:
        console.print(_prediction_table(result.held_out, "held-out predictions (95 % prediction intervals)"))
    for row in [*result.excluded, *(r for r in result.held_out if r.flag)]:
        console.print(f"flagged by the consistency check (not fitted, not in the maxima): {row.condition} {row.quantity} "
                      f"(deviation {row.deviation:+.1f} {UNIT_SYMBOLS[row.unit]}): {row.flag}")
    if cross:
        rows = [r for _, res in cross for r in res.held_out]
        console.print("leave-one-condition-out, held-out: " + _largest(rows)
                      + f" ({sum(res.model_runs for _, res in cross)} model runs, "
                        f"{sum(res.wall_time_s for _, res in cross):.0f} s)")
    console.print(f"wrote {out_dir}")
