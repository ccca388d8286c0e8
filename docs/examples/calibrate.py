"""Calibrate one declared parameter on one measured condition and predict another.

The description declares which values may be fitted and within which bounds
(``[calibration.parameters]``); the bench ships the paper's measurements (Tables 6 and 7).
Here the sliding nut's preload is fitted to the five temperatures and the elongation
measured at condition I (bounded least squares, each evaluation a fast-model run with the
cycle-averaged motion), and the calibrated description predicts condition II, which the fit
never saw: its error there, not the fit's, says what the calibration is worth.
``feedtherm calibrate --fit I --params screw_nut_preload`` does the same for all
measured conditions and writes the calibrated description.
"""

import math

from feedtherm.analysis.calibration import calibrate
from feedtherm.system.measurements import MeasurementSet, read_measurements
from feedtherm.system.load import load_system


def main(parameter: str = "screw_nut_preload", fit: str = "I", predict: str = "II") -> dict:
    loaded = load_system("paper")
    measured = read_measurements(loaded.system.meta.measurements, sensors=["T1", "T2", "T3", "T4", "T5"])
    # Only the two conditions of this example: calibrate() predicts every measured one it did not fit.
    data = MeasurementSet([r for r in measured.rows if r.condition in (fit, predict)], measured.source, {})
    result = calibrate(loaded, data, [fit], [parameter])
    held = [p for p in result.held_out if p.condition == predict]
    temperatures = [p.deviation for p in held if p.unit == "C"]
    return {
        "parameter": parameter,
        "declared": result.parameters[0].originals[0],
        "fitted": float(result.fitted[0]),
        "standard_error": float(result.standard_errors[0]),
        "model_runs": result.model_runs,
        "fit_deviation": {p.quantity: p.deviation for p in result.residuals},
        "held_out_deviation": {p.quantity: p.deviation for p in held},  # predicted − measured
        "held_out_measured": {p.quantity: p.measured for p in held},
        "held_out_rms_K": math.sqrt(sum(d * d for d in temperatures) / len(temperatures)),
    }


if __name__ == "__main__":
    r = main()
    print(f"{r['parameter']}: declared {r['declared']:g}, fitted {r['fitted']:.0f} ± {r['standard_error']:.0f} "
          f"(on condition I, {r['model_runs']} model runs)")
    print("fitted condition I, predicted − measured: "
          + ", ".join(f"{q} {d:+.2f}" for q, d in r["fit_deviation"].items()))
    print("held-out condition II, predicted − measured: "
          + ", ".join(f"{q} {d:+.2f}" for q, d in r["held_out_deviation"].items()))
    print(f"held-out RMS temperature error: {r['held_out_rms_K']:.2f} K")
