"""The compensation section of the HTML report: laws, error against K, chosen points, the measured bench.

It reads the summary document of a study (``compensation.json``, built by
:func:`feedtherm.outputs.compensation_files.summary`) and its figures, so a report can show a
study run earlier without running it again.
"""

from __future__ import annotations

from .html import number, paragraph, png_image, section, table

LAW_LABELS = {"regression": "regression", "regression_lags": "regression with lags", "kalman": "Kalman filter"}


def compensation_section(summary: dict, figures: dict[str, bytes]) -> str:
    """``<section id="compensation">`` from a study's summary and its PNG figures (name -> bytes)."""
    settings = summary["settings"]
    test = summary["sets"]["test"]
    body = [paragraph(
        f"Laws fitted on {settings['cycles']} random cycles of the nominal model ({settings['model']} model, "
        f"{settings['mode']} mode, seed {settings['seed']}), sensors chosen on {settings['cycles']} validation "
        f"cycles and judged on {settings['cycles']} test cycles, each on another machine of the same design "
        f"({_machines(summary)}). Without compensation "
        f"the RMS error over the test cycles is {number(test['uncompensated_rms_um'], 1)} µm, the largest "
        f"{number(test['uncompensated_max_um'], 1)} µm. Residuals in µm; reduction of the RMS error.")]
    body += _noise(summary.get("noise"))
    rows = []
    for kind, curve in summary["curves"].items():
        for entry in curve:
            rows.append(_row(kind, entry))
    for kind, entry in summary.get("declared", {}).items():
        rows.append(_row(kind, entry, note=" (the description's sensors)"))
    body.append(table(["law", "K", "sensors", "RMS", "max", "reduction", "validation RMS", "ridge √α [K]",
                       "worst declared offset [µm]"], rows,
                      caption="held-out test cycles (machine variants); the ridge chosen on the validation cycles; "
                              "the error one sensor's declared offset (its kind's) causes, the worst sensor's"))
    best = summary["best"]
    body.append(paragraph(
        f"Best law with at most 3 sensors (on the validation cycles): {LAW_LABELS.get(best['law'], best['law'])} on "
        f"{', '.join(best['sensors'])}: RMS {number(best['test']['rms_um'], 2)} µm, max "
        f"{number(best['test']['max_um'], 2)} µm, reduction {number(best['test']['reduction_percent'], 1)} %."))
    for name, alt in (("error_vs_k.png", "error against K"), ("sensor_map.png", "chosen sensor positions"),
                      ("test_cycle.png", "a held-out cycle compensated")):
        if name in figures:
            body.append(png_image(figures[name], alt, caption=alt))
    for kind, block in (summary.get("measured") or {}).items():
        rows = block["conditions"]
        if not rows:
            continue
        body.append(table(
            ["condition", "measured D", "law's D", "law − measured", "paper's model − measured"],
            [[m["condition"], number(m["measured_um"], 1), number(m["predicted_um"], 1),
              number(m["deviation_um"], 1, signed=True), number(m["paper_deviation_um"], 1, signed=True)]
             for m in rows],
            caption=f"the measured bench: D from the measured {', '.join(block['sensors'])} "
                    f"({LAW_LABELS.get(kind, kind)}, trained on simulated cycles only), µm"))
    body += _stroke(summary.get("stroke"))
    body += _out_of_range(summary.get("out_of_range"))
    body += _drift_tests(summary.get("drift_tests"))
    body += _leave_one_out(summary.get("leave_one_condition_out"))
    body += _adaptation(summary.get("adaptation"))
    return section("compensation", "Thermal-error compensation", "".join(body))


def _drift_tests(tests: list | None) -> list[str]:
    """Each law on each of the description's ISO 230-3 drift tests: the residual drift at each target [µm]."""
    if not tests:
        return []
    out = [paragraph("On the description's ISO 230-3 drift tests, run on the nominal model as declared (duty, start, "
                     "room) and read through the same noisy sensors: the drift at each target since its first "
                     "measurement, uncompensated and left by each law (the axis corrected by minus its prediction "
                     "at the target; a law of D by minus D), its largest magnitude and RMS over the stops, µm.")]
    for test in tests:
        targets = list(test["uncompensated"])
        laws = [("uncompensated", test["uncompensated"])] + [
            (LAW_LABELS.get(kind, kind), figures) for kind, figures in test["residual"].items()]
        rows = [[label, *(f"{number(figures[t]['largest_um'], 1, signed=True)} / {number(figures[t]['rms_um'], 1)}"
                          for t in targets)] for label, figures in laws]
        out.append(table(["test " + test["test"], *(f"{t} mm: largest / RMS" for t in targets)], rows,
                         caption=f"drift test {test['test']}: residual drift at each target, µm"))
    return out


#: The leave-one-condition-out predictors (:mod:`feedtherm.analysis.compensation.leave_one_out`) as shown.
LOCO_LABELS = {"model_only": "simulation-trained law", "adapted": "adapted law (Bayesian)",
               "regression": "regression on the measured conditions", "reference_model": "the measurements' reference model"}


def _leave_one_out(block: dict | None) -> list[str]:
    """The measured bench, each condition held out in turn: residuals [µm] of the four predictors."""
    if not block:
        return []
    names = [k for k in LOCO_LABELS if block.get(k) is not None]
    n = len(block["conditions"])
    rows = [[c["condition"], number(c["measured_um"], 1),
             *(number(c[f"{k}_um"], 1, signed=True) for k in names), number(c["adapted_sd_um"], 1)]
            for c in block["conditions"]]
    rows += [[label, "", *(number(block[k][key], 1) for k in names), ""]
             for label, key in (("RMS", "rms_um"), ("max", "max_um"))]
    return [table(["held-out condition", "measured D", *(LOCO_LABELS[k] + " − measured" for k in names),
                   "adapted law's predictive sd"], rows,
                  caption=f"leave one condition out on the measured bench ({n} conditions, equilibrium values): the "
                          f"static law on {', '.join(block['sensors'])} alone, updated on the other {n - 1} "
                          f"conditions, and a least-squares fit on them alone (minimum-norm where underdetermined), µm"),
            paragraph(f"{n} points only, equilibrium values only: a figure of how far the adaptation carries to an "
                      f"unseen operating point, not a statistic. The held-out residual lies within two predictive "
                      f"standard deviations at {block['within_2sd']} of {n} conditions.")]


def _adaptation(block: dict | None) -> list[str]:
    """With ``--adapt``: each adapted law's prior width and its residuals on the adaptation data."""
    if not block:
        return []
    rows = [[LAW_LABELS.get(kind, kind), ", ".join(a["sensors"]), str(a["samples"]), number(a["prior_width_um"], 2),
             number(a["noise_sigma_um"], 2), number(a["in_sample_rms_before_um"], 2),
             number(a["in_sample_rms_after_um"], 2), a["file"]] for kind, a in block["laws"].items()]
    return [table(["law", "sensors", "pairs", "prior width τ", "noise σ", "RMS before", "RMS after", "file"], rows,
                  caption=f"laws adapted to {block['file']} (residuals on the adaptation data itself, µm); "
                          f"the Kalman filter is {block['kalman']}")]


def _stroke(block: dict | None) -> list[str]:
    """The error along the stroke: each law of D applied at every x, and the stroke law (issue 34)."""
    if not block:
        return []
    rows = []
    for kind, entry in block["laws"].items():
        d, law = entry["d_only"], entry.get("stroke_law")
        state = entry.get("state_along_stroke")
        if law is None and state is not None:  # the Kalman filter's state read along the stroke
            law = {"test": state["test"], "order": "state", "multiply_adds_per_sample": "—"}
        rows.append([LAW_LABELS.get(kind, kind), ", ".join(entry["sensors"]), number(d["rms_um"], 2),
                     number(d["max_um"], 2),
                     "—" if law is None else number(law["test"]["rms_um"], 2),
                     "—" if law is None else number(law["test"]["max_um"], 2),
                     "—" if law is None else str(law["order"]),
                     "—" if law is None else str(law["multiply_adds_per_sample"])])
    first = next(iter(block["laws"].values()))["d_only"]
    return [table(["law", "sensors", "D at every x: RMS", "max", "E(x) law: RMS", "max", "order in x",
                   "multiply-adds per sample"], rows,
                  caption=f"the error along the stroke, over {block['positions']} table positions and every sample of "
                          f"the test cycles (without compensation RMS {number(first['uncompensated_rms_um'], 1)} µm, max "
                          f"{number(first['uncompensated_max_um'], 1)} µm); the E(x) law's Legendre order chosen on "
                          f"the validation cycles; the Kalman filter: its state read along the stroke (its model's rows), µm")]


def _machines(summary: dict) -> str:
    """How the held-out machines differ from the nominal one."""
    spread = f"{100 * summary['settings']['spread']:.0f} %"
    machines = summary["sets"]["test"].get("machines") or [{}]
    declared = sorted((machines[0] or {}).get("declared") or {})
    if not declared:
        return f"every heat and CHTC scaled by a factor within ±{spread}"
    return (f"every declared uncertainty drawn from its distribution ({', '.join(declared)}), and every heat and "
            f"CHTC scaled by a further factor within ±{spread}")


def _out_of_range(block: dict | None) -> list[str]:
    """Each law on each out-of-range case, beside (never inside) the test figures."""
    if not block:
        return []
    cases = list(block["cases"])
    rows = []
    for kind, entry in block["laws"].items():
        label = "best (≤ 3 sensors)" if kind == "best" else LAW_LABELS.get(kind, kind)
        for what, title in (("d", "D"), ("stroke", "E(x, t)")):
            if what not in entry:
                continue
            rows.append([label, ", ".join(entry["sensors"]), title,
                         *(f"{number(entry[what][c]['rms_um'], 2)} / {number(entry[what][c]['max_um'], 1)}"
                           f" ({number(entry[what][c]['reduction_percent'], 0)} %)" if c in entry[what] else "—"
                           for c in cases)])
    return [table(["law", "sensors", "error", *cases], rows,
                  caption="out of the training's range, each case on its own "
                          f"{block['cycles_per_case']} cycles and machine variants: "
                          + "; ".join(f"{c}: {text}" for c, text in block["cases"].items())
                          + ". RMS / max residual in µm (reduction of the RMS error); E(x, t) with the stroke law "
                            "where the law has one, else its D at every x")]


def _noise(block: dict | None) -> list[str]:
    """The sensors' noise and offsets the study's readings carried (issue 34)."""
    if not block:
        return [paragraph("The readings carry no sensor noise (a study from before issue 34).")]
    kinds = block["kinds"]
    return [paragraph("Every reading of the training, validation and test cycles carries its sensor's noise: "
                      + "; ".join(f"{kind} sensors {number(k['noise_K'], 2)} K white noise and offsets of "
                                  f"{number(k['offset_K'], 2)} K (standard deviations; {k['source']})"
                                  for kind, k in kinds.items())
                      + ". Contact sensors sit on parts that stay still, infrared ones read moving or turning parts.")]


def _row(kind: str, entry: dict, note: str = "") -> list:
    t = entry["test"]
    ridge = entry.get("ridge_K")
    worst = (entry.get("conditioning") or {}).get("max_offset_error_um")
    return [LAW_LABELS.get(kind, kind) + note, str(len(entry["sensors"])), ", ".join(entry["sensors"]),
            number(t["rms_um"], 2), number(t["max_um"], 2), number(t["reduction_percent"], 1),
            number(entry["validation_rms_um"], 2), "" if ridge is None else number(ridge, 2),
            "" if worst is None else number(worst, 2)]
