"""Write the ballscrew_example bench's SYNTHETIC measurements (run once; the file is committed).

The bench is not a measured machine.  To exercise every command on a second bench, and to check
that calibration and inference find what they should, its measurements are made here:

1. the bench's description with its heats perturbed (:data:`TRUTH`), each value inside its
   declared calibration bounds and uncertainty range: the ball nut's drag torque +24 %, the front
   bearing pair's preload +30 %.  The screw's CHTC factor stays at 1: inference estimates heats
   through the description's own transfer (its CHTCs and contacts), so a perturbed CHTC would be
   read as heat (x0.8 on the screw's shows as +10 % ball-nut heat, outside its interval);
   calibration fits the factor all the same and must find it at 1;
2. every condition run with the fast model (cycle-averaged motion in the 10 s steps calibration
   takes for a series; 60 s steps lag the transient by up to 0.16 K, more than the noise) over
   its 8 h, sampled every :data:`EVERY_MIN` minutes;
3. seeded Gaussian noise of the sensors' standard uncertainties (:data:`NOISE`), which the file
   also states per sample: class-A PT100s 0.1 K, the infrared reading of the screw 0.3 K, the
   laser 0.5 µm.

Usage (from the repository root; rewrites the bench's measurements.csv)::

    python scripts/make_ballscrew_measurements.py

The recovery tests (tests/integration/test_ballscrew_recovery.py) read :data:`TRUTH` from here.
"""

from __future__ import annotations

import csv
import io
import sys
from pathlib import Path

import numpy as np

#: The perturbed values [SI]: what calibration and inference should find.
TRUTH = {"sources.ball_nut.torque": 0.36, "sources.front_bearing.axial_load": 2800.0,
         "surfaces.screw_shaft.chtc_factor": 1.0}
#: Sample interval of the written series [min].
EVERY_MIN = 10
#: Standard uncertainty of each reading: contact sensors [K], the infrared reading [K], D [µm].
NOISE = {"contact": 0.1, "infrared": 0.3, "D": 0.5}
SEED = 20261126
#: The conditions measured (the bench's drift tests are measured apart: make_ballscrew_drift_tests.py).
CONDITIONS = ("v5", "v10", "v20", "v10_warm")
BENCH = "ballscrew_example"
TARGET = Path(__file__).parents[1] / "src" / "feedtherm" / "benches" / BENCH / "measurements.csv"


def truth():
    """The bench's description with :data:`TRUTH` applied."""
    from feedtherm.system.load import load_system
    from feedtherm.system.variants import with_values

    return with_values(load_system(BENCH), TRUTH, origin_suffix="synthetic truth")


def measurements() -> str:
    """The file's text: comments naming what it is, then the long-format series."""
    from feedtherm.analysis.calibration import SERIES_OPTIONS, SERIES_STEP_S
    from feedtherm.constants import KELVIN_OFFSET
    from feedtherm.simulate import simulate

    loaded = truth()
    system = loaded.system
    rng = np.random.default_rng(SEED)
    out = io.StringIO()
    out.write("# SYNTHETIC measurements of the ballscrew_example bench, not a measured machine: written by\n"
              "# scripts/make_ballscrew_measurements.py from the bench's description with "
              + ", ".join(f"{k} = {v:g}" for k, v in TRUTH.items())
              + f", run with the fast model, plus seeded sensor noise (seed {SEED}).\n")
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(["condition", "time [min]", "quantity", "value", "unit", "uncertainty"])
    for condition in CONDITIONS:
        run = simulate(loaded, condition=condition, motion="averaged", options=SERIES_OPTIONS,
                       sample_interval=SERIES_STEP_S)
        keep = np.flatnonzero(np.isclose(np.mod(run.times, EVERY_MIN * 60.0), 0.0))
        for i in keep:
            minutes = run.times[i] / 60.0
            for name, sensor in system.sensors.items():
                sigma = NOISE["infrared" if sensor.method == "infrared" else "contact"]
                value = run.sensors[name][i] - KELVIN_OFFSET + rng.normal(0.0, sigma)
                writer.writerow([condition, f"{minutes:g}", name, f"{value:.2f}", "degC", f"{sigma:g}"])
            value = run.elongation[i] * 1e6 + rng.normal(0.0, NOISE["D"])
            writer.writerow([condition, f"{minutes:g}", "D", f"{value:.2f}", "um", f"{NOISE['D']:g}"])
    return out.getvalue()


def main() -> int:
    TARGET.write_text(measurements(), encoding="utf-8")
    print(f"wrote {TARGET}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
