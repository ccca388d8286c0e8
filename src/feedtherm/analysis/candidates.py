"""Candidate sensor positions: named points on the exposed surfaces of every part.

A compensation law reads a few temperature sensors; which few is a choice
(:mod:`~feedtherm.analysis.compensation.selection`).  The candidates it chooses from are made
here from the geometry alone, by one rule:

- on each box of a part, points on its top face (``top``) and its two side faces (``side_neg_y``,
  ``side_pos_y``): at the face's centre, or, for a face longer than :data:`SPAN_FOR_THREE` along x,
  at a quarter, a half and three quarters of its length (``_x<mm>`` from the machine origin);
- on each cylinder along x, points on its top line: every :data:`SCREW_PITCH` along a long
  cylinder (the screw: an infrared reading, as the paper reads its screw), else at mid-length;
- each point :data:`DEPTH` under its face (a sensor reads the wall it is glued to), and kept only
  where the face is exposed: :data:`DEPTH` outside it there is no part that moves with it (a part
  passing by, such as the table over a rail, does not hide a surface for good);
- the description's own sensors and the ambient (``room.ambient_sensor``) are candidates
  under their names;
- each candidate has a sensor kind (:func:`sensor_kind`, issue 34): ``contact`` (a PT100 or
  thermocouple) on a part that stays still, ``infrared`` (a pyrometer on the frame) on a part that
  moves or turns, where wires could not follow; a declared sensor keeps its declared ``method``,
  the ambient is a contact sensor in the air.  A generated point whose kind the description does
  not allow (``[compensation] kinds``, :mod:`feedtherm.system.sensing`) is no candidate.

- a candidate a machine cannot carry is kept with the reason (:func:`mount_problem`, issue 56),
  and a study chooses among the others only (:func:`carriable`): a contact sensor on a part that
  turns (its wires cannot follow), a pyrometer on a part that moves (its spot would travel with
  the table), and any spot that a part moving past it covers at some position of the stroke (the
  screw under the nut's travel, a rail's side under the carriages).

Names are ``<part>[_b<box>|_c<cylinder>]_<face>[_x<mm>]``, e.g. ``front_housing_b0_top``,
``screw_top_x200``, ``screw_top_xm50`` (at x = −50 mm).
The candidates enter a run as extra sensors of the description (:func:`with_candidates`), so
every model probes them the way it probes the declared sensors.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..system.checks import turning_parts
from ..system.geometry import contains
from ..system.load import LoadedSystem
from ..system.schema import Box, Cylinder, FeedSystem, Sensor
from ..system.variants import with_values

#: Depth of a candidate under its face [m]: a PT100 reads the wall it is glued to.
DEPTH = 1e-3
#: A face longer than this along x gets three points instead of one [m] (a base, a rail, a table).
SPAN_FOR_THREE = 0.25
#: Spacing of the points along a long cylinder (the screw) [m].
SCREW_PITCH = 0.05
#: A cylinder longer than this gets points every :data:`SCREW_PITCH` [m].
LONG_CYLINDER = 0.3


@dataclass(frozen=True)
class Candidate:
    """A candidate sensor: its part, position [m] (moving parts: at mid-stroke) and where it is."""

    name: str
    part: str
    position: tuple[float, float, float]
    where: str  # "top", "side_neg_y", ..., "declared" (a sensor of the description), "ambient"
    kind: str = "contact"  # "contact" | "infrared" (:func:`sensor_kind`)
    problem: str = ""  # why a machine cannot carry it (:func:`mount_problem`); empty: it can


#: Positions of the moving group at which a spot is looked at for a part passing over it.
SWEEP_POSITIONS = 41
#: A spot within this distance of a part moving past it is covered [m]: a wiper, a carriage's
#: flank or a nut's bore runs over it.
COVER_DISTANCE = 3e-3


def mount_problem(system: FeedSystem, part: str, point, kind: str) -> str:
    """Why a sensor of ``kind`` at ``point`` [m] (moving parts: mid-stroke) on ``part`` cannot be carried
    by a machine, or an empty string where it can (module notes)."""
    if not part:
        return ""  # the air
    moving = system.parts[part].moving
    if kind == "contact" and part in turning_parts(system):
        return f"a contact sensor on {part}, which turns: its wires could not follow"
    if kind == "infrared" and moving:
        return f"a pyrometer on the frame aimed at {part}, which moves: its spot would travel with the table"
    cover = covering_part(system, part, point)
    if cover is not None:
        return f"in the path of {cover}, which passes over the spot as the table travels"
    return ""


def covering_part(system: FeedSystem, part: str, point) -> str | None:
    """The first part that moves relative to ``part`` and comes within :data:`COVER_DISTANCE` of ``point``
    at some position of the stroke, or None."""
    if system.kinematics is None:
        return None
    stroke = system.kinematics.stroke
    offsets = [stroke * (i / (SWEEP_POSITIONS - 1) - 0.5) for i in range(SWEEP_POSITIONS)]
    moving = system.parts[part].moving
    x, y, z = point
    for name, other in system.parts.items():
        if name == part or other.moving == moving:
            continue
        sign = 1.0 if moving else -1.0  # the other part's frame: the point moves with the table, or the part does
        if any(contains(other, (x + sign * d, y, z), tol=COVER_DISTANCE) for d in offsets):
            return name
    return None


def carriable(candidates: dict[str, Candidate]) -> list[str]:
    """The candidates a machine can carry (no :attr:`Candidate.problem`), in order."""
    return [name for name, c in candidates.items() if not c.problem]


def sensor_kind(system: FeedSystem, part: str) -> str:
    """``infrared`` on a part that turns (its wires could not follow it), else ``contact`` (a part that
    moves with the table carries its sensor's cable in the drag chain)."""
    screw = system.kinematics.screw if system.kinematics is not None else None
    return "infrared" if part == screw or part in turning_parts(system) else "contact"


def allowed_kinds(system: FeedSystem) -> tuple[str, ...]:
    """The sensor kinds a study may place (``[compensation] kinds``; default both)."""
    return tuple(system.compensation.kinds) if system.compensation is not None else ("contact", "infrared")


def candidate_sensors(system: FeedSystem) -> dict[str, Candidate]:
    """Every candidate of ``system``: its declared sensors first (ambient included), then the generated
    points of the kinds allowed (:func:`allowed_kinds`)."""
    out: dict[str, Candidate] = {}
    for name, sensor in system.sensors.items():
        if name != system.room.ambient_sensor:
            out[name] = Candidate(name, sensor.part, tuple(sensor.position), "declared", sensor.method,
                                  mount_problem(system, sensor.part, sensor.position, sensor.method))
    # the air: every run reports it (Solution.sensors), at no point of a part
    ambient = system.room.ambient_sensor
    out[ambient] = Candidate(ambient, "", (float("nan"),) * 3, "ambient", "contact")
    for part_name, part in system.parts.items():
        several = len(part.boxes) > 1
        for i, box in enumerate(part.boxes):
            prefix = f"{part_name}_b{i}" if several else part_name
            for face, points in _box_points(box).items():
                for suffix, point in points:
                    _keep(out, system, part_name, f"{prefix}_{face}{suffix}", point, face)
        for i, cyl in enumerate(part.cylinders):
            if cyl.axis != "x":
                continue
            prefix = f"{part_name}_c{i}" if len(part.cylinders) > 1 else part_name
            for suffix, point in _cylinder_points(cyl):
                _keep(out, system, part_name, f"{prefix}_top{suffix}", point, "top")
    return out


def with_candidates(loaded: LoadedSystem, candidates: dict[str, Candidate]) -> LoadedSystem:
    """``loaded`` with every candidate as a sensor (the declared sensors keep their entries)."""
    sensors = dict(loaded.system.sensors)
    for name, candidate in candidates.items():
        if name not in sensors and candidate.where != "ambient":
            sensors[name] = Sensor(part=candidate.part, position=[f"{v!r} m" for v in candidate.position],
                                   method=candidate.kind,
                                   description=f"candidate: {candidate.part}, {candidate.where}")
    return with_values(loaded, {"sensors": sensors}, origin_suffix="candidate sensors")


def _box_points(box: Box) -> dict[str, list[tuple[str, tuple[float, float, float]]]]:
    (x0, y0, z0), (sx, sy, sz) = box.origin, box.size
    xs = [x0 + sx * f for f in ((0.25, 0.5, 0.75) if sx > SPAN_FOR_THREE else (0.5,))]
    label = (lambda x: f"_{_x_label(x)}") if len(xs) > 1 else (lambda x: "")
    yc, zc = y0 + sy / 2, z0 + sz / 2
    return {
        "top": [(label(x), (x, yc, z0 + sz - DEPTH)) for x in xs],
        "side_neg_y": [(label(x), (x, y0 + DEPTH, zc)) for x in xs],
        "side_pos_y": [(label(x), (x, y0 + sy - DEPTH, zc)) for x in xs],
    }


def _x_label(x: float) -> str:
    """``x200`` for 200 mm, ``xm50`` for -50 mm (names are identifiers)."""
    mm = round(x * 1e3)
    return f"x{mm:d}" if mm >= 0 else f"xm{-mm:d}"


def _cylinder_points(cyl: Cylinder) -> list[tuple[str, tuple[float, float, float]]]:
    x0, y0, z0 = cyl.origin
    z = z0 + cyl.outer_diameter / 2 - DEPTH
    if cyl.length > LONG_CYLINDER:
        first = -(-x0 // SCREW_PITCH) * SCREW_PITCH  # the first multiple of the pitch on the cylinder
        xs, x = [], first
        while x <= x0 + cyl.length + 1e-12:
            xs.append(round(x, 9))
            x += SCREW_PITCH
        return [(f"_{_x_label(x)}", (x, y0, z)) for x in xs]
    return [("", (x0 + cyl.length / 2, y0, z))]


def _keep(out: dict[str, Candidate], system: FeedSystem, part_name: str, name: str,
          point: tuple[float, float, float], face: str) -> None:
    """Add the candidate where its face is exposed to the air (see the module's notes)."""
    part = system.parts[part_name]
    if not contains(part, point, tol=0.0):
        return
    outside = _outward(point, face, 2 * DEPTH)
    if contains(part, outside, tol=0.0):
        return  # the face is fused to another primitive of the part
    for other_name, other in system.parts.items():
        if other_name != part_name and other.moving == part.moving and contains(other, outside, tol=0.0):
            return
    kind = sensor_kind(system, part_name)
    if kind in allowed_kinds(system):
        position = tuple(float(v) for v in point)
        out[name] = Candidate(name, part_name, position, face, kind, mount_problem(system, part_name, position, kind))


def _outward(point, face: str, distance: float) -> tuple[float, float, float]:
    x, y, z = point
    if face == "side_neg_y":
        return (x, y - distance, z)
    if face == "side_pos_y":
        return (x, y + distance, z)
    return (x, y, z + distance)  # top of a box, top line of a cylinder along x
