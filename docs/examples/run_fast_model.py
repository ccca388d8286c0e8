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
face.  The fast model reads it along the structure's axial load path (``anchors`` in
feedtherm/models/fast/bars.py), each part expanding by α ∫ (T̄ − T_ref) dx of its section-mean
temperature from where it is held: a part fastened over a range at the middle of it.  The
base is held at its support (x = −250 mm); the front housing at the middle of its foot on the
base (−95 mm); the front (fixed) bearing at the middle of the housing's bore and the screw at
the middle of the bearing (both x = 0).  So the screw stretches from x = 0 to the laser's
target, the housing's stretch from −95 mm to 0 carries it, and the laser's stand moves with
the base, whose own expansion from −95 mm to the stand the laser sees too:
D = screw (0 → 450 mm) + front housing (−95 → 0 mm) − base (−95 → 480 mm).
"""

import numpy as np

from feedtherm.constants import KELVIN_OFFSET
from feedtherm.models.fast.bars import anchors
from feedtherm.simulate import simulate
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
    # Where each part is held on its parent along x (the middle of their joint): the screw at the
    # middle of its front bearing, the front housing at the middle of its foot on the base, the
    # base at its support.  From its anchor to the laser's target the screw stretches by
    # α ∫ (T̄ − T_ref) dx over the cells in between.
    held = anchors(system)
    screw_anchor = held[system.kinematics.screw][1]
    target = system.mechanics.elongation.target.point[0]
    free = (x > screw_anchor) & (x < target)
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
        "screw_stretch_m": (screw_anchor, target),
        "housing_anchor_m": held["front_housing"][1],
        "base_support_m": held["base"][1],
        "laser_mount_m": system.mechanics.elongation.mount.point[0],
        "front_housing_C": float(run.part_temperatures["front_housing"][-1]) - KELVIN_OFFSET,
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
    lo, hi = r["screw_stretch_m"]
    print(f"elongation D = {r['D_um']:.1f} µm: the screw stretches {r['screw_stretch_um']:.1f} µm from the middle "
          f"of its front bearing (x = {lo * 1e3:.0f} mm) to the laser's target ({hi * 1e3:.0f} mm); the front "
          f"housing's stretch from the middle of its foot on the base ({r['housing_anchor_m'] * 1e3:.0f} mm) to "
          f"the bearing, less the base's from there to the laser's stand ({r['laser_mount_m'] * 1e3:.0f} mm; the "
          f"base held at its support, {r['base_support_m'] * 1e3:.0f} mm), adds "
          f"{r['D_end_um'] - r['screw_stretch_um']:+.2f} µm")
    x, e = r["table_x_m"], r["positioning_error_um"]
    print(f"positioning error E = {e[0]:.1f} µm at x = {x[0] * 1e3:.1f} mm, {e[len(e) // 2]:.1f} µm at "
          f"{x[len(x) // 2] * 1e3:.1f} mm, {e[-1]:.1f} µm at {x[-1] * 1e3:.1f} mm")
    print(f"energy balance: {r['energy_in_J'] / 1e3:.1f} kJ in (mean {r['energy_in_J'] / r['duration_s']:.2f} W, "
          f"{r['heat_end_W']:.2f} W at the end), relative error {r['energy_relative_error']:.1e}")
