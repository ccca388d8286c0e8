"""Random but realistic duty cycles, reproducible from a seed, for training compensation laws.

A cycle is a sequence of *runs* (constant motor speeds, the table reciprocating), *dwells*
(short stops between operations) and *standstills* (long stops: a break, a tool change, a
night), under an ambient temperature that drifts smoothly by a few kelvin over hours.  Speeds
stay within the envelope of the conditions the description states, so a law is trained where
the machine is known to run.  Every range is a field of :class:`CycleRanges`, declared with its
reason; nothing else is drawn.

The same seed gives the same cycle on any machine: the draws come from NumPy's PCG64 generator
seeded by ``SeedSequence((seed, stream, index))``, so cycle ``index`` of a stream does not depend
on how many cycles are drawn.

References
----------
.. [1] J. Mayr et al., "Thermal issues in machine tools", CIRP Annals 61(2), 771-791 (2012),
   §4: compensation models are trained on load cycles with varying speeds, stops and
   environmental temperature changes, and checked on other cycles.
.. [2] ISO 230-3:2020, Test code for machine tools - Part 3: Determination of thermal effects,
   §5 (environmental temperature variation error) and §6 (thermal distortion caused by moving
   linear axes): the drift of a few kelvin over a day and the speed-and-stop cycles of a feed
   axis are the test conditions of the standard.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..constants import KELVIN_OFFSET
from ..errors import FeedthermError
from ..system.schema import DutyCycle, FeedSystem


@dataclass(frozen=True)
class CycleRanges:
    """What a random cycle may contain; SI units (s, rpm as the description states speeds, °C).

    Every default is an assumption, stated here with its reason:

    - ``duration`` 8 h: one shift, long enough for the bench to pass its equilibrium time
      (2-3 h, paper §4.2) and to see a standstill cool it down;
    - ``run_time`` 10-60 min: one machining operation holds a feed speed for minutes to an hour;
    - ``dwell_time`` 1-10 min: loading a part, measuring, a tool change;
    - ``standstill_time`` 20-90 min: a break or a stop long enough to cool the drive by a
      time constant (~30-40 min on the paper bench);
    - ``dwell_share`` 0.2, ``standstill_share`` 0.15: the chance that the next piece is a dwell
      or a standstill (else a run): a shift of mostly machining with a few stops;
    - ``ambient_mean`` 15-25 °C: the span of the paper bench's stated ambients;
    - ``ambient_amplitude`` 0-3 K and ``ambient_period`` 4-24 h: a workshop's drift of a few
      kelvin over hours (ISO 230-3 §5 [2]_; an air-conditioned room at the low end);
    - ``ambient_step`` 600 s: the ambient is held constant over steps of 10 min (the run's
      segments are of constant operating point); a 3 K swing over 4 h moves by under 0.4 K a step;
    - speeds: the screw speed uniform between the lowest and highest the description's
      conditions state, and the screw-nut relative speed likewise (a dual drive), each run drawn
      anew; a single drive draws the screw speed alone.
    """

    duration: float = 8 * 3600.0
    run_time: tuple[float, float] = (600.0, 3600.0)
    dwell_time: tuple[float, float] = (60.0, 600.0)
    standstill_time: tuple[float, float] = (1200.0, 5400.0)
    dwell_share: float = 0.2
    standstill_share: float = 0.15
    ambient_mean: tuple[float, float] = (15.0, 25.0)
    ambient_amplitude: tuple[float, float] = (0.0, 3.0)
    ambient_period: tuple[float, float] = (4 * 3600.0, 24 * 3600.0)
    ambient_step: float = 600.0

    def __post_init__(self) -> None:
        if not (self.duration > 0 and self.ambient_step > 0):
            raise FeedthermError("a random cycle needs a positive duration and ambient step")
        for name in ("run_time", "dwell_time", "standstill_time", "ambient_mean", "ambient_amplitude", "ambient_period"):
            low, high = getattr(self, name)
            if not low <= high:
                raise FeedthermError(f"random cycles: {name} range ({low:g}, {high:g}) is empty")
        if not (0 <= self.dwell_share and 0 <= self.standstill_share and self.dwell_share + self.standstill_share < 1):
            raise FeedthermError("random cycles: dwell_share + standstill_share must be below 1")


@dataclass(frozen=True)
class SpeedEnvelope:
    """The motor speeds a run may take [rpm]: from the conditions the description states."""

    screw: tuple[float, float]
    relative: tuple[float, float]  # |n_screw - n_nut|
    dual: bool

    @classmethod
    def of(cls, system: FeedSystem) -> "SpeedEnvelope":
        rpm = 60.0 / (2 * math.pi)  # the description stores angular speeds in rad/s
        screw = [abs(c.screw_speed) * rpm for c in system.conditions.values()]
        relative = [abs(c.screw_speed - c.nut_speed) * rpm for c in system.conditions.values()]
        return cls((min(screw), max(screw)), (min(relative), max(relative)), system.kinematics.drive == "dual")


def cycle_seed(seed: int, stream: int, index: int) -> np.random.Generator:
    """The generator of cycle ``index`` in ``stream`` (0: training, 1: validation, 2: test, ...)."""
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)):
        raise FeedthermError(f"--seed: {seed!r} is not an integer")
    return np.random.default_rng(np.random.SeedSequence((int(seed) % 2**63, stream, index)))


def random_cycle(system: FeedSystem, rng: np.random.Generator, ranges: CycleRanges = CycleRanges(),
                 description: str = "random duty cycle") -> DutyCycle:
    """A random duty cycle of ``system`` drawn with ``rng`` within ``ranges``.

    Parameters
    ----------
    system : FeedSystem
        Its conditions give the speed envelope (:class:`SpeedEnvelope`).
    rng : numpy.random.Generator
        From :func:`cycle_seed`.
    ranges : CycleRanges

    Returns
    -------
    DutyCycle
        Segments of constant speeds and ambient: each piece (run, dwell, standstill) is cut at
        the ambient steps.  The first piece is a run (a cycle starts when work starts).
    """
    envelope = SpeedEnvelope.of(system)
    pieces = _pieces(rng, ranges, envelope)
    ambient = _ambient(rng, ranges)
    starts = sorted({*(start for start, _, _ in pieces),
                     *np.arange(0.0, ranges.duration, ranges.ambient_step).tolist()})
    segments = []
    for start in starts:
        _, screw, nut = next(p for p in reversed(pieces) if p[0] <= start)
        step_start = math.floor(start / ranges.ambient_step) * ranges.ambient_step
        segments.append({"start": f"{start!r} s", "screw_speed": f"{screw!r} rpm", "nut_speed": f"{nut!r} rpm",
                         "ambient": f"{ambient(step_start)!r} degC"})
    return DutyCycle.model_validate({"segments": segments, "duration": f"{ranges.duration!r} s",
                                     "description": description})


def _pieces(rng: np.random.Generator, ranges: CycleRanges, envelope: SpeedEnvelope) -> list[tuple[float, float, float]]:
    """``(start [s], screw [rpm], nut [rpm])`` of each run, dwell and standstill, from 0 to the end."""
    pieces, t, kind = [], 0.0, "run"
    while t < ranges.duration:
        if kind == "run":
            screw = float(rng.uniform(*envelope.screw))
            nut = screw - float(rng.uniform(*envelope.relative)) if envelope.dual else 0.0
            pieces.append((t, screw, nut))
            t += float(rng.uniform(*ranges.run_time))
        else:
            pieces.append((t, 0.0, 0.0))
            t += float(rng.uniform(*(ranges.dwell_time if kind == "dwell" else ranges.standstill_time)))
        u = float(rng.uniform())
        kind = "dwell" if u < ranges.dwell_share else "standstill" if u < ranges.dwell_share + ranges.standstill_share else "run"
    # rounded to the second, so the CSV and the segments agree exactly
    out, seen = [], set()
    for start, screw, nut in pieces:
        start = float(round(start))
        if start < ranges.duration and start not in seen:
            seen.add(start)
            out.append((start, screw, nut))
    return out


def _ambient(rng: np.random.Generator, ranges: CycleRanges):
    """The ambient [°C] as a function of time: a mean, a sinusoidal drift of random phase."""
    mean = float(rng.uniform(*ranges.ambient_mean))
    amplitude = float(rng.uniform(*ranges.ambient_amplitude))
    period = float(rng.uniform(*ranges.ambient_period))
    phase = float(rng.uniform(0.0, 2 * math.pi))
    floor = -KELVIN_OFFSET + 1.0

    def at(t: float) -> float:
        return max(mean + amplitude * math.sin(2 * math.pi * t / period + phase), floor)

    return at
