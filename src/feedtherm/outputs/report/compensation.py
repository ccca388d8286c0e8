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
        f"(every heat and CHTC scaled by a factor within ±{100 * settings['spread']:.0f} %). Without compensation "
        f"the RMS error over the test cycles is {number(test['uncompensated_rms_um'], 1)} µm, the largest "
        f"{number(test['uncompensated_max_um'], 1)} µm. Residuals in µm; reduction of the RMS error.")]
    rows = []
    for kind, curve in summary["curves"].items():
        for entry in curve:
            rows.append(_row(kind, entry))
    for kind, entry in summary.get("declared", {}).items():
        rows.append(_row(kind, entry, note=" (the description's sensors)"))
    body.append(table(["law", "K", "sensors", "RMS", "max", "reduction", "validation RMS"], rows,
                      caption="held-out test cycles (machine variants)"))
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
    return section("compensation", "Thermal-error compensation", "".join(body))


def _row(kind: str, entry: dict, note: str = "") -> list:
    t = entry["test"]
    return [LAW_LABELS.get(kind, kind) + note, str(len(entry["sensors"])), ", ".join(entry["sensors"]),
            number(t["rms_um"], 2), number(t["max_um"], 2), number(t["reduction_percent"], 1),
            number(entry["validation_rms_um"], 2)]
