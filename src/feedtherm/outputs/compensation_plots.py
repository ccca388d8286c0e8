"""Figures of a compensation study (PNG bytes): error against K, the chosen points on the machine,
a held-out cycle compensated."""

from __future__ import annotations

import io
import math
import textwrap

import numpy as np

from ..analysis.compensation.study import LawResult, StudyResult
from ..system.schema import FeedSystem

_DPI = 110
#: Characters per line of a title at 8 pt across a 10-inch figure.
TITLE_CHARACTERS = 130
LAW_LABELS = {"regression": "regression", "regression_lags": "regression with lags", "kalman": "Kalman filter"}
_COLOURS = {"regression": "tab:blue", "regression_lags": "tab:orange", "kalman": "tab:green"}


def _figure(figsize):
    from matplotlib.figure import Figure

    return Figure(figsize=figsize, layout="constrained")


def _png(figure) -> bytes:
    buffer = io.BytesIO()
    figure.savefig(buffer, dpi=_DPI, format="png")
    return buffer.getvalue()


def error_against_k(result: StudyResult) -> bytes:
    """RMS and maximum residual [µm] on the test cycles against K, per law; the declared sensors as lines."""
    from matplotlib.ticker import NullFormatter, ScalarFormatter

    figure = _figure((8.5, 3.6))
    axes = figure.subplots(1, 2)
    for kind, curve in result.curves.items():
        ks = [r.k for r in curve]
        axes[0].plot(ks, [r.test.rms * 1e6 for r in curve], "o-", color=_COLOURS.get(kind), label=LAW_LABELS.get(kind, kind))
        axes[1].plot(ks, [r.test.max * 1e6 for r in curve], "o-", color=_COLOURS.get(kind), label=LAW_LABELS.get(kind, kind))
        own = result.declared.get(kind)
        if own is not None:
            label = f"{LAW_LABELS.get(kind, kind)}, {','.join(own.sensors)}"
            axes[0].axhline(own.test.rms * 1e6, color=_COLOURS.get(kind), ls=":", lw=1, label=label)
            axes[1].axhline(own.test.max * 1e6, color=_COLOURS.get(kind), ls=":", lw=1, label=label)
    first = next(iter(result.curves.values()))
    uncompensated = first[0].test.uncompensated_rms * 1e6
    axes[0].set_title(f"RMS residual (no compensation: {uncompensated:.1f} µm)", fontsize=9)
    axes[1].set_title("maximum |residual|", fontsize=9)
    for ax in axes:
        ax.set_xlabel("K (sensors, chosen greedily)")
        ax.set_ylabel("µm")
        ax.set_yscale("log")
        ax.yaxis.set_major_formatter(ScalarFormatter())
        ax.yaxis.set_minor_formatter(NullFormatter())
        ax.grid(alpha=0.3, which="both")
    axes[1].axhline(3.0, color="grey", lw=0.8, ls="--")
    axes[0].legend(fontsize=7)
    figure.suptitle(f"held-out cycles on {len(result.sets['test'].cycles)} machine variants", fontsize=10)
    return _png(figure)


def sensor_map(system: FeedSystem, result: StudyResult, kind: str) -> bytes:
    """The machine from above (x-y) and from the side (x-z): parts, candidates, the chosen points
    numbered in the order of choice, and the description's own sensors."""
    from matplotlib.patches import Rectangle

    figure = _figure((10, 6.2))
    top, side = figure.subplots(2, 1, sharex=True)
    for ax, (i, j) in ((top, (0, 1)), (side, (0, 2))):
        for name, part in system.parts.items():
            style = {"fill": False, "lw": 0.8, "ls": "--" if part.moving else "-",
                     "ec": "tab:red" if part.moving else "0.3"}
            for box in part.boxes:
                ax.add_patch(Rectangle((box.origin[i], box.origin[j]), box.size[i], box.size[j], **style))
            for cyl in part.cylinders:
                r = cyl.outer_diameter / 2
                ax.add_patch(Rectangle((cyl.origin[0], cyl.origin[j] - r), cyl.length, 2 * r, **style))
        points = [c for c in result.candidates.values() if not math.isnan(c.position[0])]
        ax.plot([c.position[i] for c in points], [c.position[j] for c in points], ".", color="0.6", ms=3,
                label="candidates")
        declared = [c for c in points if c.where == "declared"]
        ax.plot([c.position[i] for c in declared], [c.position[j] for c in declared], "s", mfc="none", mec="tab:green",
                ms=8, label="the description's sensors")
        for c in declared:
            ax.annotate(c.name, (c.position[i], c.position[j]), xytext=(4, -10), textcoords="offset points",
                        fontsize=7, color="tab:green")
        chosen = result.curves[kind][-1].sensors
        for order, name in enumerate(chosen, start=1):
            c = result.candidates[name]
            if math.isnan(c.position[0]):
                continue
            ax.plot(c.position[i], c.position[j], "o", color="tab:orange", ms=9, mec="k")
            ax.annotate(str(order), (c.position[i], c.position[j]), ha="center", va="center", fontsize=7)
        ax.set_aspect("equal")
        ax.autoscale_view()
        ax.set_ylabel(f"{'yz'[j - 1]} [m]")
    side.set_xlabel("x [m] (screw axis; moving parts dashed, at mid-stroke)")
    names = ", ".join(f"{k}: {n}" for k, n in enumerate(result.curves[kind][-1].sensors, start=1))
    # Six long candidate names run past a 10-inch figure's edges on one line.
    title = textwrap.fill(f"chosen in order ({LAW_LABELS.get(kind, kind)}): {names}", width=TITLE_CHARACTERS)
    top.set_title(title, fontsize=8)
    top.legend(fontsize=7, loc="upper right")
    return _png(figure)


def compensated_cycle(result: StudyResult, laws: list[LawResult], index: int = 0) -> bytes:
    """One test cycle: D simulated on its machine variant, D estimated by each law, and the residuals."""
    record = result.sets["test"].cycles[index]
    hours = record.times / 3600
    figure = _figure((8.5, 4.8))
    top, bottom = figure.subplots(2, 1, sharex=True, height_ratios=(2, 1))
    top.plot(hours, record.elongation * 1e6, color="k", label="D on the variant (simulated)")
    stopped = (record.screw_rpm == 0) & (record.nut_rpm == 0)
    top.fill_between(hours, 0, 1, where=stopped, transform=top.get_xaxis_transform(), color="0.9", label="stopped")
    for law in laws:
        estimate = law.law.predict_record(record, result.sets["test"].names)
        rms = np.sqrt(np.mean((record.elongation - estimate) ** 2)) * 1e6
        label = f"{LAW_LABELS.get(law.kind, law.kind)} ({', '.join(law.sensors)}): RMS {rms:.2f} µm"
        top.plot(hours, estimate * 1e6, color=_COLOURS.get(law.kind), ls="--", label=label)
        bottom.plot(hours, (record.elongation - estimate) * 1e6, color=_COLOURS.get(law.kind))
    top.set_ylabel("D [µm]")
    top.legend(fontsize=7)
    bottom.axhline(0, color="0.5", lw=0.6)
    bottom.set_ylabel("residual [µm]")
    bottom.set_xlabel("time [h]")
    top.set_title(f"{record.label} (a held-out cycle on another machine)", fontsize=9)
    return _png(figure)
