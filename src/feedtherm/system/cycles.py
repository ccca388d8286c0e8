"""Duty cycles in a description: segments of constant operating point, their repeats and the
measuring stops of an ISO 230-3 drift test (docs/tests.md)."""

from __future__ import annotations

from pydantic import Field, field_validator, model_serializer, model_validator

from .base import Strict
from .quantities import AngularSpeed, Length, NonNegDuration, PosDuration, Temperature


class DutySegment(Strict):
    """From ``start`` until the next segment's start, constant motor speeds and ambient.

    ``ambient`` left out is the cycle's (:attr:`DutyCycle.ambient`), or the room's of a test that runs
    the cycle (:class:`~feedtherm.system.thermal_tests.ThermalTest`).  ``table_at``: a standstill with
    the table held at this axis coordinate (the nut's centre along x in the machine frame, as
    ``positioning_error.csv``'s table positions): where a measuring stop holds it.
    """

    start: NonNegDuration
    screw_speed: AngularSpeed = 0.0  # signed; 0 = standstill
    nut_speed: AngularSpeed = 0.0
    ambient: Temperature | None = None
    table_at: Length | None = None

    @model_validator(mode="after")
    def _held_table_stands_still(self) -> "DutySegment":
        if self.table_at is not None and (self.screw_speed != 0.0 or self.nut_speed != 0.0):
            raise ValueError("table_at: the table is held at a position only at a standstill; give both speeds as "
                             "0 rpm, or leave table_at out")
        return self

    @model_serializer(mode="wrap")
    def _omit_unset(self, handler):
        # Left out when not given, so that descriptions written before they existed keep their
        # serialised form and hash (the benches' frozen provenance).
        data = handler(self)
        if isinstance(data, dict):
            for key in ("ambient", "table_at"):
                if data.get(key, 0.0) is None:
                    del data[key]
        return data


class MeasuringStops(Strict):
    """The measuring stops of an ISO 230-3 drift test: the table moved to each target in turn and
    held there ``hold`` while the interferometer reads its position (a standstill)."""

    targets: list[Length] = Field(min_length=1)
    hold: PosDuration

    @field_validator("targets")
    @classmethod
    def _distinct(cls, value: list[float]) -> list[float]:
        if len(set(value)) != len(value):
            raise ValueError("a target is listed twice")
        return value

    @property
    def duration(self) -> float:
        """One stop: every target held in turn [s]."""
        return len(self.targets) * self.hold


class DutyCycle(Strict):
    """A piecewise-constant operating profile; the table reciprocates whenever it moves.

    ``repeat``: the segments run this many times in a row (``duration`` is one block's).
    ``measuring``: each block starts with a measuring stop (:class:`MeasuringStops`), the segments'
    starts counted from the stop's end, and one more stop ends the cycle, so that the first and
    last measurements bracket the duty (ISO 230-3's drift test).  :meth:`timeline` is the whole
    profile.
    """

    segments: list[DutySegment]
    duration: PosDuration
    repeat: int = Field(default=1, ge=1, le=10_000)
    ambient: Temperature | None = None  # of every segment that states none
    measuring: MeasuringStops | None = None
    description: str = ""

    @model_serializer(mode="wrap")
    def _omit_defaults(self, handler):
        # Left out at their defaults, so that descriptions written before they existed keep their
        # serialised form and hash (the benches' frozen provenance).
        data = handler(self)
        if isinstance(data, dict):
            if data.get("repeat") == 1:
                del data["repeat"]
            for key in ("ambient", "measuring"):
                if data.get(key, 0.0) is None:
                    del data[key]
        return data

    @model_validator(mode="after")
    def _segments_in_order(self) -> "DutyCycle":
        if not self.segments:
            raise ValueError("a duty cycle needs at least one segment")
        if self.segments[0].start != 0.0:
            raise ValueError("the first segment must start at 0 s")
        starts = [seg.start for seg in self.segments]
        for i in range(1, len(starts)):
            if starts[i] <= starts[i - 1]:
                raise ValueError(f"segment {i} starts at {starts[i]:g} s, not after segment {i - 1} ({starts[i - 1]:g} s)")
        if starts[-1] >= self.duration:
            raise ValueError(f"the last segment starts at {starts[-1]:g} s, at or after the end ({self.duration:g} s)")
        return self

    @property
    def total_duration(self) -> float:
        """The whole profile [s]: every block, with its measuring stop, and the closing stop."""
        stop = self.measuring.duration if self.measuring is not None else 0.0
        return self.repeat * (stop + self.duration) + stop

    def timeline(self) -> list[DutySegment]:
        """Every segment of the whole profile in order, starts from the profile's start (the blocks
        repeated, the measuring stops put in as standstills with the table held at each target)."""
        out: list[DutySegment] = []
        t = 0.0
        stop = self.measuring

        def stops(at: float, ambient: float | None) -> float:
            for target in stop.targets:
                out.append(DutySegment.model_construct(start=at, screw_speed=0.0, nut_speed=0.0, ambient=ambient,
                                                       table_at=target))
                at += stop.hold
            return at

        for _ in range(self.repeat):
            if stop is not None:
                t = stops(t, self.segments[0].ambient)
            for seg in self.segments:
                out.append(seg.model_copy(update={"start": t + seg.start}))
            t += self.duration
        if stop is not None:
            stops(t, self.segments[-1].ambient)
        return out
