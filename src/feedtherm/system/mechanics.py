"""The mechanical side of a description: how the structure is held and what a displacement sensor reads.

A thermal error is a displacement.  The models turn temperatures into displacements
(thermoelasticity in the FE model, axial bars in the fast model) and read them as declared
here, so that no fitted "read point" stands in for mechanics:

- ``supports``: where the structure is held, and along which machine axes.  A statically
  determinate set (3-2-1: one point held along x, y, z; one along y, z; one along z) removes
  the rigid-body motion and restrains no thermal expansion, so a relative reading does not
  depend on where the supports are.
- each joint's ``release`` (in :class:`~feedtherm.system.schema.Joint`): the machine axes
  along which the joint does not hold (a floating bearing and a guide carriage release
  ``x``); a joint without releases ties its parts.
- ``elongation``: what the elongation D is, a displacement sensor: the displacement of its
  ``target`` point relative to its ``mount`` point along ``direction``,
  ``D = (u(target) − u(mount))·direction``, zero with every part at the reference temperature
  (``temperatures.reference``).  A mount of ``"ground"`` is the frame the supports hold (a
  sensor on a stand of its own).
- ``positioning``: the positioning error E(x, t) along the stroke: the axial displacement of
  the screw under the nut, at every table position x, relative to the position encoder's
  ``reference`` point.

Points are in the machine frame, moving parts at the middle of the stroke, like sensors.
"""

from __future__ import annotations

import math
from typing import Literal

from pydantic import Field, field_validator, model_serializer, model_validator

from .base import Strict
from .quantities import Length

Axis = Literal["x", "y", "z"]
AXES = ("x", "y", "z")
Vector = tuple[Length, Length, Length]

#: The mount of a displacement sensor held by the frame the supports hold.
GROUND = "ground"


def _unique_axes(axes: list[str], what: str) -> list[str]:
    if len(set(axes)) != len(axes):
        raise ValueError(f"{what}: an axis is listed twice ({', '.join(axes)})")
    return sorted(axes, key=AXES.index)


class MaterialPoint(Strict):
    """A point of a part, in the machine frame (a moving part's at the middle of the stroke)."""

    part: str
    point: Vector


class Support(Strict):
    """A part held at a point along the listed machine axes."""

    part: str
    point: Vector
    fix: list[Axis] = Field(min_length=1)
    description: str = ""

    @field_validator("fix")
    @classmethod
    def _axes_once(cls, value: list[str]) -> list[str]:
        return _unique_axes(value, "fix")


class DisplacementSensor(Strict):
    """``(u(target) − u(mount))·direction``: what a displacement sensor reads [m]."""

    target: MaterialPoint
    mount: MaterialPoint | Literal["ground"]
    direction: tuple[float, float, float]
    description: str = ""

    @field_validator("direction")
    @classmethod
    def _unit(cls, value: tuple[float, float, float]) -> tuple[float, float, float]:
        norm = math.sqrt(sum(c * c for c in value))
        if not norm > 1e-12:
            raise ValueError("must not be the zero vector")
        return tuple(c / norm for c in value)

    @property
    def axis(self) -> int | None:
        """Index of the machine axis the direction lies along (either sense), or None if oblique."""
        for i, c in enumerate(self.direction):
            if abs(abs(c) - 1.0) < 1e-12:
                return i
        return None


class Positioning(Strict):
    """The positioning error along the stroke, relative to the position encoder's reference point."""

    reference: MaterialPoint
    description: str = ""


class Mechanics(Strict):
    supports: list[Support] = Field(min_length=1)
    elongation: DisplacementSensor
    #: Required with a feed drive and refused without one (the screw under the nut is what it reads).
    positioning: Positioning | None = None
    #: Tie stiffness of a joint per unit area, as a multiple of the stiffer side's Young's
    #: modulus over the integrating side's element size (FE model; docs/fem-model.md).
    tie_penalty: float = Field(default=100.0, gt=1.0, le=1e6)
    #: The FE model's displacement elements: "linear" tetrahedra (4 nodes, the thermal mesh's
    #: own space) or "quadratic" (10 nodes: bending converges an order faster, for about seven
    #: times the unknowns; docs/fem-model.md). The fast and reduced models' bars do not use it.
    elements: Literal["linear", "quadratic"] = "linear"

    @model_serializer(mode="wrap")
    def _omit_no_positioning(self, handler):
        data = handler(self)  # TOML has no null: a system without a feed drive leaves it out
        if isinstance(data, dict) and data.get("positioning", 0) is None:
            del data["positioning"]
        return data

    @model_validator(mode="after")
    def _supports_once(self) -> "Mechanics":
        seen = set()
        for i, support in enumerate(self.supports):
            key = (support.part, support.point)
            if key in seen:
                raise ValueError(f"supports[{i}]: the same point of {support.part!r} is declared twice; "
                                 "list every axis it holds in one fix")
            seen.add(key)
        return self


def _where(point: MaterialPoint | str) -> str:
    if isinstance(point, str):
        return point
    return f"{point.part} at ({', '.join(f'{c * 1e3:g}' for c in point.point)}) mm"


def loop_summary(mechanics: Mechanics) -> dict:
    """What D and the positioning error are, in words and millimetres (for summaries and reports)."""
    sensor = mechanics.elongation
    return {"elongation": {"target": _where(sensor.target), "mount": _where(sensor.mount),
                           "direction": [round(c, 6) for c in sensor.direction], "description": sensor.description},
            "positioning_reference": None if mechanics.positioning is None else _where(mechanics.positioning.reference)}


def joint_holds(release: list[str]) -> list[int]:
    """Indices of the machine axes a joint with ``release`` holds."""
    return [i for i, axis in enumerate(AXES) if axis not in release]


__all__ = ["AXES", "Axis", "DisplacementSensor", "GROUND", "MaterialPoint", "Mechanics", "Positioning", "Support",
           "joint_holds", "loop_summary"]
