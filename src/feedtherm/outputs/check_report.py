"""The lines `feedtherm check` adds after its verdict: derived areas and what runs will cost."""

from __future__ import annotations

from ..plan import AVERAGED_MOTION_MAX_CYCLE_S, RunCost
from ..system.areas import exposed_area
from ..system.geometry import surface_area
from ..system.load import LoadedSystem


def area_lines(loaded: LoadedSystem) -> list[str]:
    """The joints' areas the geometry gave, and the surfaces whose exposed area is less than their faces'."""
    system = loaded.system
    lines = []
    for index in loaded.derived_joint_areas:
        joint = system.joints[index]
        lines.append(f"  joints[{index}] {' – '.join(joint.between)}: {joint.area:.4g} m² of contact")
    for name, surface in system.surfaces.items():
        if surface.area is not None:
            continue
        faces = surface_area(surface, system.parts[surface.part])
        exposed = exposed_area(system, name)
        if exposed < faces * (1.0 - 1e-9):
            lines.append(f"  surfaces.{name}: {exposed:.4g} m² exposed of {faces:.4g} m² of faces "
                         f"({100.0 * (faces - exposed) / faces:.0f} % covered by joined or fused parts)")
    if not lines:
        return []
    return ["areas derived from the geometry (as drawn, the moving group mid-stroke; give `area` to override):",
            *lines]


def _duration(seconds: float) -> str:
    if seconds < 60.0:
        return f"{seconds:.2g} s" if seconds < 10.0 else f"{seconds:.0f} s"
    if seconds < 3600.0:
        return f"{seconds / 60.0:.1f} min"
    return f"{seconds / 3600.0:.1f} h"


def size_lines(cost: RunCost) -> list[str]:
    """What the times below scale with: each model's nodes (the FE meshes' predicted), the moving
    group's grid positions, and what a reduced model's first run on a mesh adds."""
    sizes = cost.sizes
    fast = sizes.get(("fast", None))
    parts = [size.describe() for size in sizes.values() if size.model != "reduced"]
    line = "  " + "; ".join(parts)
    if fast is not None and fast.positions > 1:
        line += f"; {fast.positions} grid positions of the moving group"
    lines = ["run costs below: `feedtherm run`'s wall time, estimated from each model's size and the run's steps:", line]
    for (model, mesh), seconds in cost.first_build.items():
        size = sizes[(model, mesh)]
        lines.append(f"  {size.describe()}: its first run on a mesh also builds its projection, about "
                     f"{_duration(seconds)} more (kept on disk for the runs after)")
    return lines


def cost_lines(what: str, duration: float, cost: RunCost) -> list[str]:
    """Time steps and estimated wall time per model of one condition or duty cycle, and when the
    cycle-averaged motion is advised."""
    lines = [f"run cost of {what} ({_duration(duration)} simulated):"]
    for motion, steps in cost.steps.items():
        times = ", ".join(f"{model}{'' if mesh is None else ' ' + mesh} {_duration(by_motion[motion])}"
                          for (model, mesh), by_motion in cost.seconds.items())
        windows = (f" ({cost.window_steps:,} in the FE and reduced models, window by window)"
                   if motion == "resolved" and cost.window_steps is not None else "")
        lines.append(f"  --motion {motion}: {steps:,} steps{windows}; about {times}")
    if cost.suggest_averaged:
        ratio = cost.steps["resolved"] / max(cost.steps["averaged"], 1)
        lines.append(f"  the reciprocation cycle ({cost.cycle_s:.3g} s) is under {AVERAGED_MOTION_MAX_CYCLE_S:g} s: "
                     f"--motion averaged gives the same cycle means within about 0.04 K in 1/{ratio:.0f} of the steps")
    return lines


#: How the times above are estimated, printed once under them.
BASIS = ("estimated times: start-up and plots (about 5 s), the model's set-up (an FE mesh where it is not cached, "
         "its assembly and elastic readout, its contacts at every grid position), a factorisation per operating point "
         "and position visited, and a solve per step, each a power law in the model's nodes measured on both bundled "
         "benches (feedtherm.plan.cost); on a 2-core x86-64 machine with nothing else running, longer on a busy one")
