"""Sweep the screw speed: every grid point becomes a constant condition and is simulated.

``parse_grid`` reads the lists as a user types them on the command line (values or
``start:stop:step`` ranges) and checks them before anything runs; ``run_sweep`` returns
one row per point with the table speed, final and steady temperatures [°C] and D [µm].
The cycle-averaged motion keeps each run to a fraction of a second.
``feedtherm sweep --screw-rpm 396,1116 --nut-rpm 360 --ambient 20`` writes the same rows
to sweep.csv.
"""

from feedtherm.analysis.sweep import parse_grid, run_sweep
from feedtherm.system.load import load_system


def main(duration: float = 1800.0) -> dict:
    loaded = load_system("paper")
    grid = parse_grid("396,1116", "360", "20", drive=loaded.system.kinematics.drive)  # 2 × 1 × 1
    rows = run_sweep(loaded, grid, duration=duration, motion="averaged")
    return {
        "duration_s": duration,
        "points": [(row["screw_rpm"], row["nut_rpm"], row["ambient_C"]) for row in rows],
        "table_speed_m_per_min": [row["table_speed_m_per_min"] for row in rows],
        "final_T3_C": [row["final_T3"] for row in rows],
        "final_D_um": [row["final_D_um"] for row in rows],
        "energy_relative_error": [row["energy_balance_error"] for row in rows],
    }


if __name__ == "__main__":
    r = main()
    print(f"after {r['duration_s']:.0f} s, nut at 360 rpm, ambient 20 °C:")
    for (screw, _, _), v, t3, d in zip(r["points"], r["table_speed_m_per_min"], r["final_T3_C"], r["final_D_um"]):
        print(f"  screw {screw:6.0f} rpm (table {v:.2f} m/min): T3 (nut flange) {t3:.2f} °C, D {d:.1f} µm")
