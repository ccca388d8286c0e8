"""Sensor noise of a compensation study: each candidate's kind, its noise and offset, and noisy readings.

A real sensor does not read the model's temperature.  Each candidate has a kind
(:func:`~feedtherm.analysis.candidates.sensor_kind`): ``contact`` (a PT100 or thermocouple on a
part that stays still) or ``infrared`` (a pyrometer reading a moving or turning surface).  Each kind
has, as standard deviations [K],

- a **noise**: white, drawn independently at every reading;
- an **offset**: a fixed bias of one sensor on one machine, drawn once per machine and held over
  all its readings (a sensor's calibration error, its mounting, an emissivity setting).

The defaults (:data:`DEFAULT_NOISE`), with their reasons:

- contact noise 0.1 K: the value the tool declares for a PT100 (the Kalman filter's
  :class:`~.kalman.KalmanNoise`): IEC 60751 class A, ±(0.15 + 0.002|t|) K, about ±0.2 K at 30 °C,
  taken as a uniform bound, 0.12 K; here it stands for everything that varies from one reading to
  the next (electronics, lead resistance, the air film at a glued sensor);
- contact offset 0.1 K: what stays of the class-A tolerance after the usual one-point check of a
  machine's sensors against a reference thermometer at installation (about half of ±0.2 K);
- infrared noise 0.3 K: the tool's declared value; an industrial pyrometer's repeatability is
  0.1-0.5 K, and a turning screw shows it changing spots of its surface;
- infrared offset 0.5 K: an industrial pyrometer's stated accuracy is ±1 K or ±1 % of the reading
  (taken as a 2-sigma bound), and the emissivity of a painted or taped spot (ε ≈ 0.95 ± 0.02) adds
  about 0.2 K at 10 K above the surroundings.

A description overrides them in ``[compensation]`` (:mod:`feedtherm.system.sensing`).

**Where the noise enters.** Every reading of every set: the training cycles (one machine, the
nominal one: one draw of offsets for the whole set), the validation and the test cycles (one
machine per cycle, :mod:`.data`: one draw of offsets per cycle), the ambient sensor included (a
contact sensor in the air).  The draws come from their own streams of the study's seed
(:data:`NOISE_STREAM`, :data:`OFFSET_STREAM`, :func:`~feedtherm.analysis.random_cycles.cycle_seed`),
column by column in the candidates' order, so a seed gives the same readings on any machine.  The
noise-free temperatures stay in each record (``CycleRecord.truth``).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ...system.schema import FeedSystem
from ..random_cycles import cycle_seed

#: Offset of the seed streams of the white noise (per set and cycle) and of the offsets.
NOISE_STREAM = 200
OFFSET_STREAM = 300


@dataclass(frozen=True)
class KindLevels:
    """One sensor kind's noise and offset, standard deviations [K], and where they come from."""

    noise: float
    offset: float
    source: str

    def as_dict(self) -> dict:
        return {"noise_K": self.noise, "offset_K": self.offset, "source": self.source}


#: The defaults and their reasons (the module's notes).
DEFAULT_NOISE = {
    "contact": KindLevels(0.1, 0.1, "default: PT100 of IEC 60751 class A (±0.2 K at 30 °C as a uniform bound, "
                                    "0.12 K) as white noise; offset: the class-A tolerance left after a one-point "
                                    "check at installation"),
    "infrared": KindLevels(0.3, 0.5, "default: pyrometer repeatability 0.1-0.5 K as white noise; offset: a stated "
                                     "accuracy of ±1 K as a 2-sigma bound, with the emissivity of a painted spot"),
}


@dataclass(frozen=True)
class SensorNoise:
    """The noise and offset of each kind, and each candidate's kind."""

    levels: dict[str, KindLevels]
    kinds: dict[str, str]  # candidate name -> "contact" | "infrared"

    @classmethod
    def of(cls, system: FeedSystem, kinds: dict[str, str]) -> "SensorNoise":
        """The description's ``[compensation]`` values where given, else :data:`DEFAULT_NOISE`."""
        levels = dict(DEFAULT_NOISE)
        declared = system.compensation
        if declared is not None:
            for kind in levels:
                spec = getattr(declared, kind)
                if spec.noise is not None or spec.offset is not None:
                    base = levels[kind]
                    levels[kind] = KindLevels(base.noise if spec.noise is None else spec.noise,
                                              base.offset if spec.offset is None else spec.offset,
                                              f"description: {spec.reason}")
        return cls(levels, dict(kinds))

    @classmethod
    def none(cls, kinds: dict[str, str]) -> "SensorNoise":
        """No noise and no offset (the noise-free study of before issue 34)."""
        return cls({k: KindLevels(0.0, 0.0, "noise-free") for k in DEFAULT_NOISE}, dict(kinds))

    def sigma(self, names) -> tuple[np.ndarray, np.ndarray]:
        """Noise and offset standard deviations [K] of the sensors ``names``, in order."""
        return (np.array([self.levels[self.kinds[n]].noise for n in names], dtype=float),
                np.array([self.levels[self.kinds[n]].offset for n in names], dtype=float))

    def offsets(self) -> dict[str, float]:
        """Each candidate's offset [K], its kind's (what :mod:`.conditioning` prices it at)."""
        return {name: self.levels[kind].offset for name, kind in self.kinds.items()}

    def as_dict(self) -> dict:
        return {"kinds": {k: v.as_dict() for k, v in self.levels.items()},
                "white": "independent at every reading", "offset": "one draw per sensor and machine "
                "(training: one machine for the set; validation and test: one per cycle)",
                "seed_streams": {"noise": NOISE_STREAM, "offset": OFFSET_STREAM}}


def noisy_set(cycles, noise: SensorNoise, seed: int, stream: int, one_machine: bool):
    """``cycles`` (a :class:`.data.CycleSet`) read by noisy sensors: every record's ``sensors`` gets
    its offsets and white noise, its noise-free temperatures kept as ``truth``.

    Parameters
    ----------
    cycles : CycleSet
    noise : SensorNoise
    seed : int
        The study's seed.
    stream : int
        The set's stream (:data:`.data.STREAMS`).
    one_machine : bool
        All cycles on one machine (the training set): one draw of offsets for the set.
    """
    white, offset = noise.sigma(cycles.names)
    records = []
    for index, record in enumerate(cycles.cycles):
        truth = record.truth if record.truth is not None else record.sensors
        offsets = cycle_seed(seed, OFFSET_STREAM + stream, 0 if one_machine else index).standard_normal(len(white))
        draws = cycle_seed(seed, NOISE_STREAM + stream, index).standard_normal(truth.shape)
        records.append(replace(record, sensors=truth + offset * offsets + white * draws, truth=truth))
    return replace(cycles, cycles=records)
