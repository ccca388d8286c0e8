"""Run the fast model for one hour of condition I and read the Solution.

``simulate`` plans the run (condition -> operating point -> boundary conditions), integrates
it with the model chosen by name ("fast" here) and packs a ``Solution``: sensor series [K],
the screw's temperature field and its elongation D [m], final and steady values, and the
energy balance (heat in = heat lost + heat stored), the first check of any thermal run.
The bench couples its boundary conditions to the temperatures (``coupling = "nonlinear"``):
the heat of the sources changes as the bench warms, so the heat in is the time integral of
that changing heat; the run reports the heat of its last boundary conditions in
``info["heat_W"]``.
"""

import numpy as np

from feedtherm.constants import KELVIN_OFFSET
from feedtherm.simulate import simulate
from feedtherm.system.load import load_system

SENSORS = ["T1", "T2", "T3", "T4", "T5"]


def main(duration: float = 3600.0) -> dict:
    loaded = load_system("paper")
    run = simulate(loaded, condition="I", duration=duration)  # model="fast", motion="resolved"
    final = run.summary_values("final")  # °C and µm: the mean over the last reciprocation cycle
    steady = run.summary_values("steady")  # the cycle-averaged steady state of condition I
    # The screw's section-mean temperature at the last sample, averaged between the fixed
    # bearing and the point where D is read: the field the elongation integrates.
    e = loaded.system.elongation
    x = np.linspace(e.fixed_at, e.read_at, 201)
    screw = np.interp(x, run.screw_x, run.screw_temperature[-1]) - KELVIN_OFFSET
    return {
        "final_C": {name: final[name] for name in SENSORS},
        "steady_C": {name: steady[name] for name in SENSORS},
        "ambient_C": final["T6"],
        "D_um": final["D_um"],
        "screw_mean_C": float(np.trapezoid(screw, x) / (x[-1] - x[0])),
        "screw_length_m": e.read_at - e.fixed_at,
        "duration_s": duration,
        "heat_end_W": sum(run.info["heat_W"].values()),  # the sources' heat at the end of the run
        "energy_in_J": run.energy.heat_in,
        "energy_relative_error": run.energy.relative_error,
    }


if __name__ == "__main__":
    r = main()
    print("after 1 h of condition I (fast model), °C:  "
          + "  ".join(f"{n} {t:.2f}" for n, t in r["final_C"].items()))
    print("steady state, °C:                          "
          + "  ".join(f"{n} {t:.2f}" for n, t in r["steady_C"].items()))
    print(f"elongation D = {r['D_um']:.1f} µm; screw mean {r['screw_mean_C']:.2f} °C over "
          f"{r['screw_length_m'] * 1e3:.0f} mm")
    print(f"energy balance: {r['energy_in_J'] / 1e3:.1f} kJ in (mean {r['energy_in_J'] / r['duration_s']:.2f} W, "
          f"{r['heat_end_W']:.2f} W at the end), relative error {r['energy_relative_error']:.1e}")
