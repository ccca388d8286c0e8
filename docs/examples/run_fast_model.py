"""Run the fast model for one hour of condition I and read the Solution.

``simulate`` plans the run (condition -> operating point -> boundary conditions), integrates
it with the model chosen by name ("fast" here) and packs a ``Solution``: sensor series [K],
the screw's temperature and axial displacement along its length, the elongation D [m], the
positioning error E(x, t) along the stroke [m], final and steady values, and the energy
balance (heat in = heat lost + heat stored), the first check of any thermal run.
The bench couples its boundary conditions to the temperatures (``coupling = "nonlinear"``):
the heat of the sources changes as the bench warms, so the heat in is the time integral of
that changing heat; the run reports the heat of its last boundary conditions in
``info["heat_W"]``.

D is what the description's displacement sensor reads (``mechanics.elongation``): on the
paper bench a laser on a stand on the base, aimed along the axis at the screw's rear end
face.  The fast model reads it along the structure's axial load path: the screw stretches
freely beyond its front (fixed) bearing, by α ∫ (T̄ − T_ref) dx of its section-mean
temperature, and the laser's stand moves with the base, whose own expansion between the
front bearing's housing and the stand the laser sees too.
"""

import numpy as np

from feedtherm.constants import KELVIN_OFFSET
from feedtherm.simulate import simulate
from feedtherm.system.geometry import bounds
from feedtherm.system.load import load_system

SENSORS = ["T1", "T2", "T3", "T4", "T5"]


def main(duration: float = 3600.0) -> dict:
    loaded = load_system("paper")
    system = loaded.system
    run = simulate(loaded, condition="I", duration=duration)  # model="fast", motion="resolved"
    final = run.summary_values("final")  # °C and µm: the mean over the last reciprocation cycle
    steady = run.summary_values("steady")  # the cycle-averaged steady state of condition I
    # The screw at the last sample: its section-mean temperature per 5 mm cell and its axial
    # displacement relative to the positioning reference (the base under the front bearing).
    x = run.screw_x
    screw = run.screw_temperature[-1] - KELVIN_OFFSET
    # The screw moves with its front bearing where it sits in it and stretches freely beyond:
    # from there to the laser's target, α ∫ (T̄ − T_ref) dx over the cells in between.
    held_to = bounds(system.parts["front_bearing"])[1][0]
    target = system.mechanics.elongation.target.point[0]
    free = (x > held_to) & (x < target)
    alpha = system.materials[system.parts[system.kinematics.screw].material].expansion
    t_ref = system.temperatures.reference - KELVIN_OFFSET
    width = np.gradient(x)  # the cells' widths (5 mm, uniform)
    stretch = alpha * float(np.sum((screw[free] - t_ref) * width[free]))
    return {
        "final_C": {name: final[name] for name in SENSORS},
        "steady_C": {name: steady[name] for name in SENSORS},
        "ambient_C": final["T6"],
        "D_um": final["D_um"],
        "D_end_um": float(run.elongation_um[-1]),  # at the last sample, with the fields below
        "screw_x_m": x,
        "screw_C": screw,
        "screw_displacement_um": run.screw_displacement[-1] * 1e6,
        "screw_stretch_um": stretch * 1e6,
        "screw_free_m": (held_to, target),
        "base_C": float(run.part_temperatures["base"][-1]) - KELVIN_OFFSET,
        "table_x_m": run.table_x,
        "positioning_error_um": run.positioning_error[-1] * 1e6,  # E(x) at the last sample
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
    lo, hi = r["screw_free_m"]
    print(f"elongation D = {r['D_um']:.1f} µm: the screw stretches {r['screw_stretch_um']:.1f} µm from its "
          f"front bearing ({lo * 1e3:.0f} mm) to the laser's target ({hi * 1e3:.0f} mm); the base, expanding "
          f"under the laser's stand, takes {r['screw_stretch_um'] - r['D_end_um']:.2f} µm off")
    x, e = r["table_x_m"], r["positioning_error_um"]
    print(f"positioning error E = {e[0]:.1f} µm at x = {x[0] * 1e3:.1f} mm, {e[len(e) // 2]:.1f} µm at "
          f"{x[len(x) // 2] * 1e3:.1f} mm, {e[-1]:.1f} µm at {x[-1] * 1e3:.1f} mm")
    print(f"energy balance: {r['energy_in_J'] / 1e3:.1f} kJ in (mean {r['energy_in_J'] / r['duration_s']:.2f} W, "
          f"{r['heat_end_W']:.2f} W at the end), relative error {r['energy_relative_error']:.1e}")
