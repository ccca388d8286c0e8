"""Convective surfaces of a description and the ways their coefficient is found."""

from __future__ import annotations

from typing import Annotated, Literal, Union

from pydantic import (
    Field,
    model_validator,
)

from .base import Strict
from .quantities import (
    PosArea,
    PosFactor,
    PosHeatTransferCoefficient,
    PosLength,
    Temperature,
)
from .sources import ShaftName

# --------------------------------------------------------------------------- convection


class NaturalConvection(Strict):
    kind: Literal["natural"]
    orientation: Literal["horizontal_cylinder", "vertical_plate", "horizontal_plate_up", "horizontal_plate_down"]
    length: PosLength


class RotatingConvection(Strict):
    """Rotating cylinder (Eq. 27) at a shaft's speed, combined with natural convection."""

    kind: Literal["rotating"]
    shaft: ShaftName
    diameter: PosLength


class MovingPlateConvection(Strict):
    """Surface parallel to the table's motion (Eq. 28, plate average), mixed with natural."""

    kind: Literal["moving_plate"]
    length: PosLength  # along the motion
    orientation: Literal["vertical_plate", "horizontal_plate_up", "horizontal_plate_down"]
    natural_length: PosLength


class MovingFaceConvection(Strict):
    """Face normal to the table's motion (Eq. 29), mixed with natural."""

    kind: Literal["moving_face"]
    length: PosLength
    natural_length: PosLength


class FixedConvection(Strict):
    """A coefficient stated directly: a measured film coefficient, a coolant, a textbook case."""

    kind: Literal["fixed"]
    coefficient: PosHeatTransferCoefficient


Convection = Annotated[
    Union[NaturalConvection, RotatingConvection, MovingPlateConvection, MovingFaceConvection, FixedConvection],
    Field(discriminator="kind"),
]

FaceSelector = Literal["+x", "-x", "+y", "-y", "+z", "-z", "lateral", "ends", "bore"]


class Surface(Strict):
    """A convective surface: faces of one part's primitives, or an explicit area."""

    part: str
    faces: list[FaceSelector]
    boxes: list[int] | None = None  # indices of the part's boxes (default: all)
    cylinders: list[int] | None = None  # indices of the part's cylinders (default: all)
    convection: Convection
    emissivity: Annotated[float, Field(ge=0.0, le=1.0)]  # 0: no radiation
    area: PosArea | None = None  # overrides the area computed from the faces
    chtc_factor: PosFactor = 1.0  # multiplies the convective coefficient (set by calibration); 0.01 to 100
    # The medium this surface exchanges heat with, when it is not the ambient air (a coolant, a
    # clamped face held at a temperature); only with a fixed coefficient, as the air correlations
    # are for the ambient air.
    sink_temperature: Temperature | None = None
    description: str = ""

    @model_validator(mode="after")
    def _sink_needs_a_fixed_coefficient(self) -> "Surface":
        if self.sink_temperature is not None and self.convection.kind != "fixed":
            raise ValueError("sink_temperature: only a surface with convection.kind = 'fixed' may exchange heat "
                             "with a medium other than the ambient air")
        return self
