"""Consistency checks of a description that passed its schema: what ``feedtherm check`` lists.

Two kinds of finding.  An *error* is a description no model can run as meant: a sensor
outside the part it names, a face the part's shape does not have, a joint declared twice, a
displacement sensor's or support's point outside its part or in its hole (system/points.py), a
support or the positioning reference on a moving part, a joint whose parts do not touch
(system/joint_contacts.py), supports and joints that leave a part free to move, a stroke longer than the thread, calibration bounds reversed or
of another dimension than their value, a part that no path connects to the ambient, a declared
uncertainty whose range excludes its value or leaves the value's accepted range (system/uncertainty_checks.py).
:func:`~feedtherm.system.load.load_system` refuses such a description with the first error's
line, so that no command starts on it.  A *warning* is content worth a look that the models
can still run: a stated feed speed that the motor speeds contradict, a value no provenance
entry accounts for, a joint's declared area far above its contact, a contact sensor on a part
that turns.
"""

from __future__ import annotations

import math
import re

from ..physics.mechanics import speed_table
from . import points, topology
from .finding import Finding
from .geometry import bounds, screw_axis, surface_area, table_travel
from .holding import free_motions
from .joint_contacts import joint_contacts
from .paths import leaf_paths, si_unit_at, unresolved
from .quantities import same_dimension, to_base_si
from .schema import FeedSystem
from .surfaces import RotatingConvection
from .uncertainty_checks import uncertainty_problems

_RAD_PER_S_TO_RPM = 60.0 / (2.0 * math.pi)
#: Relative tolerance on a stated feed speed against (n_s - n_n) * lead.
FEED_SPEED_TOLERANCE = 0.02
#: How far [m] the nut's travel may reach beyond the screw's ends (a rounding of the drawing).
TOUCH_TOLERANCE = 1e-3


def check_system(system: FeedSystem) -> list[Finding]:
    """Every inconsistency found in ``system``, errors first (an empty list when there is none)."""
    return [
        *check_errors(system),
        *_ambient_sensor(system),
        *_wired_sensors(system),
        *_feed_speeds(system),
        *(f for f in joint_contacts(system) if f.severity == "warning"),
        *topology.warnings(system),
        *_elastic_constants(system),
        *_uncertainties(system, "warning"),
        *_provenance(system),
    ]


def _uncertainties(system: FeedSystem, severity: str) -> list[Finding]:
    """The declared uncertainties' problems of one severity (system/uncertainty_checks.py)."""
    return [Finding(path, reason, kind) for path, reason, kind in uncertainty_problems(system) if kind == severity]


class _Moved:
    screw_speed, nut_speed = 1.0, 0.0


_MOVED = _Moved()


def check_errors(system: FeedSystem) -> list[Finding]:
    """The findings no model can run past (see the module's docstring)."""
    stroke = _stroke(system)
    shape = topology.errors(system, with_overlaps=not stroke)
    errors = [
        # a stroke that takes the nut off its screw also drives the moving group into other parts:
        # its one error, not the overlaps along it
        *stroke,
        *shape,
        *_geometry(system),
        # where points lie and which faces touch read the shape: judged once it has no error
        *(() if shape else points.misplaced(system)),
        *points.on_moving_parts(system),
        *(() if shape else (f for f in joint_contacts(system) if f.severity == "error")),
        *_joints_unique(system),
        *calibration_bounds(system),
        *_ambient_paths(system),
        *_held(system),
        *_table_positions(system),
    ]
    # The priors are judged against a valid description: a bad value is reported as such, not
    # (also) as a prior that excludes it.
    return errors or _uncertainties(system, "error")


def _feed_speeds(system: FeedSystem) -> list[Finding]:
    findings = []
    if system.kinematics is None:
        return findings
    lead = system.kinematics.lead
    for name, cond in system.conditions.items():
        if cond.feed_speed is None:
            continue
        n_s, n_n = cond.screw_speed * _RAD_PER_S_TO_RPM, cond.nut_speed * _RAD_PER_S_TO_RPM
        implied = abs(speed_table(n_s, n_n, lead))
        stated = abs(cond.feed_speed)
        if not math.isclose(implied, stated, rel_tol=FEED_SPEED_TOLERANCE):
            # a standstill on either side implies no lead: no lead moves a table whose motors turn alike,
            # and none stops one whose motors do not
            if implied == 0.0:
                why = "the table stands still at these motor speeds, whatever the lead"
            elif stated == 0.0:
                why = "the stated speed is a standstill, which no lead gives at these motor speeds"
            else:
                why = f"the stated speed implies a lead of {stated / abs((n_s - n_n) / 60.0) * 1e3:.3g} mm"
            findings.append(Finding(
                f"conditions.{name}.feed_speed",
                f"stated {stated * 60:.3g} m/min, but the motor speeds give "
                f"({n_s:.0f} - {n_n:.0f}) rpm x {lead * 1e3:g} mm = {implied * 60:.3g} m/min "
                f"({why}); the motor speeds are used",
            ))
    return findings


def _geometry(system: FeedSystem) -> list[Finding]:
    findings = []
    parts = system.parts
    badly_selected = {f.path.split(".")[1] for f in topology.selections(system)}  # reported there
    for name, surface in system.surfaces.items():
        if name in badly_selected:
            continue
        try:
            area = surface_area(surface, parts[surface.part])
        except (ValueError, IndexError) as exc:
            findings.append(Finding(f"surfaces.{name}.faces", str(exc), "error"))
            continue
        if area <= 0.0:
            findings.append(Finding(f"surfaces.{name}", f"has no area ({area:g} m^2)", "error"))
    return findings


def _held(system: FeedSystem) -> list[Finding]:
    """The supports and the joints must hold every part: a free motion leaves displacements undefined."""
    free = free_motions(system)
    if not free:
        return []
    shown = "; ".join(free[:4]) + (f"; and {len(free) - 4} more" if len(free) > 4 else "")
    return [Finding("mechanics.supports", f"the supports and joints leave the structure free to move ({shown}); "
                    "hold it with supports or joints that do not release that motion", "error")]


def _elastic_constants(system: FeedSystem) -> list[Finding]:
    """The FE model's thermoelastic solve needs Young's modulus and Poisson's ratio of every part's material."""
    used = sorted({part.material for part in system.parts.values()})
    return [Finding(f"materials.{name}", "declares no youngs_modulus and poisson_ratio: the FE model, which computes "
                    "the displacements in 3D, refuses it (the fast model needs only the expansion)")
            for name in used
            if system.materials[name].youngs_modulus is None or system.materials[name].poisson_ratio is None]


def _ambient_sensor(system: FeedSystem) -> list[Finding]:
    name = system.room.ambient_sensor
    if name not in system.sensors:
        return []
    return [Finding(f"sensors.{name}", f"{name} is the ambient temperature (room.ambient_sensor); a declared "
                                       f"{name} is ignored")]


def turning_parts(system: FeedSystem) -> set[str]:
    """The parts that turn in some declared condition or duty cycle: the screw, the dual drive's
    nut, and every part with a surface cooled as a body rotating with one of them (a belt)."""
    if system.kinematics is None:
        return set()
    runs = [*system.conditions.values(),
            *(segment for cycle in system.duty_cycles.values() for segment in cycle.segments)]
    shaft_turns = {"screw": any(run.screw_speed != 0.0 for run in runs),
                   "nut": system.kinematics.drive == "dual" and any(run.nut_speed != 0.0 for run in runs)}
    turning = {getattr(system.kinematics, shaft) for shaft, turns in shaft_turns.items() if turns}
    turning.update(surface.part for surface in system.surfaces.values()
                   if isinstance(surface.convection, RotatingConvection) and shaft_turns[surface.convection.shaft])
    return turning


def _wired_sensors(system: FeedSystem) -> list[Finding]:
    """A contact sensor's wires cannot follow a part that turns at hundreds of rpm: such a reading
    needs an infrared sensor (or slip rings the description does not know of)."""
    turning = turning_parts(system)
    return [Finding(f"sensors.{name}.method",
                    f"a contact sensor on {sensor.part!r}, which turns while the drive runs: its wires could not "
                    "follow it; read a turning part with method = \"infrared\", or put the sensor on a part that "
                    "does not turn")
            for name, sensor in system.sensors.items()
            if sensor.method == "contact" and sensor.part in turning]


def _joints_unique(system: FeedSystem) -> list[Finding]:
    """A pair of parts joined twice would count its contact conductance twice."""
    findings, first = [], {}
    for i, joint in enumerate(system.joints):
        pair = frozenset(joint.between)
        if len(pair) == 1:
            findings.append(Finding(f"joints[{i}].between", f"joins {joint.between[0]!r} to itself", "error"))
        elif pair in first:
            findings.append(Finding(f"joints[{i}].between", f"{' and '.join(map(repr, joint.between))} are already "
                                    f"joined by joints[{first[pair]}]; one joint per pair of parts", "error"))
        else:
            first[pair] = i
    return findings


def _table_positions(system: FeedSystem) -> list[Finding]:
    """A held table and a measuring stop's targets lie within the table's travel."""
    held = [(f"duty_cycles.{name}.segments[{i}].table_at", seg.table_at)
            for name, cycle in system.duty_cycles.items() for i, seg in enumerate(cycle.segments)
            if seg.table_at is not None]
    held += [(f"duty_cycles.{name}.measuring.targets[{i}]", x)
             for name, cycle in system.duty_cycles.items() if cycle.measuring is not None
             for i, x in enumerate(cycle.measuring.targets)]
    if not held:
        return []
    kin = system.kinematics
    if kin is None:
        return [Finding(held[0][0], "the system has no feed drive ([kinematics] is left out): no table to hold", "error")]
    lo, hi = table_travel(system)
    return [Finding(path, f"{x * 1e3:g} mm lies outside the table's travel, {lo * 1e3:g}..{hi * 1e3:g} mm (the nut's "
                    "centre along x in the machine frame)", "error")
            for path, x in held if not lo - TABLE_TOLERANCE <= x <= hi + TABLE_TOLERANCE]


#: How far a held position may lie beyond the travel's ends [m]: a rounding of the written value.
TABLE_TOLERANCE = 1e-6


def _stroke(system: FeedSystem) -> list[Finding]:
    """The nut must travel its stroke on the screw (where any condition moves the table)."""
    kin = system.kinematics
    if kin is None:
        return []
    screw, nut = system.parts[kin.screw], system.parts[kin.nut]
    points = [*system.conditions.values(), *(s for cycle in system.duty_cycles.values() for s in cycle.segments)]
    if any(cycle.measuring is not None for cycle in system.duty_cycles.values()):
        points.append(_MOVED)  # a measuring stop moves the table to its targets
    if not (screw.cylinders and (nut.cylinders or nut.boxes)) or all(p.screw_speed == p.nut_speed for p in points):
        return []
    axis = screw_axis(screw)
    (nut_lo, nut_hi) = bounds(nut)
    length = axis.end - axis.start
    if kin.stroke > length:
        return [Finding("kinematics.stroke", f"{kin.stroke * 1e3:g} mm is longer than the screw "
                        f"({length * 1e3:g} mm)", "error")]
    centre = 0.5 * (nut_lo[0] + nut_hi[0])
    half = 0.5 * (nut_hi[0] - nut_lo[0])
    lo, hi = centre - 0.5 * kin.stroke - half, centre + 0.5 * kin.stroke + half
    if lo < axis.start - TOUCH_TOLERANCE or hi > axis.end + TOUCH_TOLERANCE:
        return [Finding("kinematics.stroke", f"the nut would travel {lo * 1e3:g}..{hi * 1e3:g} mm, beyond the screw "
                        f"({axis.start * 1e3:g}..{axis.end * 1e3:g} mm)", "error")]
    return []


def calibration_bounds(system: FeedSystem) -> list[Finding]:
    """Paths that name numbers; bounds finite, lower below upper, and of their values' dimension
    (factors for a scale)."""
    if system.calibration is None:
        return []
    findings = []
    for name, spec in system.calibration.parameters.items():
        why = next((w for w in (unresolved(system, p) for p in spec.paths) if w is not None), None)
        if why is not None:  # as calibrate would meet it
            findings.append(Finding(f"calibration.parameters.{name}.paths", why, "error"))
            continue
        where = f"calibration.parameters.{name}.bounds"
        try:
            lower, upper = (to_base_si(b) for b in spec.bounds)
        except ValueError as exc:
            findings.append(Finding(where, str(exc), "error"))
            continue
        if not lower < upper:
            findings.append(Finding(where, f"the lower bound ({spec.bounds[0]}) must be below the upper "
                                    f"({spec.bounds[1]})", "error"))
        expected = "" if spec.kind == "scale" else _unit_of_paths(system, spec.paths)
        if expected is None:
            continue
        for bound in spec.bounds:
            if not same_dimension(bound, expected):
                why = ("a scale parameter's bounds are factors (bare numbers)" if spec.kind == "scale" else
                       f"does not have the dimension of the values it bounds ({expected})")
                findings.append(Finding(where, f"{bound!r} {why}" if spec.kind == "value" else f"{bound!r}: {why}",
                                        "error"))
                break
    return findings


def _unit_of_paths(system: FeedSystem, paths: list[str]) -> str | None:
    """The SI unit of the values at ``paths`` (``None`` where it cannot be told)."""
    for path in paths:
        try:
            unit = si_unit_at(system, path.replace("[*]", "[0]"))
        except (KeyError, IndexError, AttributeError, TypeError):
            continue
        if unit is not None:
            return unit
    return None


def _ambient_paths(system: FeedSystem) -> list[Finding]:
    """Every part must reach the ambient (a surface) through joints, or its temperature is undefined."""
    joined: dict[str, set[str]] = {name: set() for name in system.parts}
    for joint in system.joints:
        a, b = joint.between
        joined[a].add(b)
        joined[b].add(a)
    reached = {surface.part for surface in system.surfaces.values()}
    frontier = list(reached)
    while frontier:
        for other in joined[frontier.pop()] - reached:
            reached.add(other)
            frontier.append(other)
    return [Finding(f"parts.{name}", "no surface and no chain of joints connects it to the ambient; its "
                    "temperature would have no steady state", "error")
            for name in system.parts if name not in reached]


def covers(prefix: str, path: str) -> bool:
    """True when the provenance prefix ``prefix`` covers the value at ``path``.

    ``[*]`` in a prefix stands for any list index: ``joints[*].area`` covers ``joints[3].area``.
    """
    if "[*]" in prefix:
        pattern = re.escape(prefix).replace(r"\[\*\]", r"\[\d+\]")
        return re.match(pattern + r"(\Z|[.\[])", path) is not None
    return path == prefix or path.startswith(prefix + ".") or path.startswith(prefix + "[")


def specificity(prefix: str) -> tuple[int, int]:
    """How precisely a prefix names a value: explicit indices beat wildcards, longer beats shorter."""
    return (prefix.count(".") + prefix.count("[") - 2 * prefix.count("[*]"), len(prefix))


def _provenance(system: FeedSystem) -> list[Finding]:
    """Every value must be accounted for by a [[provenance]] entry (paper or assumption)."""
    # A declared uncertainty carries its own reason (uncertainties.py): it is its provenance.
    data = system.model_dump(exclude={"provenance", "uncertainty"}, exclude_defaults=True)
    prefixes = [p for entry in system.provenance for p in entry.paths]
    uncovered = [path for path in leaf_paths(data) if not any(covers(p, path) for p in prefixes)]
    findings = [Finding(path, "no [[provenance]] entry says where this value comes from") for path in uncovered[:20]]
    if len(uncovered) > 20:
        findings.append(Finding("provenance", f"... and {len(uncovered) - 20} more values without provenance"))
    return findings
