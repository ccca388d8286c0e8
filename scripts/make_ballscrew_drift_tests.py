"""Write the ballscrew_example bench's SYNTHETIC drift tests (run once; the file is committed).

The bench is not a measured machine.  Its ISO 230-3-style tests (``drift``, ``drift_fast``,
``etve``: the description's ``[tests]``) get measurements made here, so that calibrating the fast
model on them meets what it meets on a real machine: data its own model did not generate.

1. The machine: the bench's description with two declared values changed (:data:`TRUTH`), each
   inside its calibration bounds and its declared uncertainty: the ball nut's drag torque +24 %,
   the front bearing pair's preload +30 %.
2. The model: the **FE model** (coarse mesh, the moving group's contacts and heats averaged over
   each reciprocation, 10 s steps), not the fast model that calibration fits.
3. The room: a smooth drift of the air (:func:`room_air`), which the truth runs follow; the logged
   air adds the logger's noise.
4. The start: ``drift`` starts, as declared, from the end of ``warm_up`` (30 min at 5 m/min from
   the room's temperature); the machine of ``drift_fast`` had run the same warm-up and then stood
   for 10 min, and that of ``etve`` stood at the room's air: both tests declare ``start =
   "measured"``, the field read from the sensors at 0 s, which the truth does not know.
5. The readings: T1-T5 and D every 2 min, the air every minute, the positioning deviation E at
   each target 1 s before the end of its hold at every measuring stop, plus a geometric
   (pitch) error per target that the model does not have (:data:`PITCH_UM`) and seeded Gaussian
   noise of the stated standard uncertainties (:data:`NOISE`).

Usage (from the repository root; rewrites the bench's drift_tests.csv; a few minutes)::

    python scripts/make_ballscrew_drift_tests.py

The tutorial's and the recovery test's figures come from calibrating on this file
(tests/integration/test_drift_tests.py reads :data:`TRUTH` from here).
"""

from __future__ import annotations

import csv
import io
import sys
from pathlib import Path

import numpy as np

#: The changed values [SI]: what calibration should find (within the model-form error).
TRUTH = {"sources.ball_nut.torque": 0.36, "sources.front_bearing.axial_load": 2800.0}
#: Standard uncertainty of each reading: contact sensors [K], the infrared reading [K], D [µm],
#: the interferometer's E [µm], the air [K].
NOISE = {"contact": 0.1, "infrared": 0.3, "D": 0.5, "E": 1.0, "air": 0.05}
#: The axis's geometric positioning error at each target [µm], there cold and unchanged: what an
#: interferometer reads beside the thermal error, and what ISO 230-3's drift takes away.
PITCH_UM = {0.110: 2.0, 0.200: -1.5, 0.300: 0.5, 0.400: 3.0, 0.490: -2.0}
SENSOR_EVERY_S, AIR_EVERY_S = 120.0, 60.0
SEED = 20261129
BENCH = "ballscrew_example"
TARGET = Path(__file__).parents[1] / "src" / "feedtherm" / "benches" / BENCH / "drift_tests.csv"
TESTS = ("drift", "drift_fast", "etve")


def room_air(test: str, times: np.ndarray) -> np.ndarray:
    """The room's true air temperature [°C]: a slow drift and a swing, different in each test."""
    hours = times / 3600.0
    if test == "drift":
        return 20.0 + 0.25 * hours + 0.2 * np.sin(2 * np.pi * hours / 2.0)
    if test == "drift_fast":
        return 20.6 - 0.15 * hours + 0.3 * np.sin(2 * np.pi * (hours + 0.4) / 1.5)
    return 20.0 + 1.2 * np.sin(2 * np.pi * hours / 8.0) - 0.3 * np.sin(2 * np.pi * hours / 2.5)


def truth_description(loaded):
    """The machine the readings come from: :data:`TRUTH` applied, and the starts the truth knows."""
    from feedtherm.system.thermal_tests import Soak
    from feedtherm.system.variants import with_values

    machine = with_values(loaded, TRUTH, origin_suffix="synthetic truth")
    tests = dict(machine.system.tests)
    standing = machine.system.duty_cycles["etve_stops"].model_copy(update={"repeat": 1, "measuring": None,
                                                                          "duration": 600.0})
    cycles = {**machine.system.duty_cycles, "truth_standing": standing}
    tests["truth_warm_then_standing"] = tests["warm_up"].model_copy(update={"condition": None, "cycle": "truth_standing",
                                                                             "start": Soak(soaked="warm_up"),
                                                                             "duration": None})
    tests["drift_fast"] = tests["drift_fast"].model_copy(update={"start": Soak(soaked="truth_warm_then_standing")})
    tests["etve"] = tests["etve"].model_copy(update={"start": "ambient"})
    return with_values(machine, {"duty_cycles": cycles, "tests": tests}, origin_suffix="synthetic starts")


def measurements(model: str = "fem", mesh: str = "coarse") -> str:
    """The file's text: comments naming what it is, then the long-format series."""
    from feedtherm.system.load import load_system

    header = ("# SYNTHETIC measurements of the ballscrew_example bench's drift tests, not a measured machine: written by\n"
              "# scripts/make_ballscrew_drift_tests.py from the bench's description with "
              + ", ".join(f"{k} = {v:g}" for k, v in TRUTH.items())
              + f", run with the {model} model ({mesh} mesh, cycle-averaged motion),\n# the positioning "
              "deviations with a geometric error per target, plus seeded noise (seed "
              f"{SEED}); the truth's starts in the script's notes.\n")
    return header + drift_test_log(truth_description(load_system(BENCH)), TESTS, room_air, model, mesh, SEED)


def drift_test_log(loaded, tests, air, model: str, mesh: str, seed: int) -> str:
    """The long-format log of ``tests`` of ``loaded`` (the truth), without comments: every sensor and D
    every :data:`SENSOR_EVERY_S`, the air every :data:`AIR_EVERY_S` (``air(test, times)`` [°C], the
    truth's; the log adds noise), E at each target at the end of each hold plus :data:`PITCH_UM`."""
    from feedtherm.analysis.calibration import SERIES_OPTIONS, SERIES_STEP_S
    from feedtherm.analysis.transient_scores import positioning_at
    from feedtherm.constants import KELVIN_OFFSET
    from feedtherm.simulate import simulate
    from feedtherm.system.measurement_series import Series
    from feedtherm.system.measurements import MeasurementSet
    from feedtherm.system.runs import run_duration

    system = loaded.system
    rng = np.random.default_rng(seed)
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(["test", "time [s]", "quantity", "value", "unit", "uncertainty", "target [mm]"])
    for test in tests:
        end = run_duration(system, test)
        air_times = np.arange(0.0, end + 1e-9, AIR_EVERY_S)
        truth_air = MeasurementSet([], "synthetic room", {}, air={
            name: Series(air_times, air(name, air_times)) for name in tests})
        run = simulate(loaded, test=test, model=model, mesh=None if model == "fast" else mesh, motion="averaged",
                       options=SERIES_OPTIONS, sample_interval=SERIES_STEP_S, measured=truth_air)
        rows = []
        for t in air_times:
            value = air(test, np.array([t]))[0] + rng.normal(0.0, NOISE["air"])
            rows.append((t, system.room.ambient_sensor, value, "degC", NOISE["air"], ""))
        for t in np.arange(0.0, end + 1e-9, SENSOR_EVERY_S):
            for name, sensor in system.sensors.items():
                sigma = NOISE["infrared" if sensor.method == "infrared" else "contact"]
                value = np.interp(t, run.times, run.sensors[name]) - KELVIN_OFFSET + rng.normal(0.0, sigma)
                rows.append((t, name, value, "degC", sigma, ""))
            value = np.interp(t, run.times, run.elongation_um) + rng.normal(0.0, NOISE["D"])
            rows.append((t, "D", value, "um", NOISE["D"], ""))
        cycle = system.duty_cycles[system.tests[test].cycle]
        for seg in cycle.timeline():
            if seg.table_at is None:
                continue
            t = seg.start + cycle.measuring.hold - 1.0
            if t > end:
                break
            target = round(seg.table_at, 6)
            value = (np.interp(t, run.times, positioning_at(run, seg.table_at)) + PITCH_UM[target]
                     + rng.normal(0.0, NOISE["E"]))
            rows.append((t, "E", value, "um", NOISE["E"], f"{target * 1e3:g}"))
        for t, quantity, value, unit, sigma, target in sorted(rows, key=lambda r: r[0]):
            writer.writerow([test, f"{t:g}", quantity, f"{value:.2f}", unit, f"{sigma:g}", target])
        print(f"{test}: {end / 3600:.2f} h, {run.info['wall_time_s']:.1f} s", file=sys.stderr)
    return out.getvalue()


def main(argv: list[str]) -> int:
    model = argv[0] if argv else "fem"
    TARGET.write_text(measurements(model), encoding="utf-8")
    print(f"wrote {TARGET}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
