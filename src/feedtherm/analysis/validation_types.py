"""Data produced by a validation against measurements, read by the report and the CLI."""

from __future__ import annotations

from dataclasses import dataclass, field

from ..solution import Solution
from .consistency import ConsistencyReport
from .inverse import Inference
from .measurements import ELONGATION_QUANTITY  # noqa: F401 (re-exported for the report and CLI)
from .transient_scores import TransientComparison

TEMPERATURE_QUANTITIES = ("T1", "T2", "T3", "T4", "T5")


@dataclass(frozen=True)
class Comparison:
    """One row of validation.csv (°C or µm)."""

    condition: str
    quantity: str  # T1..T5 or D_um
    unit: str  # "C" or "um"
    simulated: float
    measured: float
    paper_simulated: float | None

    @property
    def deviation(self) -> float:
        return self.simulated - self.measured


@dataclass(frozen=True)
class Sensitivity:
    """Effect of one declared assumption, perturbed alone, on the steady state of a condition."""

    parameter: str  # dotted path in the description
    assumption: str  # the provenance entry's source
    factor: float  # the value was multiplied by this
    effect: dict[str, float]  # quantity -> change (K or µm)
    name: str = ""  # a readable name where the path has an index ("joint nut–screw: tcr")

    @property
    def label(self) -> str:
        return self.name or self.parameter

    @property
    def max_temperature_effect(self) -> float:
        return max(abs(self.effect[q]) for q in TEMPERATURE_QUANTITIES)


@dataclass(frozen=True)
class Validation:
    """Everything `feedtherm validate` computed."""

    system_name: str
    mode: str
    model: str
    comparisons: list[Comparison]
    solutions: dict[str, Solution]  # condition -> run
    single_drive: dict[str, Solution]  # condition -> run with the nut motor off, same table speed
    heat_budget: dict[str, dict[str, float]]  # condition -> source -> W
    measured_equilibrium_min: dict[str, float]  # condition -> the paper's stated equilibrium time
    sensitivities: list[Sensitivity]
    sensitivity_condition: str
    inconsistencies: list[str]  # findings of `feedtherm check` and of the data
    assumptions: list[dict]  # provenance entries with origin "assumption"
    calibrated: list[dict] = field(default_factory=list)  # values fitted by `feedtherm calibrate`
    provenance: dict = field(default_factory=dict)
    measurement_source: str = ""
    wall_time_s: float = 0.0
    consistency: ConsistencyReport | None = None  # the measurements' own consistency check
    inferred: list[Inference] = field(default_factory=list)  # heats inferred from each condition's measurements
    calibration: dict | None = None  # calibration.json of a `feedtherm calibrate --cross-validate` run
    # a `feedtherm compensate` folder: {"summary": compensation.json, "figures": {png name: bytes}}
    compensation: dict | None = None
    # a `feedtherm uncertainty` folder: {"summary": uncertainty.json, "figures": {png name: bytes}}
    uncertainty: dict | None = None
    # every measured time series against its run (empty when the measurements are finals only)
    transients: list[TransientComparison] = field(default_factory=list)

    def largest(self, kind: str) -> Comparison:
        """The comparison with the largest |deviation| among temperatures or elongations."""
        rows = [c for c in self.comparisons if (c.unit == "C") == (kind == "temperature")]
        return max(rows, key=lambda c: abs(c.deviation))

    def largest_per_condition(self) -> dict[str, dict[str, Comparison]]:
        out: dict[str, dict[str, Comparison]] = {}
        for c in self.comparisons:
            kind = "temperature" if c.unit == "C" else "elongation"
            slot = out.setdefault(c.condition, {})
            if kind not in slot or abs(c.deviation) > abs(slot[kind].deviation):
                slot[kind] = c
        return out
