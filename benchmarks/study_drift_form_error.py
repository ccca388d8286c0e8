"""A study, not a speed figure: the fast model against the FE model on ballscrew_example's drift test.

Run:  .venv/bin/python benchmarks/study_drift_form_error.py [--test drift]

Both models run the bench's truth (scripts/make_ballscrew_drift_tests.py: the description with its
two changed values and the truth's starts) through the test as it was measured, the same room air
without the logger's noise, cycle-averaged motion in 10 s steps (the FE model on the coarse mesh):
the difference is the models' form alone, which calibrating the fast model on the FE-made
measurements meets (docs/calibration.md, *Tests measured by another model*).  Prints each sensor's
and D's RMS and final difference (fast − FE), and E's drift at each target; about 1 min.
"""

from __future__ import annotations

import argparse
import importlib.util
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]


def maker():
    spec = importlib.util.spec_from_file_location("make_ballscrew_drift_tests",
                                                  ROOT / "scripts" / "make_ballscrew_drift_tests.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--test", default="drift")
    args = parser.parse_args()
    from feedtherm.analysis.calibration import SERIES_OPTIONS
    from feedtherm.analysis.transient_scores import positioning_at
    from feedtherm.simulate import simulate
    from feedtherm.system.load import load_system
    from feedtherm.system.measurement_series import Series
    from feedtherm.system.measurements import MeasurementSet
    from feedtherm.system.runs import run_duration, visited_targets

    m = maker()
    loaded = m.truth_description(load_system(m.BENCH))
    end = run_duration(loaded.system, args.test)
    t = np.arange(0.0, end + 1e-9, 60.0)
    air = MeasurementSet([], "room", {}, air={n: Series(t, m.room_air(n, t)) for n in m.TESTS})
    runs = {model: simulate(loaded, test=args.test, model=model, mesh=None if model == "fast" else "coarse",
                            motion="averaged", options=SERIES_OPTIONS, sample_interval=10.0, measured=air)
            for model in ("fast", "fem")}
    fast, fem = runs["fast"], runs["fem"]
    print(f"test {args.test}, {end / 3600:.2f} h: fast − FE on the truth")
    for name in loaded.system.sensors:
        d = fast.sensors[name] - fem.sensors[name]
        print(f"  {name}: RMS {np.sqrt(np.mean(d ** 2)):.2f} K, final {d[-1]:+.2f} K")
    d = fast.elongation_um - fem.elongation_um
    print(f"  D: RMS {np.sqrt(np.mean(d ** 2)):.2f} µm, final {d[-1]:+.2f} µm")
    for x in sorted(visited_targets(loaded.system, args.test)):
        pf, pe = positioning_at(fast, x), positioning_at(fem, x)
        drift = (pf - pf[0]) - (pe - pe[0])
        print(f"  E's drift at {x * 1e3:.0f} mm: final {drift[-1]:+.2f} µm, largest |·| {np.max(np.abs(drift)):.2f} µm "
              f"(the FE model's own drift {pe[-1] - pe[0]:.1f} µm)")


if __name__ == "__main__":
    main()
