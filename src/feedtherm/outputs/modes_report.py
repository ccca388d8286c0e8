"""``feedtherm modes``: the slowest thermal modes of a condition as console tables or one JSON object."""

from __future__ import annotations

import sys

from rich.console import Console
from rich.markup import escape
from rich.table import Table

from ..analysis.thermal_modes import ThermalModes, settling_time
from .files import json_text

#: Parts listed per mode: the largest shares of its stored heat.
TOP_PARTS = 4


def modes_json(result: ThermalModes) -> str:
    """One JSON object: per mode the time constant [s], its 95 % settling time [s], part shares and
    sensor amplitudes [K]; the parts' capacities [J/K]."""
    return json_text({
        "condition": result.condition,
        "capacity_J_per_K": result.capacities,
        "modes": [{"time_constant_s": m.time_constant, "settling_95_s": settling_time(m.time_constant),
                   "part_shares": m.part_shares, "sensor_amplitude_K": m.sensor_amplitudes}
                  for m in result.modes],
    })


def print_modes(result: ThermalModes, system_name: str, console: Console | None = None) -> None:
    console = console or Console(width=None if sys.stdout.isatty() else 160)
    console.print(f"[bold]{system_name}[/], condition [bold]{result.condition}[/]: the slowest thermal modes "
                  "around the steady state (start at the initial temperature)")
    sensors = list(result.modes[0].sensor_amplitudes) if result.modes else []
    table = Table(title="Modes, slowest first", title_justify="left")
    table.add_column(escape("τ [min]"), justify="right")
    table.add_column(escape("95 % [min]"), justify="right")
    table.add_column("where its heat is stored (share)")
    for name in sensors:
        table.add_column(escape(f"{name} [K]"), justify="right")
    for m in result.modes:
        top = sorted(m.part_shares.items(), key=lambda kv: -kv[1])[:TOP_PARTS]
        table.add_row(f"{m.time_constant / 60:.1f}", f"{settling_time(m.time_constant) / 60:.0f}",
                      ", ".join(f"{p} {s:.2f}" for p, s in top),
                      *(f"{m.sensor_amplitudes[s]:+.2f}" for s in sensors))
    console.print(table)
    console.print("A sensor's amplitude is that mode's part of (initial − steady) temperature there; the sensor "
                  "settles with the slowest mode of large amplitude.")
    caps = Table(title="Heat capacity per part", title_justify="left")
    caps.add_column("part")
    caps.add_column(escape("C [J/K]"), justify="right")
    for part, c in sorted(result.capacities.items(), key=lambda kv: -kv[1]):
        caps.add_row(part, f"{c:,.0f}")
    console.print(caps)
