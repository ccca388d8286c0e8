"""Write ballscrew_v10_series.csv: a SYNTHETIC measured time series, not a measurement.

The bundled ``ballscrew_example`` bench has its own (8 h) series; this one is shorter. It runs its condition
``v10`` for 20 min with the fast model, takes T1, T3, T4 and the elongation D every 2 min, adds
seeded Gaussian noise (0.1 K, 0.5 µm) and writes them in the long format of
``feedtherm.system.measurement_series`` with standard uncertainties of 0.2 K and 1 µm, in
mixed units (°C, K, mm) so that the reader's conversions are exercised. The tests validate
against it a description whose ``v10`` lasts 20 min (tests/integration/test_cli_validate_series.py).

    PYTHONPATH=src python tests/data/make_ballscrew_series.py
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from feedtherm.simulate import simulate
from feedtherm.system.load import load_system

CONDITION = "v10"
DURATION_S = 1200.0
EVERY_S = 120.0
SENSORS = {"T1": "degC", "T3": "degC", "T4": "K"}
NOISE_K, NOISE_UM = 0.1, 0.5
UNCERTAINTY_K, UNCERTAINTY_UM = 0.2, 1.0
SEED = 33
OUT = Path(__file__).with_name("ballscrew_v10_series.csv")


def main() -> None:
    run = simulate(load_system("ballscrew_example"), condition=CONDITION, duration=DURATION_S)
    rng = np.random.default_rng(SEED)
    times = np.arange(0.0, DURATION_S + 1.0, EVERY_S)
    celsius = run.sensors_celsius()
    lines = ["# SYNTHETIC: the fast model's ballscrew_example v10 run plus noise (tests/data/make_ballscrew_series.py)",
             "condition,time [min],quantity,value,unit,uncertainty"]
    for t in times:  # time-major, as a logger writes
        for name, unit in SENSORS.items():
            value = np.interp(t, run.times, celsius[name]) + rng.normal(0.0, NOISE_K)
            value += 273.15 if unit == "K" else 0.0
            lines.append(f"{CONDITION},{t / 60:g},{name},{value:.3f},{unit},{UNCERTAINTY_K:g}")
        d_um = np.interp(t, run.times, run.elongation_um) + rng.normal(0.0, NOISE_UM)
        lines.append(f"{CONDITION},{t / 60:g},D,{d_um / 1000:.5f},mm,{UNCERTAINTY_UM / 1000:g}")
    OUT.write_text("\n".join(lines) + "\n", encoding="utf-8")
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
