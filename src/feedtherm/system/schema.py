"""Typed description of a feed system, validated once when it is loaded.

Coordinates: a right-handed machine frame, x along the screw axis, z up, in metres.
Parts that move with the table (``moving = true``) are declared at the middle of the
stroke; the moving group travels ``±stroke/2`` along x from there.

Nothing here assumes a particular bench: parts, sources and surfaces are named freely and
cross-referenced by name; the kinematics section names which part is the screw and which
the nut.  The canonical names of the paper's bench are listed in ``names.py``.
"""

from __future__ import annotations

import re
from typing import Annotated, Literal

from pydantic import (
    Field,
    StrictBool,
    StringConstraints,
    field_validator,
    model_serializer,
    model_validator,
)

from .base import ParameterPaths, Strict
from .mechanics import Axis, Mechanics
from .quantities import (
    AngularSpeed,
    Length,
    NonNegSpeed,
    NonNegLength,
    PosArea,
    PosConductivity,
    PosContactResistance,
    PosDensity,
    PosDisplacement,
    PosDuration,
    PosExpansion,
    PosHeatTransferCoefficient,
    PosLength,
    PosModulus,
    PosSpecificHeat,
    PosTemperatureDifference,
    Power,
    Speed,
    Temperature,
)
from .references import check_references
from .sources import (
    HeatSource,
)
from .surfaces import (
    Surface,
)
from .uncertainties import Uncertainty
from .cycles import DutyCycle, DutySegment, MeasuringStops  # noqa: F401 (part of the schema)
from .sensing import Compensation
from .thermal_tests import ThermalTest

_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_]*\Z")  # \Z: "$" would let a trailing newline through
#: Length of a run when nothing else says [s]: the paper's 10,800 s (§4.3).
DEFAULT_DURATION_S = 10800.0


# --------------------------------------------------------------------------- materials


class Material(Strict):
    density: PosDensity
    conductivity: PosConductivity
    specific_heat: PosSpecificHeat
    expansion: PosExpansion
    youngs_modulus: PosModulus | None = None
    poisson_ratio: Annotated[float, Field(gt=0.0, lt=0.5)] | None = None
    name: str = ""


# --------------------------------------------------------------------------- geometry

Vector = tuple[Length, Length, Length]
PosVector = tuple[PosLength, PosLength, PosLength]


class Box(Strict):
    """Axis-aligned block: ``origin`` is its corner of smallest x, y, z."""

    origin: Vector
    size: PosVector


class Cylinder(Strict):
    """Solid or hollow cylinder; ``origin`` is the centre of its face of smallest coordinate."""

    origin: Vector
    axis: Literal["x", "y", "z"] = "x"
    length: PosLength
    outer_diameter: PosLength
    inner_diameter: NonNegLength = 0.0

    @model_validator(mode="after")
    def _bore_inside(self) -> "Cylinder":
        if self.inner_diameter >= self.outer_diameter:
            raise ValueError("inner_diameter must be smaller than outer_diameter")
        return self


class Part(Strict):
    material: str
    boxes: list[Box] = []
    cylinders: list[Cylinder] = []
    holes: list[Cylinder] = []  # bores cut out of the boxes (e.g. a bearing seat)
    moving: StrictBool = False  # true or false only: "yes", "off" and 1 are refused
    #: The FE mesh puts this many times more elements across the part than its density's rule
    #: (models/fem/geometry.py; the screw's own factor comes on top): a part whose field a study
    #: resolves finely.  The fast model does not use it.
    mesh_refinement: float = Field(default=1.0, ge=0.25, le=8.0)
    description: str = ""

    @model_serializer(mode="wrap")
    def _omit_the_default_refinement(self, handler):
        # Left out at its default, so that descriptions written before it existed keep their
        # serialised form and hash (the benches' frozen provenance).
        data = handler(self)
        if isinstance(data, dict) and data.get("mesh_refinement") == 1.0:
            del data["mesh_refinement"]
        return data

    @model_validator(mode="after")
    def _has_geometry(self) -> "Part":
        if not self.boxes and not self.cylinders:
            raise ValueError("a part needs at least one box or cylinder")
        return self


# --------------------------------------------------------------------------- joints


class Joint(Strict):
    """Contact between two parts: thermal conductance = area / tcr; mechanically a tie.

    ``release`` lists the machine axes along which the joint does not hold its parts together
    (a floating bearing, a guide carriage: ``["x"]``); the other axes are tied.  ``area`` left
    out is the contact area of the drawn geometry, filled in when the description is loaded
    (:func:`feedtherm.system.areas.with_joint_areas`).
    """

    between: tuple[str, str]
    tcr: PosContactResistance
    area: PosArea | None = None
    sliding: StrictBool = False  # the contact travels with the table (nut-screw, slider-rail)
    release: list[Axis] = []
    #: A press fit: the two parts are drawn overlapping on purpose (an interference), which
    #: ``check`` otherwise refuses (system/topology.py).
    fit: StrictBool = False
    description: str = ""

    @field_validator("release")
    @classmethod
    def _axes_once(cls, value: list[str]) -> list[str]:
        if len(set(value)) != len(value):
            raise ValueError(f"an axis is listed twice ({', '.join(value)})")
        return sorted(value, key="xyz".index)

    @model_serializer(mode="wrap")
    def _omit_no_release(self, handler):
        data = handler(self)
        if isinstance(data, dict) and not self.release:
            data.pop("release", None)  # a tie: descriptions that predate releases keep their form
        if isinstance(data, dict) and not self.fit:
            data.pop("fit", None)  # likewise a joint that is no press fit
        return data


# --------------------------------------------------------------------------- sensors


class Sensor(Strict):
    part: str
    position: Vector  # machine frame; for moving parts, at the middle of the stroke
    method: Literal["contact", "infrared"] = "contact"
    description: str = ""


# --------------------------------------------------------------------------- kinematics


class Kinematics(Strict):
    drive: Literal["dual", "single"]
    screw: str  # part names
    nut: str
    lead: PosLength
    stroke: PosLength
    reversal: Literal["both_reverse"] = "both_reverse"


def feed_drive(system: "FeedSystem", needed_by: str) -> Kinematics:
    """The system's feed drive; a one-line :class:`~feedtherm.errors.FeedthermError` naming
    ``needed_by`` (a command or study) for a system without one."""
    if system.kinematics is None:
        from ..errors import FeedthermError

        raise FeedthermError(f"{needed_by} needs a feed drive, and {system.meta.name!r} has none ([kinematics] is "
                             "left out): it varies motor speeds and reads the screw")
    return system.kinematics


class Temperatures(Strict):
    """Initial and reference temperatures, and how temperature-dependent values are taken.

    ``coupling = "frozen"`` (the paper's assumption 3): every CHTC, radiative coefficient,
    lubricant viscosity and winding resistance is taken once, at ambient +
    ``convection_delta_t``.  ``"nonlinear"``: the models evaluate them at each surface's and
    each source's simulated temperature and iterate with it, in transient and steady runs.
    """

    initial: Literal["ambient"] | Temperature = "ambient"
    reference: Temperature  # zero-strain temperature: every displacement and its sensors read 0 there
    convection_delta_t: PosTemperatureDifference  # frozen CHTCs are taken at this rise
    coupling: Literal["frozen", "nonlinear"] = "frozen"


class Room(Strict):
    """The air around the machine.

    ``air_speed``: the mean speed of the room's air past the machine (an air-conditioned room's
    draught, say 0.1-0.3 m/s); it adds forced convection to every surface whose CHTC comes from
    a correlation (mixed convection, boundary/surfaces.py).  0: still air, convection only from
    buoyancy and the machine's own motion.

    ``ambient_sensor``: the name the air's temperature goes by among the sensors' readings (in
    runs, measurements and compensation laws); every model reports it from the boundary
    conditions, so it is not declared under ``[sensors]``.
    """

    air_speed: NonNegSpeed = 0.0
    ambient_sensor: Annotated[str, StringConstraints(pattern=r"^[A-Za-z_][A-Za-z0-9_.-]*$")] = "ambient"


class Condition(Strict):
    screw_speed: AngularSpeed = 0.0  # signed; a system without a feed drive leaves it out
    nut_speed: AngularSpeed = 0.0
    ambient: Temperature
    feed_speed: Speed | None = None  # as stated by the source; checked, never used
    duration: PosDuration = DEFAULT_DURATION_S
    description: str = ""


# --------------------------------------------------------------------------- calibration


class CalibrationParameter(Strict):
    """A value (or a group of values scaled together) that calibration may fit, within bounds.

    ``kind = "value"``: the parameter is the value at every path (they share it); bounds are
    quantities in the values' units.  ``kind = "scale"``: the parameter is a factor on the
    original values at the paths; bounds are factors.  Paths may use ``[*]`` for any index.
    """

    kind: Literal["value", "scale"]
    paths: ParameterPaths
    bounds: tuple[str | float, str | float]
    description: str = ""


class Calibration(Strict):
    parameters: dict[str, CalibrationParameter]
    temperature_sigma: PosTemperatureDifference = 0.5  # weights of the residuals
    elongation_sigma: PosDisplacement = 2e-6
    equilibrium_sigma: PosDuration = 600.0  # of a stated equilibrium time [s]

    @model_serializer(mode="wrap")
    def _omit_the_default_equilibrium_sigma(self, handler):
        # Left out at its default, so that descriptions written before it existed keep their
        # serialised form and hash (the benches' frozen provenance).
        data = handler(self)
        if isinstance(data, dict) and data.get("equilibrium_sigma") == 600.0:
            del data["equilibrium_sigma"]
        return data


# --------------------------------------------------------------------------- provenance


class Provenance(Strict):
    """Where a group of values comes from.  ``paths`` are dotted prefixes of the description."""

    paths: list[str]
    origin: Literal["paper", "assumption"]
    source: str
    reason: str = ""

    @model_validator(mode="after")
    def _assumptions_have_reasons(self) -> "Provenance":
        if self.origin == "assumption" and not self.reason.strip():
            raise ValueError("an assumption needs a reason")
        return self


class Meta(Strict):
    name: str
    title: str
    reference: str = ""
    description: str = ""
    measurements: str = ""  # "bundled:<name>" or a CSV path relative to this file
    overlay: str = ""  # printed values to lay over the physics: "bundled:<name>" or a path (system/overlay.py)


# --------------------------------------------------------------------------- the system


class FeedSystem(Strict):
    meta: Meta
    materials: dict[str, Material]
    parts: dict[str, Part]
    joints: list[Joint]
    sources: dict[str, HeatSource]
    surfaces: dict[str, Surface]
    sensors: dict[str, Sensor]
    #: The feed drive: which part is the screw, which the nut, lead and stroke.  Left out, the
    #: system has none: nothing moves or turns, every source is ``fixed`` (a test piece, a
    #: housing on its own; docs/system-description.md, *A system without a feed drive*).
    kinematics: Kinematics | None = None
    mechanics: Mechanics
    temperatures: Temperatures
    room: Room = Room()
    conditions: dict[str, Condition]
    duty_cycles: dict[str, DutyCycle] = {}
    #: What a machine's owner runs and logs (system/thermal_tests.py): a condition or duty cycle, the
    #: state it starts from and the room it runs in, with the measurements taken.
    tests: dict[str, ThermalTest] = {}
    calibration: Calibration | None = None
    uncertainty: Uncertainty | None = None
    #: How a compensation study's sensors read (system/sensing.py): the kinds that may be
    #: mounted and each kind's noise and offset; left out, the defaults declared there.
    compensation: Compensation | None = None
    provenance: list[Provenance] = []

    @model_serializer(mode="wrap")
    def _omit_a_still_room(self, handler):
        # ``room`` left at its default (still air) is left out, so that descriptions written
        # before it existed keep their serialised form and hash (the benches' frozen provenance).
        # Likewise a source's heat_factor at 1 (added for perturbation studies).
        data = handler(self)
        if isinstance(data, dict) and self.room == Room():
            data.pop("room", None)
        if isinstance(data, dict) and self.uncertainty is None:
            data.pop("uncertainty", None)  # likewise: descriptions without declared uncertainties
        if isinstance(data, dict) and self.compensation is None:
            data.pop("compensation", None)  # likewise: descriptions without sensor-noise settings
        if isinstance(data, dict) and not self.tests:
            data.pop("tests", None)  # likewise: descriptions without declared tests
        if isinstance(data, dict) and self.kinematics is None:
            data.pop("kinematics", None)  # TOML has no null: a system without a feed drive leaves it out
        if isinstance(data, dict) and isinstance(data.get("sources"), dict):
            for name, source in data["sources"].items():
                if isinstance(source, dict) and source.get("heat_factor") == 1.0 and self.sources[name].heat_factor == 1.0:
                    del source["heat_factor"]
                if isinstance(source, dict) and "through" in source and source["through"] is None:
                    del source["through"]  # likewise a source whose heat enters its own parts
        return data

    @field_validator("tests")
    @classmethod
    def _names_are_identifiers_if_any(cls, value: dict) -> dict:
        for name in value:
            if not _NAME.match(name):
                raise ValueError(f"{name!r} is not a valid name (letters, digits, underscores)")
        return value

    @field_validator("materials", "parts", "sources", "surfaces", "sensors", "conditions")
    @classmethod
    def _names_are_identifiers(cls, value: dict) -> dict:
        for name in value:
            if not _NAME.match(name):
                raise ValueError(f"{name!r} is not a valid name (letters, digits, underscores)")
        if not value:
            raise ValueError("must not be empty")
        return value

    @model_validator(mode="after")
    def _references_resolve(self) -> "FeedSystem":
        check_references(self)
        return self
