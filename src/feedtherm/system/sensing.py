"""How a compensation study's sensors read: the kinds that may be mounted, each kind's noise and offset.

A description's optional ``[compensation]`` section overrides the defaults of
:mod:`feedtherm.analysis.compensation.noise` (where each default is declared with its reason)::

    [compensation]
    kinds = ["contact", "infrared"]   # the sensor kinds that may be mounted (default: both)

    [compensation.infrared]
    noise = "0.2 K"                   # white noise, standard deviation, per reading
    offset = "1 K"                    # fixed bias of one sensor on one machine, standard deviation
    reason = "pyrometer X, stated accuracy ±2 K (a 2-sigma bound), repeatability 0.2 K"

A kind is ``contact`` (a PT100 or thermocouple glued to a part that stays still: its wires cannot
follow a moving or turning part) or ``infrared`` (a pyrometer on the machine's frame, reading a
moving or turning surface without contact).  A value given needs a reason, as every assumption
of a description does.  Values are temperature differences, never negative.
"""

from __future__ import annotations

from typing import Literal

from pydantic import field_validator, model_validator

from .base import Strict
from .quantities import NonNegTemperatureDifference

#: The sensor kinds a compensation study knows.
SENSOR_KINDS = ("contact", "infrared")


class KindNoise(Strict):
    """One kind's noise [K] (white, standard deviation per reading) and offset [K] (standard
    deviation of a sensor's fixed bias, drawn once per machine); either left out keeps its default."""

    noise: NonNegTemperatureDifference | None = None
    offset: NonNegTemperatureDifference | None = None
    reason: str = ""

    @model_validator(mode="after")
    def _values_have_reasons(self) -> "KindNoise":
        if (self.noise is not None or self.offset is not None) and not self.reason.strip():
            raise ValueError("reason: a declared noise or offset needs a reason (a data sheet, a calibration)")
        return self


class Compensation(Strict):
    kinds: list[Literal["contact", "infrared"]] = list(SENSOR_KINDS)
    contact: KindNoise = KindNoise()
    infrared: KindNoise = KindNoise()

    @field_validator("kinds")
    @classmethod
    def _kinds(cls, value: list[str]) -> list[str]:
        if not value:
            raise ValueError("name at least one sensor kind (contact, infrared)")
        if len(set(value)) != len(value):
            raise ValueError(f"a kind is listed twice ({', '.join(value)})")
        return value
