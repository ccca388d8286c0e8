"""Numbers the report's sections and figures share, read from a Validation (°C, µm, W, min)."""

from __future__ import annotations

from dataclasses import dataclass

from ...analysis.validation_types import ELONGATION_QUANTITY, Comparison, Validation
from ...constants import KELVIN_OFFSET
from ...solution import Solution


@dataclass(frozen=True)
class Series:
    """Conditions run that differ in one thing only: ``varies`` is "speed" or "ambient"."""

    varies: str
    conditions: list[str]
    title: str  # what the others share, e.g. "ambient 20 °C"


def conditions(validation: Validation) -> list[str]:
    """Conditions in the order they were run, then any only compared."""
    names = list(validation.solutions)
    for row in validation.comparisons:
        if row.condition not in names:
            names.append(row.condition)
    return names


def comparisons_by_key(validation: Validation) -> dict[tuple[str, str], Comparison]:
    """``(condition, quantity) -> Comparison``."""
    return {(row.condition, row.quantity): row for row in validation.comparisons}


def speed_series(validation: Validation) -> Series | None:
    """The largest set of run conditions at one ambient with different screw speeds, slowest first."""
    return _series(validation, "speed", lambda p: round(p.ambient_c, 6), lambda p: p.screw_rpm,
                   lambda p: f"ambient {p.ambient_c:g} °C")


def ambient_series(validation: Validation) -> Series | None:
    """The largest set of run conditions at the same motor speeds with different ambients, coldest first."""
    return _series(validation, "ambient", lambda p: (round(p.screw_rpm, 6), round(p.nut_rpm, 6)),
                   lambda p: p.ambient_c, lambda p: f"screw {p.screw_rpm:.0f} rpm, nut {p.nut_rpm:.0f} rpm")


def _series(validation: Validation, varies: str, shared, varying, title) -> Series | None:
    points = {c: p for c, p in validation.operating_points.items() if c in validation.solutions}
    groups: dict = {}
    for condition, point in points.items():
        groups.setdefault(shared(point), []).append(condition)
    best = []
    for members in groups.values():
        distinct = {round(varying(points[c]), 6) for c in members}
        if len(distinct) >= 2 and len(members) > len(best):
            best = members
    if not best:
        return None
    best = sorted(best, key=lambda c: varying(points[c]))
    return Series(varies, best, title(points[best[0]]))


def reference_condition(validation: Validation) -> str | None:
    """The condition whose screw field the report shows: the bench's choice, else the first run."""
    if validation.notes.field_condition in validation.solutions:
        return validation.notes.field_condition
    return next(iter(validation.solutions), None)


def final_values(solution: Solution) -> dict[str, float]:
    """Final sensor temperatures [°C] and ``D_um`` [µm] (mean over the last full cycle)."""
    return solution.summary_values("final")


def ambient_c(solution: Solution) -> float | None:
    """The run's final ambient temperature [°C] (its ambient sensor), None without one."""
    ambient = solution.ambient_sensor
    if ambient in solution.final:
        return float(solution.final[ambient] - KELVIN_OFFSET)
    if ambient in solution.sensors:
        return float(solution.sensors[ambient][-1] - KELVIN_OFFSET)
    return None


def mean_heat_w(solution: Solution) -> float | None:
    """Heat generated over the run divided by its length [W] (energy balance's heat in)."""
    span = float(solution.times[-1] - solution.times[0]) if solution.times.size > 1 else 0.0
    return solution.energy.heat_in / span if span > 0 else None


def run_minutes(solution: Solution) -> float:
    return float(solution.times[-1] - solution.times[0]) / 60.0


def equilibrium_minutes(solution: Solution) -> float | None:
    return None if solution.equilibrium_time is None else solution.equilibrium_time / 60.0


def screw_rpm(validation: Validation, condition: str) -> float | None:
    """Screw speed [rpm] of a declared condition, None for other conditions."""
    point = validation.operating_points.get(condition)
    return None if point is None else point.screw_rpm


def nut_rpm(validation: Validation, condition: str) -> float | None:
    point = validation.operating_points.get(condition)
    return None if point is None else point.nut_rpm


def label(quantity: str) -> str:
    """``D_um`` -> ``D``; sensor names unchanged."""
    return "D" if quantity == ELONGATION_QUANTITY else quantity


def location(validation: Validation, quantity: str) -> str:
    """Where a sensor is (its description's first words, ``front bearing``), or ``screw elongation D``."""
    if quantity == ELONGATION_QUANTITY:
        return "screw elongation D"
    return validation.sensor_locations.get(quantity, "")


def reference_worst(validation: Validation, unit: str) -> float | None:
    """The reference model's largest |simulated − measured| (the measurements' ``reference_simulated``
    column, in sample: the values it was shown against), None without that column."""
    return validation.reference_worst(unit)


def deviation_bands(validation: Validation, unit: str) -> tuple[float, float, float]:
    """Upper limits of colour bands 0–2: 1 K / 3 µm, the reference model's own worst where known
    (else 2 K / 6 µm), 5 K / 15 µm."""
    low, middle, high = DEVIATION_BANDS["um" if unit == "um" else "C"]
    return low, reference_worst(validation, "um" if unit == "um" else "C") or middle, high


def deviation_band(deviation: float, limits: tuple[float, float, float]) -> int:
    """0–3: the first band of ``limits`` (:func:`deviation_bands`) that holds |deviation|, 3 beyond."""
    size = abs(deviation)
    return next((band for band, limit in enumerate(limits) if size <= limit), len(limits))


DEVIATION_BANDS = {"C": (1.0, 2.0, 5.0), "um": (3.0, 6.0, 15.0)}


# --------------------------------------------------------------------------- which model a value is of

UNCALIBRATED = "uncalibrated model"
CALIBRATED = "calibrated model"
BOTH = "uncalibrated and calibrated model"


def runs_model(validation: Validation) -> str:
    """The model the report's runs are of: calibrated where the description carries values that
    `feedtherm calibrate` fitted (a calibrated.toml validated), else uncalibrated."""
    return CALIBRATED if validation.calibrated else UNCALIBRATED


@dataclass(frozen=True)
class CalibratedValue:
    """The calibrated model's final value of one measured quantity (calibration.json), °C or µm."""

    simulated: float
    held_out: bool  # a condition the calibration was not fitted to


def calibrated_values(validation: Validation) -> dict[tuple[str, str], CalibratedValue]:
    """``(condition, quantity) ->`` the value of the calibration given with ``--calibration``.

    Its fit conditions' values (flagged ones too) and its held-out predictions; empty without a
    calibration, and where the runs are the calibrated model already (the two would repeat).
    """
    calibration = validation.calibration
    if not calibration or validation.calibrated:
        return {}
    out = {}
    for key, value, held in (("residuals", "simulated", False), ("excluded", "simulated", False),
                             ("held_out", "predicted", True)):
        for row in calibration.get(key) or []:
            if row.get("unit") in ("C", "um") and row.get(value) is not None:
                out[(row["condition"], row["quantity"])] = CalibratedValue(float(row[value]), held)
    return out


def fit_conditions(validation: Validation) -> list[str]:
    return list((validation.calibration or {}).get("fit_conditions", []))
