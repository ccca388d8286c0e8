"""Data produced by a validation against measurements, read by the report and the CLI."""

from __future__ import annotations

from dataclasses import dataclass, field

from ..benches import ReportNotes
from ..solution import Solution
from .consistency import ConsistencyReport
from .inverse import Inference
from ..system.measurements import ELONGATION_QUANTITY  # noqa: F401 (re-exported for the report and CLI)
from .drift_tests import DriftTest
from .transient_scores import TransientComparison


@dataclass(frozen=True)
class OperatingPointRow:
    """A declared condition as the report states it: motor speeds [rpm] and ambient [°C]."""

    screw_rpm: float
    nut_rpm: float
    ambient_c: float


@dataclass(frozen=True)
class Comparison:
    """One row of validation.csv (°C or µm)."""

    condition: str
    quantity: str  # a sensor or D_um
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
        return max((abs(v) for q, v in self.effect.items() if q != ELONGATION_QUANTITY), default=0.0)


@dataclass(frozen=True)
class Validation:
    """Everything `feedtherm validate` computed."""

    system_name: str
    model: str
    comparisons: list[Comparison]
    solutions: dict[str, Solution]  # condition -> run
    single_drive: dict[str, Solution]  # condition -> run with the nut motor off, same table speed
    heat_budget: dict[str, dict[str, float]]  # condition -> source -> W
    measured_equilibrium_min: dict[str, float]  # condition -> the stated equilibrium time
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
    drift_tests: list[DriftTest] = field(default_factory=list)  # each test's ISO 230-3 figures, measured and simulated
    #: a test of a measured condition from another start or room, with no measurements of its own:
    #: test -> (its condition, its run), compared with the condition's measurements
    start_variants: dict[str, tuple[str, Solution]] = field(default_factory=dict)
    # the bench's own content: its conditions, where its sensors are, what the report says of it
    operating_points: dict[str, OperatingPointRow] = field(default_factory=dict)
    sensor_locations: dict[str, str] = field(default_factory=dict)  # sensor -> where it is
    notes: ReportNotes = ReportNotes()

    @property
    def temperature_quantities(self) -> list[str]:
        """The measured temperatures compared, in the order of the comparisons (the ambient's left out)."""
        ambients = {s.ambient_sensor for s in self.solutions.values()}
        return list(dict.fromkeys(c.quantity for c in self.comparisons if c.unit == "C" and c.quantity not in ambients))

    def reference_worst(self, unit: str) -> float | None:
        """The reference model's largest |simulated − measured| in ``unit`` ("C" or "um"; the measurements'
        ``reference_simulated`` column, in sample), None without that column."""
        values = [abs(c.paper_simulated - c.measured) for c in self.comparisons
                  if c.unit == unit and c.paper_simulated is not None]
        return round(max(values), 6) if values else None

    @property
    def quantities(self) -> list[str]:
        """:attr:`temperature_quantities` and the elongation."""
        return [*self.temperature_quantities, ELONGATION_QUANTITY]

    @property
    def mode(self) -> str:
        """The overlay the runs took, by name, or ``"physics"`` (from the provenance)."""
        return self.provenance.get("mode", "physics")

    def largest(self, kind: str) -> Comparison | None:
        """The comparison with the largest |deviation| among temperatures or elongations (None: none measured)."""
        rows = [c for c in self.comparisons if (c.unit == "C") == (kind == "temperature")]
        return max(rows, key=lambda c: abs(c.deviation), default=None)

    def largest_per_condition(self) -> dict[str, dict[str, Comparison]]:
        out: dict[str, dict[str, Comparison]] = {}
        for c in self.comparisons:
            kind = "temperature" if c.unit == "C" else "elongation"
            slot = out.setdefault(c.condition, {})
            if kind not in slot or abs(c.deviation) > abs(slot[kind].deviation):
                slot[kind] = c
        return out
