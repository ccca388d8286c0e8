"""`feedtherm compensate` outputs: the laws (JSON a controller evaluates), the study's summary,
a CSV of the error against K, the figures and the report section as a page.

Files (all in one directory, replaced as a set):

- ``law.json``: the law asked for (``--sensors``), with lags (:mod:`~feedtherm.analysis.compensation.evaluator`
  evaluates it); ``law_static.json``: the same sensors without lags; ``law_kalman.json``: the
  Kalman estimator on the same sensors (:class:`~feedtherm.analysis.compensation.kalman.KalmanLaw`
  reads it back; its ``stroke`` block gives E(x) from the filter's state, ``KalmanEstimator.stroke_error``);
- ``law_stroke.json``, ``law_stroke_static.json``: the laws of the positioning error E(x, t) at a
  table position x on the sensors of ``law.json`` and ``law_static.json`` (format version 2,
  :mod:`~feedtherm.analysis.compensation.stroke`; the evaluator takes x);
- ``compensation.json``: settings, the error of every law for K = 1 … 6 and of the description's
  own sensors, the best law with at most 3 sensors, the measured bench, the test machines' factors,
  the leave-one-condition-out check of the adaptation on the measured bench and, with ``--adapt``,
  the ``adaptation`` block; ``stroke``: each law asked for judged along the stroke (RMS and max over
  positions and time on the test cycles), the law of D applied at every x beside the stroke law;
- ``law_adapted.json``, ``law_adapted_static.json`` (with ``--adapt``): the two regression laws
  updated on measurements (:mod:`~feedtherm.analysis.compensation.adapt`), with the posterior
  covariance and the noise σ, from which the evaluator gives the predictive standard deviation;
- ``compensation.csv``: one row per law and K;
- ``error_vs_k.png``, ``sensor_map.png``, ``test_cycle.png`` and ``compensation.html`` (the report's section).
"""

from __future__ import annotations

import csv
from dataclasses import asdict
from pathlib import Path

from ..analysis.compensation.adapt import AdaptedLaw
from ..analysis.compensation.adaptation import ADAPTED_FILES, adaptation_block
from ..analysis.compensation.envelope import training_envelope
from ..analysis.compensation.law import adapted_law_document, law_document, stroke_law_document
from ..analysis.compensation.leave_one_out import LeaveOneOut
from ..system.measurements import MeasurementSet
from ..analysis.compensation.measured import MeasuredPrediction
from ..analysis.compensation.stroke import stroke_conditioning
from ..analysis.compensation.study import LawResult, StrokeResult, StudyResult
from ..system.load import LoadedSystem
from ..system.overlay import mode_of
from . import compensation_plots as plots
from .files import read_study_summary, staged_directory, write_json
from .report.compensation import compensation_section
from .report.html import page

#: The stroke laws' files, by the law of D whose sensors they read.
STROKE_FILES = {"regression_lags": "law_stroke.json", "regression": "law_stroke_static.json"}
COMPENSATION_FILES = ("law.json", "law_static.json", "law_kalman.json", *STROKE_FILES.values(), *ADAPTED_FILES.values(), "compensation.json", "compensation.csv", "error_vs_k.png",
                      "sensor_map.png", "test_cycle.png", "compensation.html")
CSV_HEADER = ["law", "k", "sensors", "test_rms_um", "test_max_um", "reduction_percent", "validation_rms_um",
              "uncompensated_rms_um"]


def _entry(result: LawResult) -> dict:
    entry = {"law": result.kind, "sensors": list(result.sensors), "validation_rms_um": result.validation.rms * 1e6,
             "test": result.test.as_dict()}
    if hasattr(result.law, "ridge"):
        entry["ridge_K"] = float(result.law.ridge) ** 0.5  # chosen on the validation cycles
    if result.conditioning:
        entry["conditioning"] = result.conditioning
    return entry


def _stroke_entry(stroke: StrokeResult, offsets: dict[str, float]) -> dict:
    """One law along the stroke, µm: its law of D at every x, and the stroke law where there is one."""
    entry = {"law": stroke.kind, "sensors": list(stroke.sensors),
             "d_only": stroke.d_only.as_dict(per_cycle=False)}
    if stroke.choice is None:
        entry["stroke_law"] = None
        if stroke.test is not None:
            entry["state_along_stroke"] = {
                "validation_rms_um": stroke.validation.rms * 1e6, "test": stroke.test.as_dict(),
                "how": "the filter's reduced state read under the nut at each position (the full model's "
                       "displacement rows projected on the reduced basis); law_kalman.json's stroke block, "
                       "KalmanEstimator.stroke_error(x)"}
        entry["note"] = "no fitted stroke law: the filter's own model gives E(x)"
        return entry
    law = stroke.choice.law
    entry["stroke_law"] = {**stroke.choice.as_dict(), "file": STROKE_FILES[stroke.kind],
                           "test": stroke.test.as_dict(),
                           "multiply_adds_per_sample": law.cost["total"],
                           "conditioning": stroke_conditioning(law, offsets=offsets),
                           "stroke_m": [law.x_min, law.x_max]}
    return entry


def summary(result: StudyResult, loaded: LoadedSystem, measured: dict[str, list[MeasuredPrediction]],
            loco: LeaveOneOut | None = None, adaptation: dict | None = None) -> dict:
    """The study as a JSON-able document (µm at output)."""
    settings = {**asdict(result.settings), "mode": mode_of(loaded)}  # the overlay the runs took
    best = result.best(3)
    test = result.curves["regression"][0].test
    return {
        "system": loaded.origin,
        "description_sha256": loaded.sha256,
        "settings": settings,
        "request": result.request if isinstance(result.request, int) else list(result.request),
        "noise": None if result.noise is None else result.noise.as_dict(),
        "candidates": {name: {"part": c.part, "where": c.where, "kind": c.kind, "position_m": list(c.position),
                              **({"not_carriable": c.problem} if c.problem else {})}
                       for name, c in result.candidates.items()},
        "sets": {"test": {"uncompensated_rms_um": test.uncompensated_rms * 1e6,
                          "uncompensated_max_um": test.uncompensated_max * 1e6,
                          "machines": [c.variant for c in result.sets["test"].cycles]}},
        "curves": {kind: [_entry(r) for r in curve] for kind, curve in result.curves.items()},
        "chosen": {kind: _entry(r) for kind, r in result.chosen.items()},
        "declared": {kind: _entry(r) for kind, r in result.declared.items()},
        "best": _entry(best),
        "measured": {kind: {"law": kind, "sensors": list(result.declared[kind].sensors),
                            "conditions": [m.as_dict() for m in rows]} for kind, rows in measured.items()},
        "leave_one_condition_out": None if loco is None else loco.as_dict(),
        "stroke": None if not result.stroke else {
            "positions": len(result.sets["test"].cycles[0].positions),
            "metric": "RMS and max of E(x_j, t) - prediction over the recorded table positions and every sample of "
                      "the test cycles; d_only: the law of D applied at every x (correction -D everywhere)",
            "laws": {kind: _stroke_entry(s, result.offsets) for kind, s in result.stroke.items()}},
        "out_of_range": _out_of_range_entry(result),
        "drift_tests": [j.as_dict() for j in result.drift_tests],
        **({} if adaptation is None else {"adaptation": adaptation}),
    }


def _out_of_range_entry(result: StudyResult) -> dict | None:
    """Each law on each out-of-range case, µm: never mixed into the test figures."""
    if not result.out_of_range:
        return None
    from ..analysis.compensation import data

    return {
        "cases": data.out_of_range_cases(),
        "cycles_per_case": min(data.OUT_OF_RANGE_CYCLES, result.settings.cycles),
        "machines": "each cycle on its own variant drawn from every declared uncertainty, as the test cycles",
        "laws": {kind: {"sensors": list((result.chosen[kind] if kind in result.chosen else result.best(3)).sensors),
                        **{what: {case: r.as_dict(per_cycle=False) for case, r in cases.items()} for what, cases in entry.items()}}
                 for kind, entry in result.out_of_range.items()},
    }


def write_compensation(result: StudyResult, loaded: LoadedSystem, out_dir: Path, *,
                       measured: dict[str, list[MeasuredPrediction]] | None = None,
                       adapted: dict[str, AdaptedLaw] | None = None, adapt_data: MeasurementSet | None = None,
                       loco: LeaveOneOut | None = None) -> list[Path]:
    """Write the study's files (see the module's notes) into ``out_dir``; return their paths.

    ``measured``: law kind -> its predictions of the measured bench (the law on the description's
    own sensors, :mod:`~feedtherm.analysis.compensation.measured`); ``adapted``: law kind -> the law
    updated on ``adapt_data`` (:func:`~feedtherm.analysis.compensation.adaptation.adapt_study`);
    ``loco``: the leave-one-condition-out check on the measured bench.
    """
    adaptation = None if not adapted else adaptation_block(adapted, adapt_data, loaded)
    document = summary(result, loaded, measured or {}, loco, adaptation)
    provenance = {"system": loaded.origin, "description_sha256": loaded.sha256,
                  "settings": document["settings"], "noise": document["noise"],
                  "fitted_on": "nominal model, training cycles read through noisy sensors"}
    best = result.best(3)
    figures = {"error_vs_k.png": plots.error_against_k(result),
               "sensor_map.png": plots.sensor_map(loaded.system, result, best.kind),
               "test_cycle.png": plots.compensated_cycle(result, [result.chosen["regression_lags"],
                                                                   result.chosen["kalman"]])}
    reference = float(loaded.system.temperatures.reference)
    train = result.sets["train"]

    def envelope(sensors) -> dict:  # the training cycles' readings of the law's inputs, as read (noisy)
        columns = [train.names.index(s) for s in sensors]
        return training_envelope(((c.times, c.sensors[:, columns]) for c in train.cycles), sensors)

    with staged_directory(out_dir, replaces=COMPENSATION_FILES) as stage:
        for name, kind in (("law.json", "regression_lags"), ("law_static.json", "regression")):
            law = result.chosen[kind].law
            write_json(stage / name, law_document(law, result.candidates, {**provenance, "test": result.chosen[kind].test.as_dict()},
                                                  reference, envelope(law.sensors), result.offsets))
        for kind, stroke in result.stroke.items():
            if stroke.choice is not None:
                write_json(stage / STROKE_FILES[kind], stroke_law_document(
                    stroke.choice.law, result.candidates, {**provenance, "test": stroke.test.as_dict()},
                    stroke.choice.as_dict(), stroke_conditioning(stroke.choice.law, offsets=result.offsets), reference,
                    envelope(stroke.choice.law.sensors)))
        kalman = result.chosen["kalman"].law.document({**provenance, "test": result.chosen["kalman"].test.as_dict()})
        kalman["conditioning"] = result.chosen["kalman"].conditioning
        write_json(stage / "law_kalman.json", kalman)
        for kind, law in (adapted or {}).items():
            write_json(stage / ADAPTED_FILES[kind], adapted_law_document(law, result.candidates, {
                **provenance, "fitted_on": "nominal model, training cycles; updated on measurements",
                "measurements": adapt_data.source, "adaptation": adaptation["laws"][kind]}, reference,
                envelope(law.law.sensors), result.offsets))
        write_json(stage / "compensation.json", document)
        with open(stage / "compensation.csv", "w", newline="") as handle:
            writer = csv.writer(handle, lineterminator="\n")
            writer.writerow(CSV_HEADER)
            for kind, curve in result.curves.items():
                for r in curve:
                    writer.writerow([kind, r.k, " ".join(r.sensors), f"{r.test.rms * 1e6:.4f}", f"{r.test.max * 1e6:.4f}",
                                     f"{100 * r.test.reduction:.2f}", f"{r.validation.rms * 1e6:.4f}",
                                     f"{r.test.uncompensated_rms * 1e6:.4f}"])
        for name, png in figures.items():
            (stage / name).write_bytes(png)
        html = page(f"feedtherm: compensation, {loaded.system.meta.name}", compensation_section(document, figures))
        (stage / "compensation.html").write_text(html, encoding="utf-8")
        names = sorted(p.name for p in stage.iterdir())
    return [Path(out_dir) / name for name in names]


def summary_line(out_dir: Path, result: StudyResult, wall_time_s: float) -> str:
    """One line: the law asked for, its held-out error, where the files are."""
    chosen = result.chosen["regression_lags"]
    reduction = 100 * chosen.test.reduction
    change = f"{reduction:.1f} % less than" if reduction >= 0 else f"{-reduction:.0f} % more than"
    stroke = result.stroke.get("regression_lags")
    along = "" if stroke is None or stroke.test is None else (
        f"; along the stroke E(x) RMS {stroke.test.rms * 1e6:.2f} µm, max {stroke.test.max * 1e6:.2f} µm "
        f"(-D everywhere: {stroke.d_only.rms * 1e6:.2f}, {stroke.d_only.max * 1e6:.2f} µm)")
    outside = result.out_of_range.get("regression_lags", {}).get("d", {})
    worst = max(outside, key=lambda case: outside[case].rms, default=None)
    beyond = "" if worst is None else (f"; out of range, worst {worst}: RMS {outside[worst].rms * 1e6:.2f} µm, "
                                       f"max {outside[worst].max * 1e6:.2f} µm")
    return (f"{out_dir}: law on {', '.join(chosen.sensors)}: held-out RMS {chosen.test.rms * 1e6:.2f} µm, "
            f"max {chosen.test.max * 1e6:.2f} µm ({change} uncompensated){along}{beyond}{_drift(result)}; "
            f"written in {wall_time_s:.1f} s")


def _drift(result: StudyResult) -> str:
    """The law asked for on the description's drift tests: its largest residual drift over the targets."""
    parts = [f"{j.test} {j.worst('regression_lags') * 1e6:.1f} µm (uncompensated {j.worst() * 1e6:.1f})"
             for j in result.drift_tests if "regression_lags" in j.residual]
    return f"; on the drift tests, largest at a target: {', '.join(parts)}" if parts else ""


FIGURES = ("error_vs_k.png", "sensor_map.png", "test_cycle.png")


def read_compensation_summary(folder: Path) -> dict:
    """``{"summary": compensation.json, "figures": {name: PNG bytes}}`` of a study's folder;
    one-line errors naming what is wrong (``feedtherm validate --compensation DIR``)."""
    document = read_study_summary(folder, "compensation.json", "--compensation", "compensate",
                                  ("settings", "curves", "best", "sets"))
    figures = {name: (Path(folder) / name).read_bytes() for name in FIGURES if (Path(folder) / name).is_file()}
    return {"summary": document, "figures": figures}
