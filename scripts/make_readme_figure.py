"""The README's figure: a condition of the paper's bench that the calibration did not see.

The fast model (physics mode) is calibrated on conditions I, II and IV with the parameters
`make validate` fits, then run at condition III: its sensors and the screw elongation D over the
3 h, calibrated (solid) and as declared (dashed), beside the measured final values (dots, the
bench's measurements.csv).

    .venv/bin/python scripts/make_readme_figure.py   # writes docs/images/paper-bench.png
"""

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402

import feedtherm as ft  # noqa: E402
from feedtherm.benches import bench  # noqa: E402

OUT = Path(__file__).resolve().parents[1] / "docs" / "images" / "paper-bench.png"
FIT = ["I", "II", "IV"]
PARAMS = ["screw_nut_preload", "front_bearing_preload", "foundation", "chtc_screw"]  # the Makefile's CAL_PARAMS
HELD_OUT = "III"


def main() -> None:
    declared = ft.load("paper")
    calibrated = ft.calibrate(declared, fit=FIT, params=PARAMS).calibrated
    runs = {name: ft.simulate(system, condition=HELD_OUT, sample_interval=60.0).to_dataframe()
            for name, system in (("calibrated", calibrated), ("declared", declared))}
    measured = pd.read_csv(bench("paper").folder / "measurements.csv")
    measured = measured[measured["condition"] == HELD_OUT].set_index("quantity")["measured"]
    fig, (temps, elong) = plt.subplots(1, 2, figsize=(9.0, 3.4), constrained_layout=True)
    for name, style in (("calibrated", "-"), ("declared", "--")):
        table = runs[name]
        hours = table["time [s]"] / 3600.0
        for index, sensor in enumerate(f"T{k}" for k in range(1, 6)):
            temps.plot(hours, table[f"{sensor} [degC]"], style, color=f"C{index}",
                       label=sensor if name == "calibrated" else None)
            if name == "calibrated":
                temps.plot(hours.iloc[-1], measured[sensor], "o", color=f"C{index}")
        elong.plot(hours, table["D [um]"], style, color="k", label=f"model, {name}")
    elong.plot(hours.iloc[-1], measured["D_um"], "o", color="k", label="measured")
    temps.set(xlabel="time [h]", ylabel="temperature [°C]", title="sensors")
    temps.legend(ncol=5, fontsize=8, loc="lower right")
    elong.set(xlabel="time [h]", ylabel="D [µm]", title="screw elongation D")
    elong.legend(fontsize=8, loc="lower right")
    fig.suptitle(f"Paper bench, condition {HELD_OUT}, held out: calibrated on {', '.join(FIT)} (solid), "
                 "as declared (dashed), measured (dots)", fontsize=10)
    fig.savefig(OUT, dpi=90)
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
