"""``feedtherm heat``: the boundary conditions as console tables or one JSON object."""

from __future__ import annotations

import sys

from rich.console import Console
from rich.markup import escape
from rich.table import Table

from ..boundary import BoundaryConditions
from ..constants import KELVIN_OFFSET
from ..system.overlay import Overlay
from .files import json_text


def heat_json(bc: BoundaryConditions, printed: Overlay | None = None) -> str:
    """One JSON object: heats [W] and CHTCs [W/(m^2 K)], with the values ``printed`` (the bench's
    overlay, if it has one) beside, at its reference condition.

    A value the correlations could not compute (NaN, infinite) is ``null``: JSON has no NaN.
    """
    return json_text({
        "condition": bc.condition,
        "mode": bc.mode,
        "heat_W": {name: h.power for name, h in bc.heats.items()},
        "chtc_W_per_m2K": {name: s.convection for name, s in bc.surfaces.items()},
        "radiation_W_per_m2K": {name: s.radiation for name, s in bc.surfaces.items()},
        # the exposed areas (a surface without `area`: its faces less what joined parts cover)
        "surface_area_m2": {name: s.area for name, s in bc.surfaces.items()},
        "joints": [{"between": list(j.parts), "area_m2": j.area, "tcr_m2K_per_W": j.tcr,
                    "conductance_W_per_K": j.conductance, "sliding": j.sliding} for j in bc.joints],
        "printed": None if printed is None else {
            "overlay": printed.name, "title": printed.title, "condition": printed.reference_condition,
            "heat_W": printed.printed_heats(), "chtc_W_per_m2K": printed.printed_chtcs()},
        "screw_rpm": bc.point.screw_rpm,
        "nut_rpm": bc.point.nut_rpm,
        "table_speed_m_per_min": bc.point.table_speed * 60.0,
        "ambient_C": bc.point.ambient - KELVIN_OFFSET,
        "details": {name: h.details for name, h in bc.heats.items()},
        "correlation": {name: s.correlation for name, s in bc.surfaces.items()},
        "warnings": bc.warnings,
    })


def _duty(ratio: float | None) -> str:
    """A motor's torque as a share of its rated continuous torque; over 100 % in red."""
    if ratio is None:
        return "—"
    text = f"{100.0 * ratio:.0f} %"
    return f"[red]{text}[/]" if ratio > 1.0 else text


def _current(details: dict) -> str:
    """A motor's current [A r.m.s.] and, where declared, its continuous current."""
    if "current_A" not in details:
        return "—"
    rated = details.get("continuous_current_A")
    return f"{details['current_A']:.2f}" + ("" if rated is None else f" / {rated:.2f}")


def _printed(value: float | None, fmt: str) -> str:
    return "—" if value is None else format(value, fmt)


def print_heat(bc: BoundaryConditions, system_name: str, console: Console | None = None,
               printed: Overlay | None = None) -> None:
    """The heats, CHTCs and joints as console tables, with the values ``printed`` beside (an overlay)."""
    console = console or Console(width=None if sys.stdout.isatty() else 132)
    p = bc.point
    heat = printed.printed_heats() if printed else {}
    chtc = printed.printed_chtcs() if printed else {}
    column = printed.name if printed else "printed"
    console.print(
        f"[bold]{system_name}[/], condition [bold]{bc.condition}[/], mode [bold]{bc.mode}[/]: "
        f"screw {p.screw_rpm:.0f} rpm, nut {p.nut_rpm:.0f} rpm, relative {p.relative_rpm:.0f} rpm, "
        f"table {abs(p.table_speed) * 60:.3g} m/min, ambient {p.ambient - KELVIN_OFFSET:.1f} °C"
    )
    heats = Table(title="Heat per source", title_justify="left")
    heats.add_column("source")
    heats.add_column(escape("heat [W]"), justify="right")
    heats.add_column(escape(f"{column} [W]"), justify="right")
    heats.add_column(escape("speed [rpm]"), justify="right")
    heats.add_column(escape("torque [N·m]"), justify="right")
    heats.add_column("of continuous", justify="right")
    heats.add_column(escape("current [A]"), justify="right")
    for name, h in bc.heats.items():
        torque = h.details.get("friction_torque_Nm", h.details.get("torque_Nm"))
        heats.add_row(
            name, f"{h.power:.3f}", _printed(heat.get(name), ".2f"), f"{h.speed_rpm:.0f}",
            "—" if torque is None else f"{torque:.4f}",
            _duty(h.details.get("torque_to_continuous")), _current(h.details),
        )
    heats.add_row("[bold]total[/]", f"[bold]{bc.total_heat:.3f}[/]", "", "", "", "", "")
    console.print(heats)
    surfaces = Table(title="Heat transfer per surface", title_justify="left")
    surfaces.add_column("surface")
    surfaces.add_column(escape("area [m²]"), justify="right")
    surfaces.add_column(escape("CHTC [W/(m²·K)]"), justify="right")
    surfaces.add_column(escape(f"{column} [W/(m²·K)]"), justify="right")
    surfaces.add_column(escape("radiation [W/(m²·K)]"), justify="right")
    surfaces.add_column("correlation")
    for name, s in bc.surfaces.items():
        surfaces.add_row(
            name, f"{s.area:.4f}", f"{s.convection:.2f}", _printed(chtc.get(name), ".2f"),
            f"{s.radiation:.2f}", s.correlation,
        )
    console.print(surfaces)
    joints = Table(title="Thermal contact resistance per joint", title_justify="left")
    for column in ("joint", "TCR [m²·K/W]", "area [m²]", "conductance [W/K]", "sliding"):
        joints.add_column(column, justify="left" if column == "joint" else "right")
    for j in bc.joints:
        joints.add_row(" – ".join(j.parts), f"{j.tcr:.3g}", f"{j.area:.4g}", f"{j.conductance:.3g}", "yes" if j.sliding else "")
    console.print(joints)
    if printed is not None:
        console.print(f"{printed.name}: {printed.title or 'printed values'}, at condition {printed.reference_condition}.")
    for message in bc.warnings:
        console.print(f"[yellow]correlation range:[/] {message}")
