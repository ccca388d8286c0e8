"""Consistency checks of a valid description: what ``feedtherm check`` lists.

A description that loads is valid; these findings are warnings about its content: a stated
feed speed that its motor speeds contradict, a value no provenance entry accounts for, a
sensor outside its part, a joint between parts that do not touch, and so on.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

from ..constants import AMBIENT_SENSOR
from ..physics.mechanics import speed_table
from .geometry import contains, gap, screw_axis, surface_area
from .schema import FeedSystem

_RAD_PER_S_TO_RPM = 60.0 / (2.0 * math.pi)
#: Relative tolerance on a stated feed speed against (n_s - n_n) * lead.
FEED_SPEED_TOLERANCE = 0.02
#: Distance [m] below which two parts are taken to touch.
TOUCH_TOLERANCE = 1e-3


@dataclass(frozen=True)
class Finding:
    path: str
    message: str

    def __str__(self) -> str:
        return f"{self.path}: {self.message}"


def check_system(system: FeedSystem) -> list[Finding]:
    """Every inconsistency found in ``system`` (an empty list when there is none)."""
    return [
        *_feed_speeds(system),
        *_geometry(system),
        *_provenance(system),
    ]


def _feed_speeds(system: FeedSystem) -> list[Finding]:
    findings = []
    lead = system.kinematics.lead
    for name, cond in system.conditions.items():
        if cond.feed_speed is None:
            continue
        n_s, n_n = cond.screw_speed * _RAD_PER_S_TO_RPM, cond.nut_speed * _RAD_PER_S_TO_RPM
        implied = abs(speed_table(n_s, n_n, lead))
        stated = abs(cond.feed_speed)
        if not math.isclose(implied, stated, rel_tol=FEED_SPEED_TOLERANCE):
            lead_implied = stated / abs((n_s - n_n) / 60.0) if n_s != n_n else math.inf
            findings.append(Finding(
                f"conditions.{name}.feed_speed",
                f"stated {stated * 60:.3g} m/min, but the motor speeds give "
                f"({n_s:.0f} - {n_n:.0f}) rpm x {lead * 1e3:g} mm = {implied * 60:.3g} m/min "
                f"(the stated speed implies a lead of {lead_implied * 1e3:.3g} mm); the motor speeds are used",
            ))
    return findings


def _geometry(system: FeedSystem) -> list[Finding]:
    findings = []
    parts = system.parts
    for name, sensor in system.sensors.items():
        if not contains(parts[sensor.part], sensor.position):
            findings.append(Finding(f"sensors.{name}.position", f"lies outside part {sensor.part!r}"))
    for i, joint in enumerate(system.joints):
        a, b = joint.between
        distance = gap(parts[a], parts[b])
        if distance > TOUCH_TOLERANCE:
            findings.append(Finding(f"joints[{i}]", f"{a!r} and {b!r} do not touch ({distance * 1e3:.1f} mm apart)"))
    for name, surface in system.surfaces.items():
        try:
            area = surface_area(surface, parts[surface.part])
        except (ValueError, IndexError) as exc:
            findings.append(Finding(f"surfaces.{name}.faces", str(exc)))
            continue
        if area <= 0.0:
            findings.append(Finding(f"surfaces.{name}", f"has no area ({area:g} m^2)"))
    screw = screw_axis(parts[system.kinematics.screw])
    for key in ("fixed_at", "read_at"):
        x = getattr(system.elongation, key)
        if not screw.start <= x <= screw.end:
            findings.append(Finding(f"elongation.{key}", f"x = {x * 1e3:g} mm is not on the screw ({screw.start * 1e3:g}..{screw.end * 1e3:g} mm)"))
    if AMBIENT_SENSOR in system.sensors:
        findings.append(Finding(f"sensors.{AMBIENT_SENSOR}",
                                f"{AMBIENT_SENSOR} is the ambient temperature; a declared {AMBIENT_SENSOR} is ignored"))
    return findings


def leaf_paths(data, prefix: str = "") -> list[str]:
    """Dotted paths of every value in nested dicts/lists (lists of scalars are leaves)."""
    if isinstance(data, dict):
        paths = []
        for key, value in data.items():
            paths.extend(leaf_paths(value, f"{prefix}.{key}" if prefix else str(key)))
        return paths
    if isinstance(data, list) and any(isinstance(v, (dict, list)) for v in data):
        paths = []
        for i, value in enumerate(data):
            paths.extend(leaf_paths(value, f"{prefix}[{i}]"))
        return paths
    return [prefix]


def covers(prefix: str, path: str) -> bool:
    """True when the provenance prefix ``prefix`` covers the value at ``path``.

    ``[*]`` in a prefix stands for any list index: ``joints[*].area`` covers ``joints[3].area``.
    """
    if "[*]" in prefix:
        pattern = re.escape(prefix).replace(r"\[\*\]", r"\[\d+\]")
        return re.match(pattern + r"($|[.\[])", path) is not None
    return path == prefix or path.startswith(prefix + ".") or path.startswith(prefix + "[")


def specificity(prefix: str) -> tuple[int, int]:
    """How precisely a prefix names a value: explicit indices beat wildcards, longer beats shorter."""
    return (prefix.count(".") + prefix.count("[") - 2 * prefix.count("[*]"), len(prefix))


def _provenance(system: FeedSystem) -> list[Finding]:
    """Every value must be accounted for by a [[provenance]] entry (paper or assumption)."""
    data = system.model_dump(exclude={"provenance"}, exclude_defaults=True)
    prefixes = [p for entry in system.provenance for p in entry.paths]
    uncovered = [path for path in leaf_paths(data) if not any(covers(p, path) for p in prefixes)]
    findings = [Finding(path, "no [[provenance]] entry says where this value comes from") for path in uncovered[:20]]
    if len(uncovered) > 20:
        findings.append(Finding("provenance", f"... and {len(uncovered) - 20} more values without provenance"))
    return findings
