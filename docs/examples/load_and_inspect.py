"""Load the paper's bench and look at its boundary conditions at condition I.

Shows the description as typed data (parts, heat sources) and what the boundary-condition
step makes of it at one operating point: the heat of every source [W] beside the paper's
Table 1, their total, how the screw motor's loss is made (its torque, current, copper and
no-load loss), and the screw shaft's convective coefficient (CHTC) [W/(m²·K)] beside Table 2.
``feedtherm heat --condition I`` prints the same numbers as a table.

The bench's losses come from catalogue models (the motors' data-sheet copper and no-load
losses, the SKF bearing friction model), not from the paper's equations, so the heats
differ from Table 1, which is printed for comparison only.  They are taken here at the
declared surface temperature, ambient + ``temperatures.convection_delta_t``; a run of this
description (``coupling = "nonlinear"``) re-evaluates them at its own temperatures.
"""

from feedtherm.boundary import boundary_conditions
from feedtherm.system.load import load_system
from feedtherm.system.overlay import available_overlay


def main() -> dict:
    loaded = load_system("paper")  # a bundled bench by name, or a path to a TOML description
    system = loaded.system
    bc = boundary_conditions(system, "I")
    printed = available_overlay(loaded)  # the bench's overlay: Tables 1 and 2 at condition I
    shaft = bc.surfaces["screw_shaft"]
    return {
        "parts": list(system.parts),
        "sources": list(system.sources),
        "screw_rpm": bc.point.screw_rpm,
        "nut_rpm": bc.point.nut_rpm,
        "total_heat_W": bc.total_heat,
        "heat_W": {name: heat.power for name, heat in bc.heats.items()},
        "details": {name: dict(heat.details) for name, heat in bc.heats.items()},  # what made each heat
        "table1_heat_W": printed.printed_heats(),  # the paper's printed values, for comparison
        "screw_shaft_chtc": shaft.convection,
        "screw_shaft_radiation": shaft.radiation,
        "table2_screw_shaft_chtc": printed.printed_chtcs()["screw_shaft"],
    }


if __name__ == "__main__":
    r = main()
    print(f"{len(r['parts'])} parts: {', '.join(r['parts'])}")
    print(f"{len(r['sources'])} heat sources: {', '.join(r['sources'])}")
    print(f"condition I: screw {r['screw_rpm']:g} rpm, nut {r['nut_rpm']:g} rpm")
    print(f"{'source':<14}{'physics [W]':>12}{'Table 1 [W]':>13}")
    for name, power in r["heat_W"].items():
        printed = r["table1_heat_W"].get(name)
        print(f"{name:<14}{power:>12.2f}{'' if printed is None else f'{printed:.2f}':>13}")
    print(f"total heat: {r['total_heat_W']:.2f} W")
    m = r["details"]["screw_motor"]
    print(f"screw motor: {m['torque_Nm']:.3f} N·m on its shaft, {m['current_A']:.2f} A, copper loss "
          f"{m['copper_loss_W']:.2f} W ({m['terminal_resistance_ohm']:.2f} ohm) + no-load loss {m['no_load_loss_W']:.2f} W")
    print(f"screw shaft CHTC: {r['screw_shaft_chtc']:.1f} W/(m²·K) convection "
          f"(+ {r['screw_shaft_radiation']:.1f} radiation); Table 2: {r['table2_screw_shaft_chtc']:.1f}")
