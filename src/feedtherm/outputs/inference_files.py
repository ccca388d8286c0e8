"""`feedtherm infer` outputs: inference.csv, inference.json and a console table per condition.

A condition inferred from measured series (a transient inference) is summarised per series:
its samples, where each sample's standard uncertainty came from, and the fit's RMS residual,
rather than sample by sample.
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
from rich.console import Console
from rich.table import Table

from ..analysis.inverse import RESOLVED, TRANSIENT_STEP_S, Inference
from ..constants import ELONGATION_PROBE, KELVIN_OFFSET
from .files import staged_directory, write_json

INFERENCE_HEADER = ["condition", "group", "sources", "loss_model_W", "inferred_W", "low_95_W", "high_95_W",
                    "resolution", "at_zero_bound"]


def write_inference(results: list[Inference], out_dir: Path, context: dict) -> list[Path]:
    """inference.csv (one row per condition and group) and inference.json (fit, correlations, settings)."""
    with staged_directory(out_dir) as stage:
        with open(stage / "inference.csv", "w", newline="") as handle:
            writer = csv.writer(handle, lineterminator="\n")
            writer.writerow(INFERENCE_HEADER)
            for r in results:
                for e in r.estimates:
                    writer.writerow([r.condition, e.group, " ".join(e.sources), f"{e.loss_model:.4f}",
                                     f"{e.inferred:.4f}", f"{e.low:.4f}", f"{e.high:.4f}", f"{e.resolution:.3f}",
                                     str(e.at_bound).lower()])
        write_json(stage / "inference.json", {**context, "conditions": [_summary(r) for r in results]})
        names = sorted(p.name for p in stage.iterdir())
    return [Path(out_dir) / name for name in names]


def _display(name: str, value: float) -> float:
    return value * 1e6 if name == ELONGATION_PROBE else value - KELVIN_OFFSET


#: Where an observation's standard uncertainty came from, as inference.json says it.
SIGMA_FROM = {True: "declared uncertainty of the measurement file", False: "--sigma-temperature / --sigma-elongation"}


def _series(r: Inference) -> dict:
    """Per observed series: its samples, the source of their uncertainties and the fit's residuals."""
    out = {}
    names = np.array(r.observations)
    for name in dict.fromkeys(r.observations):
        at = names == name
        scale = 1e6 if name == ELONGATION_PROBE else 1.0  # K stays K; m → µm
        residual = (r.fitted[at] - r.measured[at]) * scale
        declared = bool(r.declared[at].all()) if r.declared is not None else False
        out[name] = {"unit": "um" if name == ELONGATION_PROBE else "C", "samples": int(at.sum()),
                     "start_s": float(r.times[at][0]), "end_s": float(r.times[at][-1]),
                     "sigma_from": SIGMA_FROM[declared],
                     "sigma_range": [float(np.min(r.sigma[at])) * scale, float(np.max(r.sigma[at])) * scale],
                     "rms_residual": float(np.sqrt(np.mean(residual**2))), "max_abs_residual": float(np.max(np.abs(residual))),
                     "final_measured": _display(name, r.measured[at][-1]), "final_fitted": _display(name, r.fitted[at][-1]),
                     "final_loss_models": _display(name, r.loss_model_prediction[at][-1])}
    return out


def _summary(r: Inference) -> dict:
    if r.transient:
        observations = {"transient": True, "step_s": TRANSIENT_STEP_S, "series": _series(r)}
    else:
        observations = {"observations": {n: {"unit": "um" if n == ELONGATION_PROBE else "C", "measured": _display(n, m),
                                             "fitted": _display(n, f), "loss_models": _display(n, p)}
                                         for n, m, f, p in zip(r.observations, r.measured, r.fitted,
                                                               r.loss_model_prediction)}}
    return {
        "condition": r.condition,
        "groups": {e.group: {"sources": list(e.sources), "loss_model_W": e.loss_model, "inferred_W": e.inferred,
                             "interval_95_W": [e.low, e.high], "resolution": e.resolution, "at_zero_bound": e.at_bound}
                   for e in r.estimates},
        **observations,
        "chi2": r.chi2,
        "degrees_of_freedom": len(r.observations),
        "not_told_apart": [{"groups": [a, b], "correlation": rho} for a, b, rho in r.not_told_apart],
        "correlation": {"groups": r.groups, "matrix": r.correlation},
    }


def print_inference(results: list[Inference], out_dir: Path | None) -> None:
    console = Console(width=120)
    for r in results:
        table = Table(title=f"condition {r.condition}: heat per group [W]", title_justify="left")
        for column in ("group", "loss models", "inferred", "95 % interval", "from data"):
            table.add_column(column, justify="left" if column == "group" else "right")
        for e in r.estimates:
            note = " (at 0)" if e.at_bound else ""
            table.add_row(e.group, f"{e.loss_model:.2f}", f"{e.inferred:.2f}{note}", f"{e.low:.2f} – {e.high:.2f}",
                          f"{100 * e.resolution:.0f} %")
        console.print(table)
        if r.transient:
            series = _series(r)
            fit = ", ".join(f"{n} {s['samples']} samples, RMS {s['rms_residual']:.2f} {'µm' if n == ELONGATION_PROBE else 'K'}"
                            for n, s in series.items())
            origins = {s["sigma_from"] for s in series.values()}
            console.print(f"  fitted to the whole transient: {fit}; χ² {r.chi2:.1f} over {len(r.observations)} samples, "
                          f"weighted by the {' and '.join(sorted(origins))}")
        else:
            fit = ", ".join(f"{n} {_display(n, m):.1f}/{_display(n, f):.1f}" for n, m, f in
                            zip(r.observations, r.measured, r.fitted))
            console.print(f"  measured/fitted (°C, µm): {fit}; χ² {r.chi2:.1f} over {len(r.observations)} measurements")
        if r.not_told_apart:
            pairs = "; ".join(f"{a} and {b} (correlation {rho:+.2f})" for a, b, rho in r.not_told_apart)
            console.print(f"  the sensors cannot tell apart: {pairs}: only their sum or difference is measured")
        weak = [e.group for e in r.estimates if e.resolution < RESOLVED]
        if weak:
            console.print(f"  mostly from the prior (the loss models), not the measurements: {', '.join(weak)}")
    if out_dir is not None:
        console.print(f"wrote {out_dir}/inference.csv, inference.json")
