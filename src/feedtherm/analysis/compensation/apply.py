"""An exported law's correction over logged readings: ``feedtherm correct``.

A law file (``law*.json``, :mod:`.evaluator`) is run over a measurement file of the machine, in
either format the measurement readers accept (docs/measurements.md), as a controller would run it
sample by sample:

- every condition of the file is one log, evaluated on its own (the law's lags restart);
- the law's inputs are read on the union of their sample times, each interpolated linearly and
  held at its first and last value outside its own samples (a logger that reads its channels in
  turn); final values are one reading, with the lags settled at it;
- a law of D gives D [m] at each time (and its predictive standard deviation for an adapted law);
  a stroke law gives E(x) [m] at each table position asked for;
- where the log holds D, a law of D is compared with it: the residual measured − predicted;
- where the law carries its training envelope (:mod:`.envelope`), every sample whose reading or
  rate lies outside it is flagged with the input and by how much (``outside_envelope``).

Every problem with the law, the file or a position is one :class:`~feedtherm.errors.FeedthermError`
line naming the file or ``--x`` and the reason, raised before anything is written.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...constants import KELVIN_OFFSET
from ...errors import FeedthermError
from ...system.measurements import ELONGATION_QUANTITY, read_measurements
from .envelope import envelope_flags
from .evaluator import CompensationLaw
from .law_files import check_law, one_line, parse_law_file
from .pairs import union_times, values_at


@dataclass(frozen=True)
class Correction:
    """One log's prediction: ``times`` [s]; ``predicted`` ``(n, len(x))`` [m] (a law of D: one
    column, ``x`` empty); ``sd`` [m] an adapted law's predictive standard deviation, else None;
    ``measured`` D [m] at ``times`` where the log holds D at that time (NaN elsewhere), else None."""

    condition: str
    times: np.ndarray
    x: tuple[float, ...]
    predicted: np.ndarray
    sd: np.ndarray | None = None
    measured: np.ndarray | None = None
    flags: list[str] | None = None  # per sample, why it lies outside the law's training envelope ("" inside)
    readings: dict[str, np.ndarray] | None = None  # the law's inputs [K] at ``times``, as the law was given them

    @property
    def flagged(self) -> int:
        """Samples outside the law's training envelope."""
        return sum(1 for f in self.flags or () if f)


def read_law(path: str | Path) -> CompensationLaw:
    """The law of ``path``, checked at the boundary (:mod:`.law_files`: one line naming the file, the
    key and the reason); its ``envelope`` (or None) and ``warnings`` (suspect but possible) beside it."""
    document = parse_law_file(path)
    if isinstance(document, dict) and document.get("kind") == "kalman":
        raise FeedthermError(f"{one_line(str(path))}: a Kalman estimator needs the motor speeds and the ambient as "
                             "well as the readings; evaluate it with feedtherm.analysis.compensation.kalman.KalmanEstimator")
    warnings = check_law(document, str(path))
    law = CompensationLaw(document)
    law.envelope = document.get("envelope")
    law.warnings = warnings
    return law


def check_positions(law: CompensationLaw, positions: tuple[float, ...]) -> None:
    """``--x`` against the law: a stroke law needs positions inside its stroke; a law of D takes none."""
    if not law.stroke:
        if positions:
            raise FeedthermError("--x: this law predicts D, the same at every table position; leave --x out")
        return
    if not positions:
        raise FeedthermError(f"--x: a stroke law needs the table positions, between {law.x_min * 1e3:.6g} and "
                             f"{law.x_max * 1e3:.6g} mm")
    for x in positions:
        if not law.x_min - 1e-9 <= x <= law.x_max + 1e-9:
            raise FeedthermError(f"--x: {x * 1e3:.6g} mm is outside the law's stroke, "
                                 f"[{law.x_min * 1e3:.6g}, {law.x_max * 1e3:.6g}] mm")


def correct(law: CompensationLaw, readings: str, positions: tuple[float, ...] = ()) -> list[Correction]:
    """The law over every log (condition) of the measurement file ``readings`` (module notes)."""
    check_positions(law, positions)
    data = read_measurements(readings)
    out = []
    for condition in data.conditions():
        rows = {r.quantity: r for r in data.for_condition(condition)}
        missing = [name for name in law.inputs if name not in rows]
        if missing:
            raise FeedthermError(f"{data.source}: condition {condition} does not log {missing[0]}, an input of the law "
                                 f"on {', '.join(law.inputs)}")
        d_row = None if law.stroke else rows.get(ELONGATION_QUANTITY)
        logged = [*law.inputs, *([ELONGATION_QUANTITY] if d_row is not None else [])]
        times = union_times([rows[n] for n in logged])
        columns = {name: values_at(rows[name], times) + KELVIN_OFFSET for name in law.inputs}
        law.reset()
        predicted, sd = [], []
        for j, t in enumerate(times):
            values = {name: float(columns[name][j]) for name in law.inputs}
            if law.stroke:
                law.update(float(t), values, positions[0])
                predicted.append([law.at(x) for x in positions])
            elif law.posterior is not None:
                d, s = law.update_with_sd(float(t), values)
                predicted.append([d])
                sd.append(s)
            else:
                predicted.append([law.update(float(t), values)])
        measured = None if d_row is None else _at_own_samples(d_row, times) * 1e-6
        envelope = getattr(law, "envelope", None)
        flags = None if envelope is None else envelope_flags(envelope, times, columns)
        out.append(Correction(condition, times, tuple(positions), np.asarray(predicted, float),
                              np.asarray(sd, float) if sd else None, measured, flags, columns))
    return out


def _at_own_samples(row, times: np.ndarray) -> np.ndarray:
    """A measurement's values at those of ``times`` where it was sampled, NaN elsewhere."""
    out = np.full(len(times), np.nan)
    if row.series is None:
        out[:] = float(row.measured)
        return out
    at = np.searchsorted(times, row.series.times)
    out[at] = row.series.values
    return out


def rows(corrections: list[Correction]) -> tuple[list[str], list[list]]:
    """The CSV's header and rows: one row per log, time and position (µm, seconds, millimetres)."""
    stroke = any(c.x for c in corrections)
    has_sd = any(c.sd is not None for c in corrections)
    has_measured = any(c.measured is not None for c in corrections)
    header = ["condition", "time_s"] + (["x_mm", "E_um"] if stroke else ["D_um"])
    header += ["sd_um"] if has_sd else []
    header += ["measured_D_um", "residual_um"] if has_measured else []
    has_flags = any(c.flags is not None for c in corrections)
    header += ["outside_envelope"] if has_flags else []
    out = []
    for c in corrections:
        for j, t in enumerate(c.times):
            for i, x in enumerate(c.x or (None,)):
                row = [c.condition, float(t)] + ([x * 1e3] if stroke else []) + [c.predicted[j, i] * 1e6]
                if has_sd:
                    row.append(c.sd[j] * 1e6 if c.sd is not None else "")
                if has_measured:
                    m = None if c.measured is None else c.measured[j]
                    row += ["", ""] if m is None or np.isnan(m) else [m * 1e6, (m - c.predicted[j, i]) * 1e6]
                if has_flags:
                    row.append(c.flags[j] if c.flags is not None else "")
                out.append(row)
    return header, out
