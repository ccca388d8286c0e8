"""Numbers the report's sections and figures share, read from a Validation (°C, µm, W, min)."""

from __future__ import annotations

from functools import lru_cache

from ...analysis.validation_types import ELONGATION_QUANTITY, TEMPERATURE_QUANTITIES, Comparison, Validation
from ...constants import AMBIENT_SENSOR, KELVIN_OFFSET
from ...solution import Solution

QUANTITIES = (*TEMPERATURE_QUANTITIES, ELONGATION_QUANTITY)
# The paper's two series (§4.3): speed at 20 °C ambient, and ambient at the speed of II.
SPEED_SERIES = ("I", "II", "III")
AMBIENT_SERIES = ("IV", "II", "V")
REFERENCE_CONDITION = "I"  # the paper's Fig. 11 shows the screw field of condition I


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


def series(validation: Validation, names: tuple[str, ...]) -> list[str]:
    """The conditions of a series that were run."""
    return [name for name in names if name in validation.solutions]


def reference_condition(validation: Validation) -> str | None:
    if REFERENCE_CONDITION in validation.solutions:
        return REFERENCE_CONDITION
    return next(iter(validation.solutions), None)


def final_values(solution: Solution) -> dict[str, float]:
    """Final sensor temperatures [°C] and ``D_um`` [µm] (mean over the last full cycle)."""
    return solution.summary_values("final")


def ambient_c(solution: Solution) -> float | None:
    """The run's final ambient temperature [°C] (sensor T6), None without one."""
    if AMBIENT_SENSOR in solution.final:
        return float(solution.final[AMBIENT_SENSOR] - KELVIN_OFFSET)
    if AMBIENT_SENSOR in solution.sensors:
        return float(solution.sensors[AMBIENT_SENSOR][-1] - KELVIN_OFFSET)
    return None


def mean_heat_w(solution: Solution) -> float | None:
    """Heat generated over the run divided by its length [W] (energy balance's heat in)."""
    span = float(solution.times[-1] - solution.times[0]) if solution.times.size > 1 else 0.0
    return solution.energy.heat_in / span if span > 0 else None


def run_minutes(solution: Solution) -> float:
    return float(solution.times[-1] - solution.times[0]) / 60.0


def equilibrium_minutes(solution: Solution) -> float | None:
    return None if solution.equilibrium_time is None else solution.equilibrium_time / 60.0


@lru_cache(maxsize=1)
def _table5() -> dict[str, dict[str, float]]:
    from ...benches import bench

    return {row["condition"]: {key: float(value) for key, value in row.items() if key != "condition"}
            for row in bench("paper").table(5)}


@lru_cache(maxsize=1)
def _locations() -> dict[str, str]:
    from ...benches import bench

    return {row["point"]: row["location"] for row in bench("paper").table(6)}


def screw_rpm(condition: str) -> float | None:
    """Screw speed [rpm] of a paper condition (Table 5), None for other conditions."""
    row = _table5().get(condition)
    return None if row is None else row["screw_speed_rpm"]


def nut_rpm(condition: str) -> float | None:
    row = _table5().get(condition)
    return None if row is None else row["nut_speed_rpm"]


def label(quantity: str) -> str:
    """``D_um`` -> ``D``; sensor names unchanged."""
    return "D" if quantity == ELONGATION_QUANTITY else quantity


def location(quantity: str) -> str:
    """Where the paper measured a point (§4.2): ``T1`` -> ``front bearing``."""
    if quantity == ELONGATION_QUANTITY:
        return "screw elongation D"
    return _locations().get(quantity, "")


def deviation_band(deviation: float, unit: str) -> int:
    """0–3: within 1 K / 3 µm, within the paper's own worst (2.1 K / 6.2 µm), within 5 K / 15 µm, beyond."""
    limits = DEVIATION_BANDS["um" if unit == "um" else "C"]
    size = abs(deviation)
    return next((band for band, limit in enumerate(limits) if size <= limit), len(limits))


DEVIATION_BANDS = {"C": (1.0, 2.1, 5.0), "um": (3.0, 6.2, 15.0)}
