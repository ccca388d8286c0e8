"""Validation: run every measured condition and compare with the measurements.

Nothing here is fitted: the description is used as it is (the paper's bench with its frozen
assumptions), and the measurements are only compared with.
"""

from __future__ import annotations

import time
from typing import Callable

from ..benches import ReportNotes, bench, bench_name_of
from ..boundary import boundary_conditions
from ..constants import KELVIN_OFFSET, RPM_PER_RAD_S
from ..models.options import ModelOptions
from ..simulate import provenance, simulate
from ..system.checks import check_system
from ..system.load import LoadedSystem
from ..system.overlay import available_overlay
from .consistency import check_description_measurements
from .inverse import Noise, infer_conditions
from ..system.measurements import MeasurementSet, declared_measurements, read_description_measurements
from .sensitivity import sensitivities
from .sweep import sensor_labels
from ..system.runs import as_test, is_idle
from .drift_tests import drift_test
from .transient_scores import compare_series, drift
from .validation_types import ELONGATION_QUANTITY, Comparison, OperatingPointRow, Validation

#: Ratio beyond which a printed value and the physics are reported as inconsistent.
INCONSISTENCY_RATIO = 2.0


def measurements_of(loaded: LoadedSystem, measured: str | None) -> MeasurementSet:
    """The measurement file given, else the description's ``meta.measurements``, else its bench's own."""
    # a file given on the command line is where the user says; one the description names is beside it.
    # A series may not outlast its run: validate simulates each test's duration.
    if measured:
        return read_description_measurements(loaded.system, measured, None)
    return declared_measurements(loaded.system, loaded.origin)


def validate(loaded: LoadedSystem, *, model: str = "fast", mesh: str | None = None, motion: str | None = None,
             measured: str | None = None, progress: Callable[[float], None] | None = None,
             calibration: dict | None = None, compensation: dict | None = None,
             uncertainty: dict | None = None) -> Validation:
    """Run every measured condition of ``loaded`` (with the overlay it carries) and compare it with
    its measurements (``motion``: the runs' table motion, see :func:`~feedtherm.simulate.simulate`).

    Also checks the measurements' own consistency, infers the heat of every source from each
    condition's measurements (the fast model's transfer matrix), and carries ``calibration``
    (a ``calibration.json`` of ``feedtherm calibrate --cross-validate``) into the headline and
    ``compensation`` (a ``feedtherm compensate`` folder as read by
    :func:`~feedtherm.outputs.compensation_files.read_compensation_summary`) into its own section, and
    ``uncertainty`` (a ``feedtherm uncertainty`` folder as read by
    :func:`~feedtherm.outputs.uncertainty_files.read_uncertainty_summary`) into another.
    Where the measurements are time series, each is scored against its run over the whole
    transient (:mod:`~feedtherm.analysis.transient_scores`).
    """
    started = time.perf_counter()
    system = loaded.system
    data = measurements_of(loaded, measured)
    conditions = data.runs()  # the tests and conditions measured
    dual = system.kinematics is not None and system.kinematics.drive == "dual"
    steps = sum(2 if dual and c in system.conditions else 1 for c in conditions) + 2
    done = 0

    def tick():
        nonlocal done
        done += 1
        if progress is not None:
            progress(done / steps)

    solutions, single, budget, comparisons, transients, drifts = {}, {}, {}, [], [], []
    # one description's runs: a reduced model built for them is trained at its own numbers (models/reduced/store.py)
    options = ModelOptions(reduced_training="description")
    for condition in conditions:
        run = simulate(loaded, condition=condition, model=model, mesh=mesh, motion=motion, options=options,
                       measured=data)
        solutions[condition] = run
        transients += compare_series(condition, run, data.for_condition(condition))
        transients += compare_series(condition, run, [drift(r) for r in data.positioning_of(condition)])
        evaluated = drift_test(condition, run, data, idle=is_idle(system, condition))
        if evaluated is not None:
            drifts.append(evaluated)
        tick()
        if dual and condition in system.conditions:
            single[condition] = simulate(loaded, condition=condition, model=model, mesh=mesh, motion=motion,
                                         single_drive=True, options=options)
            tick()
        test = as_test(system, condition)
        if test.condition is not None:
            point = boundary_conditions(system, test.condition, loaded.overlay)
            budget[condition] = {name: h.power for name, h in point.heats.items()}
        final = run.summary_values("final")
        for row in data.for_condition(condition):
            comparisons.append(Comparison(condition, row.quantity, row.unit, float(final[row.quantity]), row.measured,
                                          row.reference_simulated))
    # tests of a measured condition with no measurements of their own: the condition from another start
    # (or in another constant room), shown beside it against the same measurements
    variants = {}
    for name, test in system.tests.items():
        if name not in conditions and test.condition in solutions and not test.needs_measurements:
            variants[name] = (test.condition, simulate(loaded, test=name, model=model, mesh=mesh, motion=motion,
                                                       options=options))
    printed = available_overlay(loaded)
    # the sensitivities are steady states: of the first measured condition (a test has none), else the first declared
    reference = printed.reference_condition if printed else next(
        (c for c in conditions if c in system.conditions), next(iter(system.conditions)))
    ranking = sensitivities(loaded, reference)
    tick()
    weights = system.calibration
    consistency = check_description_measurements(system, data)
    inferred = infer_conditions(loaded, data, [c for c in conditions if c in system.conditions],
                                noise=Noise(weights.temperature_sigma if weights else 0.5,
                                            weights.elongation_sigma if weights else 2e-6))
    tick()
    return Validation(
        system_name=system.meta.name,
        model=model,
        comparisons=comparisons,
        solutions=solutions,
        single_drive=single,
        heat_budget=budget,
        measured_equilibrium_min=data.equilibrium_min,
        sensitivities=ranking,
        sensitivity_condition=reference,
        inconsistencies=inconsistencies(loaded),
        assumptions=provenance(loaded)["assumptions"],
        calibrated=calibrated_values(loaded),
        provenance=provenance(loaded),
        measurement_source=data.source,
        wall_time_s=time.perf_counter() - started,
        consistency=consistency,
        inferred=inferred,
        calibration=calibration,
        compensation=compensation,
        uncertainty=uncertainty,
        operating_points=operating_points(loaded),
        sensor_locations=sensor_locations(loaded),
        notes=report_notes(loaded),
        transients=transients,
        drift_tests=drifts,
        start_variants=variants,
    )


def operating_points(loaded: LoadedSystem) -> dict[str, OperatingPointRow]:
    """Each declared condition's motor speeds [rpm] and ambient [°C], as the report states them."""
    return {name: OperatingPointRow(c.screw_speed * RPM_PER_RAD_S, c.nut_speed * RPM_PER_RAD_S,
                                    c.ambient - KELVIN_OFFSET)
            for name, c in loaded.system.conditions.items()}


def sensor_locations(loaded: LoadedSystem) -> dict[str, str]:
    """Sensor -> where it is: its description up to the first colon (``"front bearing"``), else its part."""
    return sensor_labels(loaded)


def report_notes(loaded: LoadedSystem) -> ReportNotes:
    """What the report says of the bench ``loaded`` comes from (none for a description of its own)."""
    name = bench_name_of(loaded.origin)
    return bench(name).report_notes() if name is not None else ReportNotes()


def inconsistencies(loaded: LoadedSystem) -> list[str]:
    """`feedtherm check`'s findings, and printed values (the overlay's) the physics contradicts by over 2x."""
    system = loaded.system
    found = [str(f) for f in check_system(system)]
    printed = available_overlay(loaded)
    if printed is None:
        return found
    condition = printed.reference_condition
    bc = boundary_conditions(system, condition)
    for row in printed.heat:
        physics = bc.heats[row.source].power
        if not _within(physics, row.value):
            found.append(f"{row.ref} {row.table_label}: printed {row.value:.3g} W at condition {condition}; "
                         f"the physics gives {physics:.3g} W with the declared inputs")
    for row in printed.chtc:
        for surface in row.surfaces[:1]:
            physics = bc.surfaces[surface].convection
            if not _within(physics, row.value):
                found.append(f"{row.ref} {row.table_label}: printed {row.value:.3g} W/(m² K) at condition {condition}; "
                             f"the correlations give {physics:.3g} W/(m² K) for {surface}")
    return found


def calibrated_values(loaded: LoadedSystem) -> list[dict]:
    """Provenance entries a calibration wrote (origin 'assumption', source starting 'calibrated')."""
    return [{"paths": p.paths, "source": p.source, "reason": p.reason}
            for p in loaded.system.provenance if p.source.startswith("calibrated")]


def _within(a: float, b: float) -> bool:
    if a <= 0 or b <= 0:
        return a == b
    return 1.0 / INCONSISTENCY_RATIO <= a / b <= INCONSISTENCY_RATIO


__all__ = ["validate", "measurements_of", "inconsistencies", "ELONGATION_QUANTITY"]
