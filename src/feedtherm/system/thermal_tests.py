"""Tests: what a machine's owner runs and logs, declared beside the conditions.

A test names what the machine did (a condition, or a duty cycle with its repeats and measuring
stops), the state it started from and the room it ran in; its measurements are the file its
``measurements`` names, or the description's.  A condition is the simplest test: it starts from
``temperatures.initial`` in a room at its own ambient.  Every command that takes a condition
takes a test by its name (docs/tests.md).

``start``:

- ``"ambient"``: uniform at the room's air temperature at t = 0 (a machine left standing long enough);
- a temperature (``"25 degC"``): uniform at it;
- ``{ soaked = "NAME" }``: the end state of another test, condition or duty cycle, run first
  from its own start (a machine that has just done that);
- ``"measured"``: the field that matches the test's measured temperatures at t = 0 (the steady
  field a heat at each sensor would hold, the room's air at its first reading: ``plan.py``).

``room``:

- ``"declared"``: the air of the condition or of each segment of the cycle;
- a temperature: the air throughout;
- ``"measured"``: the air as the test's measurements log it (the quantity ``room.ambient_sensor``),
  linear between samples and held beyond the first and the last.  The surfaces' coefficients are
  taken at the log's mean air temperature; the sinks follow the log at every time step.
"""

from __future__ import annotations

from typing import Literal

from pydantic import Field, model_serializer, model_validator

from .base import Strict
from .quantities import PosDuration, Temperature


class Soak(Strict):
    """The end state of another run: a test, a condition or a duty cycle of the description, by name."""

    soaked: str = Field(min_length=1)


Start = Literal["ambient", "measured"] | Soak | Temperature
Room = Literal["declared", "measured"] | Temperature


class ThermalTest(Strict):
    """A test: a condition or a duty cycle, from a declared start, in a declared room (module notes)."""

    condition: str | None = None
    cycle: str | None = None
    #: Default: the condition's duration, or the cycle's whole profile (its repeats and stops).
    duration: PosDuration | None = None
    start: Start = "ambient"
    room: Room = "declared"
    #: A measurement file (relative to the description's folder) or ``bundled:<bench>``; empty: the
    #: description's own (``meta.measurements``, else its bench's).
    measurements: str = ""
    description: str = ""

    @model_validator(mode="after")
    def _one_profile(self) -> "ThermalTest":
        if (self.condition is None) == (self.cycle is None):
            raise ValueError("give exactly one of condition and cycle: what the machine did during the test")
        return self

    @model_serializer(mode="wrap")
    def _omit_unset(self, handler):
        data = handler(self)  # TOML has no null
        if isinstance(data, dict):
            for key in ("condition", "cycle", "duration"):
                if data.get(key, 0.0) is None:
                    del data[key]
        return data

    @property
    def profile(self) -> str:
        """The condition's or the duty cycle's name."""
        return self.condition if self.condition is not None else self.cycle

    @property
    def needs_measurements(self) -> bool:
        """Whether planning the test reads its measurements (a measured room or start)."""
        return self.room == "measured" or self.start == "measured"
