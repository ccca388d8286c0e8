"""Points a description places in a part's material, and the parts that may hold them.

Every point that names a part must lie in that part's material (within 1 mm, as written
coordinates are rounded): a sensor's position, a support's point, the elongation sensor's
target and mount, the positioning reference.  A point in a hole's empty bore is outside the
part, although it lies inside one of the part's boxes: nothing there reads, holds or moves
with the part (:func:`~feedtherm.system.geometry.hole_at`).  Heat sources name parts, not
points, and have none to place.

A part that moves with the table (``moving = true``) travels ±stroke/2 along x, where the drive
sets its place.  A support on it may hold it across its travel (``y``, ``z``: its guides, as
the free-bar verification case holds its ring; the support travels with the part), and along x
only where no joint ties its moving group to the frame: joined (the nut on the screw), the drive
holds it along x, and a support there would hold the table against the drive; joined to nothing
fixed, its own supports stand for the drive.  The positioning reference is a point
of the machine's frame the error is measured from, so it may not lie on a moving part.  The
elongation's target and mount may (a displacement sensor can ride on the table).
"""

from __future__ import annotations

from typing import NamedTuple

from .finding import Finding
from .geometry import contains, hole_at
from .schema import FeedSystem


class PlacedPoint(NamedTuple):
    """A point the description places in ``part``: its field ``path`` and coordinates [m]."""

    path: str
    part: str
    point: tuple[float, float, float]
    why: str  # what the point is, said after "which it names" where it lies outside


def placed_points(system: FeedSystem) -> list[PlacedPoint]:
    """Every point of the description that must lie in the part it names."""
    points = [PlacedPoint(f"sensors.{name}.position", s.part, s.position,
                          " (a sensor reads its part's surface or inside)") for name, s in system.sensors.items()]
    mech = system.mechanics
    points += [PlacedPoint(f"mechanics.supports[{i}].point", s.part, s.point, "") for i, s in enumerate(mech.supports)]
    points.append(PlacedPoint("mechanics.elongation.target.point", mech.elongation.target.part,
                              mech.elongation.target.point, ""))
    if not isinstance(mech.elongation.mount, str):
        points.append(PlacedPoint("mechanics.elongation.mount.point", mech.elongation.mount.part,
                                  mech.elongation.mount.point, ""))
    if mech.positioning is not None:
        points.append(PlacedPoint("mechanics.positioning.reference.point", mech.positioning.reference.part,
                                  mech.positioning.reference.point, ""))
    return points


def misplaced(system: FeedSystem) -> list[Finding]:
    """Errors: a point outside the part it names, or in the empty bore of one of its holes."""
    findings = []
    for path, name, point, why in placed_points(system):
        part = system.parts[name]
        if contains(part, point):
            continue
        where = ", ".join(f"{x * 1e3:g}" for x in point)
        hole = hole_at(part, point)
        if hole is not None:
            findings.append(Finding(path, f"({where}) mm lies in the hole of part {name!r} (holes[{hole}]), which it "
                                    f"names: a bore is empty, not the part's material{why}", "error"))
        else:
            findings.append(Finding(path, f"({where}) mm lies outside part {name!r}, which it names{why}", "error"))
    return findings


def driven_moving_parts(system: FeedSystem) -> set[str]:
    """The moving parts a joint ties, through other moving parts, to a part that does not move: the
    nut on the screw, the sliders on the rails.  The drive holds them along x; a moving group joined
    to nothing fixed (a carriage drawn beside a test's rod) is held by its own supports."""
    moving = {name for name, part in system.parts.items() if part.moving}
    driven = {a if a in moving else b for j in system.joints for a, b in [tuple(j.between)]
              if (a in moving) != (b in moving)}
    grown = True
    while grown:
        more = {b if a in driven else a for j in system.joints for a, b in [tuple(j.between)]
                if a in moving and b in moving and (a in driven) != (b in driven)}
        grown = bool(more - driven)
        driven |= more
    return driven


def on_moving_parts(system: FeedSystem) -> list[Finding]:
    """Errors: a support along x on a part of a driven moving group (:func:`driven_moving_parts`), or the
    positioning reference on a part that moves with the table."""
    parts, mech = system.parts, system.mechanics
    driven = driven_moving_parts(system)
    findings = [Finding(f"mechanics.supports[{i}].fix",
                        f"holds {s.part!r} along x, and it moves with the table (moving = true), joined to the "
                        "machine's frame: along x the drive sets where the moving group stands, so a support there "
                        "holds the table against it; a support on a moving part holds it across its travel only "
                        "(y, z: its guides)", "error")
                for i, s in enumerate(mech.supports) if s.part in driven and "x" in s.fix]
    if mech.positioning is not None and parts[mech.positioning.reference.part].moving:
        findings.append(Finding("mechanics.positioning.reference.part",
                                f"{mech.positioning.reference.part!r} moves with the table (moving = true): the "
                                "positioning error is the table's deviation from where the encoder's count puts it, "
                                "measured from a point of the machine's frame (the rotary encoder's bearing, a linear "
                                "scale's reference); a point that travels with the table would measure the table "
                                "against itself", "error"))
    return findings
