"""Convective (and radiative) heat transfer coefficient of every surface.

The convection kinds of the description map onto the paper's §3.2: natural convection of
fixed parts (Eqs. 24-26), the rotating screw or nut (Eq. 27), faces of moving parts
parallel to the motion (Eq. 28, plate average) or normal to it (Eq. 29).  Forced and
natural convection are combined as mixed convection (Churchill, n = 3), because the table
moves at only millimetres per second and natural convection dominates there.  The room's
draught (``room.air_speed``) adds forced convection to every correlated surface the same
way: a plate in parallel flow on its natural length, a cylinder in cross flow
(Churchill-Bernstein) on its diameter.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..physics import convection, radiation
from ..physics.air import film_temperature
from ..system.areas import exposed_area
from ..system.schema import FeedSystem
from ..system.surfaces import (
    FixedConvection,
    MovingFaceConvection,
    MovingPlateConvection,
    NaturalConvection,
    RotatingConvection,
    Surface,
)
from .operating import OperatingPoint


@dataclass(frozen=True)
class SurfaceTransfer:
    """Heat transfer of one surface to the ambient air (or its sink) at an operating point."""

    name: str
    part: str
    area: float  # [m^2]
    convection: float  # CHTC [W/(m^2 K)]
    radiation: float  # linearised radiative coefficient [W/(m^2 K)] (0 when off)
    emissivity: float
    correlation: str  # how the convective coefficient was obtained
    sink: float  # temperature of the medium the surface exchanges heat with [K]: the ambient or its own

    @property
    def total(self) -> float:
        return self.convection + self.radiation


def convective_coefficient(surface: Surface, point: OperatingPoint, t_surface: float,
                           room_air_speed: float = 0.0) -> tuple[float, str]:
    """CHTC [W/(m^2 K)] of ``surface`` at surface temperature ``t_surface`` [K].

    ``room_air_speed`` [m/s]: the room's draught, forced convection on the surface's natural
    length (a plate) or diameter (a cylinder), cube-summed with the rest (mixed convection).
    """
    conv, ambient = surface.convection, point.ambient
    if isinstance(conv, FixedConvection):
        return conv.coefficient, "fixed"
    t_film = film_temperature(t_surface, ambient)
    speed = abs(point.table_speed)
    if isinstance(conv, NaturalConvection):
        h, how = convection.h_natural(conv.orientation, conv.length, t_surface, ambient), f"natural, {conv.orientation} (Eq. 25)"
        cylinder, length = conv.orientation == "horizontal_cylinder", conv.length
    elif isinstance(conv, RotatingConvection):
        forced = convection.h_rotating_cylinder(conv.diameter, point.shaft_rpm(conv.shaft), t_film)
        natural = convection.h_natural("horizontal_cylinder", conv.diameter, t_surface, ambient)
        h, how = convection.h_mixed(forced, natural), f"rotating at {conv.shaft} speed (Eq. 27) + natural"
        cylinder, length = True, conv.diameter
    elif isinstance(conv, MovingPlateConvection):
        forced = convection.h_flat_plate_laminar_average(conv.length, speed, t_film) if speed > 0 else 0.0
        natural = convection.h_natural(conv.orientation, conv.natural_length, t_surface, ambient)
        h, how = convection.h_mixed(forced, natural), "moving plate (Eq. 28, average) + natural"
        cylinder, length = False, conv.natural_length
    elif isinstance(conv, MovingFaceConvection):
        forced = convection.h_plate_normal_to_flow(conv.length, speed, t_film) if speed > 0 else 0.0
        natural = convection.h_natural("vertical_plate", conv.natural_length, t_surface, ambient)
        h, how = convection.h_mixed(forced, natural), "face normal to motion (Eq. 29) + natural"
        cylinder, length = False, conv.natural_length
    else:
        raise TypeError(f"unknown convection kind {conv!r}")  # the schema admits no other
    if room_air_speed > 0.0:
        room = (convection.h_cylinder_crossflow(length, room_air_speed, t_film) if cylinder
                else convection.h_flat_plate_laminar_average(length, room_air_speed, t_film))
        h = float(convection.h_mixed(room, h))
        how = f"{how} + room air at {room_air_speed:.3g} m/s ({'cross flow' if cylinder else 'plate'})"
    return h, how


def surface_transfer(
    system: FeedSystem, name: str, point: OperatingPoint, t_surface: float, *, with_radiation: bool
) -> SurfaceTransfer:
    """Heat transfer of surface ``name`` when its temperature is ``t_surface`` [K]."""
    surface = system.surfaces[name]
    h_conv, how = convective_coefficient(surface, point, t_surface, system.room.air_speed)
    if surface.chtc_factor != 1.0:
        h_conv *= surface.chtc_factor
        how = f"{how}, x {surface.chtc_factor:.3g} (calibrated)"
    sink = point.ambient if surface.sink_temperature is None else surface.sink_temperature
    radiates = with_radiation and surface.emissivity > 0.0
    h_rad = radiation.h_radiation(surface.emissivity, t_surface, sink) if radiates else 0.0
    area = exposed_area(system, name)  # the faces less what joined parts cover, as the models take them
    return SurfaceTransfer(name, surface.part, area, h_conv, h_rad, surface.emissivity, how, sink)
