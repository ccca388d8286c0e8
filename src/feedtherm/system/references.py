"""Cross-references inside a description: every name used must be declared.

Raised errors start with the dotted path of the offending field and, where a name is
unknown, suggest the closest declared one.

The schema runs :func:`check_references` as the validator of its
:class:`~feedtherm.system.schema.FeedSystem`; so that the dependency runs one way, the rules
here take that description (``system``) without importing its class.
"""

from __future__ import annotations

import difflib
from typing import Iterable

from .thermal_tests import Soak


def closest(name: str, candidates: Iterable[str]) -> str:
    """``"; did you mean 'x'?"`` for the closest candidate, or an empty string."""
    match = difflib.get_close_matches(name, list(candidates), n=1, cutoff=0.6)
    return f"; did you mean {match[0]!r}?" if match else ""


def _require(kind: str, name: str, declared: dict, path: str) -> None:
    if name not in declared:
        raise ValueError(f"{path}: no {kind} named {name!r}{closest(name, declared)}")


def check_references(system) -> None:
    """Raise ``ValueError("<path>: <reason>")`` for the first dangling reference of ``system`` (a FeedSystem)."""
    parts, sources, surfaces = system.parts, system.sources, system.surfaces
    for name, part in parts.items():
        _require("material", part.material, system.materials, f"parts.{name}.material")
    for i, joint in enumerate(system.joints):
        a, b = joint.between
        for side in (a, b):
            _require("part", side, parts, f"joints[{i}].between")
        if a == b:
            raise ValueError(f"joints[{i}].between: a joint needs two different parts, got {a!r} twice")
    joined = {frozenset(j.between) for j in system.joints}
    for name, source in sources.items():
        for target in source.into:
            _require("part", target, parts, f"sources.{name}.into")
        if source.through is not None:
            _require("part", source.through, parts, f"sources.{name}.through")
            if source.through in source.into:
                raise ValueError(f"sources.{name}.through: {source.through!r} is also in into; the part the heat "
                                 "arises in only conducts it to the parts in into")
            for target in source.into:
                if frozenset((target, source.through)) not in joined:
                    raise ValueError(f"sources.{name}.into: {target!r} is not joined to {source.through!r} (through), "
                                     "so the heat cannot enter over their contact")
    for name, surface in surfaces.items():
        _require("part", surface.part, parts, f"surfaces.{name}.part")
    for name, sensor in system.sensors.items():
        _require("part", sensor.part, parts, f"sensors.{name}.part")
    kin = system.kinematics
    if kin is None:
        _check_without_feed_drive(system)
    else:
        _require("part", kin.screw, parts, "kinematics.screw")
        _require("part", kin.nut, parts, "kinematics.nut")
        screw = parts[kin.screw]
        if screw.boxes or len(screw.cylinders) != 1 or screw.cylinders[0].axis != "x":
            raise ValueError("kinematics.screw: the screw must be a single cylinder along x")
        if screw.moving:
            raise ValueError(f"parts.{kin.screw}.moving: the screw is axially fixed; it cannot move with the table")
        if not parts[kin.nut].moving:
            raise ValueError(f"parts.{kin.nut}.moving: the nut travels with the table; set moving = true")
        if kin.drive == "single":
            _check_single_drive(system)
        _check_speeds_given(system)
    _check_mechanics(system)
    _check_tests(system)


def _check_tests(system) -> None:
    """A test names a declared condition or duty cycle, and a soaked start one that does not lead back to it."""
    for name, cycle in system.duty_cycles.items():
        if cycle.ambient is None:
            for i, segment in enumerate(cycle.segments):
                if segment.ambient is None:
                    raise ValueError(f"duty_cycles.{name}.segments[{i}].ambient: give the air's temperature here or "
                                     f"for the whole cycle (duty_cycles.{name}.ambient)")
    runs = {**system.conditions, **system.duty_cycles, **system.tests}
    for name, test in system.tests.items():
        path = f"tests.{name}"
        if name in system.conditions or name in system.duty_cycles:
            raise ValueError(f"{path}: the name is taken by a {'condition' if name in system.conditions else 'duty cycle'}; "
                             "commands take a test or a condition by its name, so each name must be one run's")
        if test.condition is not None:
            _require("condition", test.condition, system.conditions, f"{path}.condition")
        else:
            _require("duty cycle", test.cycle, system.duty_cycles, f"{path}.cycle")
        if isinstance(test.start, Soak):
            _require("test, condition or duty cycle", test.start.soaked, runs, f"{path}.start.soaked")
            chain, current = [name], test.start
            while isinstance(current, Soak) and current.soaked in system.tests:
                if current.soaked in chain:
                    raise ValueError(f"{path}.start.soaked: the soaks lead back to themselves "
                                     f"({' -> '.join([*chain, current.soaked])})")
                chain.append(current.soaked)
                current = system.tests[current.soaked].start


def _check_mechanics(system) -> None:
    mech, parts = system.mechanics, system.parts
    for i, support in enumerate(mech.supports):
        _require("part", support.part, parts, f"mechanics.supports[{i}].part")
    sensor = mech.elongation
    _require("part", sensor.target.part, parts, "mechanics.elongation.target.part")
    if not isinstance(sensor.mount, str):
        _require("part", sensor.mount.part, parts, "mechanics.elongation.mount.part")
    if system.kinematics is None:
        if mech.positioning is not None:
            raise ValueError(f"mechanics.positioning: {_NO_DRIVE}; the positioning error is the screw's displacement "
                             "under the nut, so leave it out")
    elif mech.positioning is None:
        raise ValueError("mechanics.positioning: a feed drive needs the positioning error's reference point "
                         "(the position encoder's; docs/system-description.md)")
    else:
        _require("part", mech.positioning.reference.part, parts, "mechanics.positioning.reference.part")


#: How the errors below name a description without [kinematics].
_NO_DRIVE = "the system has no feed drive ([kinematics] is left out)"


def _runs(system):
    """``(path, run)`` of every condition, then every duty-cycle segment, in declared order."""
    for name, condition in system.conditions.items():
        yield f"conditions.{name}", condition
    for name, cycle in system.duty_cycles.items():
        for i, segment in enumerate(cycle.segments):
            yield f"duty_cycles.{name}.segments[{i}]", segment


def _check_without_feed_drive(system) -> None:
    """Without a feed drive nothing moves or turns: no moving part, sliding joint, turning
    source or speed; only ``fixed`` sources and still or natural convection."""
    for name, part in system.parts.items():
        if part.moving:
            raise ValueError(f"parts.{name}.moving: {_NO_DRIVE}, so no part can move with a table")
    for i, joint in enumerate(system.joints):
        if joint.sliding:
            raise ValueError(f"joints[{i}].sliding: {_NO_DRIVE}, so no contact slides")
    for name, source in system.sources.items():
        if source.model != "fixed":
            raise ValueError(f"sources.{name}.model: a {source.model!r} source runs with a feed drive and {_NO_DRIVE}; "
                             "give its heat as a 'fixed' source")
    for name, surface in system.surfaces.items():
        kind = surface.convection.kind
        if kind in ("rotating", "moving_plate", "moving_face"):
            raise ValueError(f"surfaces.{name}.convection.kind: {kind!r} convection needs a turning or moving part and "
                             f"{_NO_DRIVE}")
    for path, run in _runs(system):
        for field in ("screw_speed", "nut_speed"):
            if getattr(run, field) != 0.0:
                raise ValueError(f"{path}.{field}: {_NO_DRIVE}; leave the speed out")


def _check_speeds_given(system) -> None:
    """With a feed drive a condition or segment states its screw speed: it defaults to 0 only so
    that a system without a drive can leave it out, and a forgotten speed is not a standstill."""
    for path, run in _runs(system):
        if "screw_speed" not in run.model_fields_set:
            raise ValueError(f"{path}.screw_speed: missing (required with a feed drive; 0 rpm for a standstill)")


def _check_single_drive(system) -> None:
    """A single drive has no nut motor: nothing may turn with the nut."""
    for path, run in _runs(system):
        if run.nut_speed != 0.0:
            raise ValueError(f"{path}.nut_speed: a single drive has no nut motor; the nut speed must be 0 rpm")
    for name, source in system.sources.items():
        if getattr(source, "shaft", None) == "nut":
            raise ValueError(f"sources.{name}.shaft: a single drive has no rotating nut")
    for name, surface in system.surfaces.items():
        if getattr(surface.convection, "shaft", None) == "nut":
            raise ValueError(f"surfaces.{name}.convection.shaft: a single drive has no rotating nut")
