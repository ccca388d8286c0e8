"""What an uncertainty study produces: the resolved uncertain parameters, bands and Sobol indices.

The study (:mod:`feedtherm.analysis.uncertainty.study`) fills these; the output side
(:mod:`feedtherm.outputs.uncertainty_files`, the figures and the report section) reads only
these, so either side can change without the other.

Quantities are named as in the measurements: sensors (the ambient's included) [°C] and ``D_um`` [µm].
Percentile bands are the 5 % and 95 % quantiles of the sampled runs (``BAND``).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

#: The lower and upper quantile of a prediction band.
BAND = (0.05, 0.95)


@dataclass(frozen=True)
class UncertainParameter:
    """One declared uncertainty, resolved against its description.

    ``kind`` "value": the sampled number is the value at every path [SI]; "scale": a multiplier on
    each path's declared value.  ``declared`` is the value at the first path (or 1.0 for a scale).
    ``low``/``high`` bound a uniform or triangular distribution (and truncate a normal one);
    ``sigma`` is a normal distribution's standard deviation, or a lognormal one's of ln x.
    "posterior normal" (sampling.POSTERIOR): a parameter fitted by a calibration, normal around the
    fit (``declared``) with its standard error (``sigma``), correlated with the other fitted ones
    (the set's ``calibration["correlation"]``), clipped to the fit's bounds (``low``/``high``).
    """

    name: str
    description: str
    kind: str  # "value" | "scale"
    paths: tuple[str, ...]
    declared: float
    distribution: str  # "uniform" | "triangular" | "normal" | "lognormal" | "posterior normal" (after calibration)
    low: float | None
    high: float | None
    sigma: float | None
    unit: str  # the unit the description states the value in ("" for a scale)
    reason: str
    provenance: str  # the provenance entry covering the first path: "assumption: <source>"


@dataclass
class Band:
    """Bands of one condition over time."""

    time_s: np.ndarray  # (n_t,) [s]
    quantiles: dict[str, np.ndarray]  # quantity -> (3, n_t): 5 %, 50 %, 95 %
    nominal: dict[str, np.ndarray]  # quantity -> (n_t,): the run at the declared values


@dataclass(frozen=True)
class FinalBand:
    """The band of one quantity's final value at one condition, beside its measurement."""

    condition: str
    quantity: str  # a sensor (the ambient's included) or "D_um"
    unit: str  # "C" or "um"
    p05: float
    p50: float
    p95: float
    nominal: float
    measured: float | None = None
    flag: str = ""  # why the consistency check flags the measured value ("" if it does not)

    @property
    def inside(self) -> bool | None:
        """Whether the measured value lies within the 5–95 % band (None without a measurement)."""
        if self.measured is None:
            return None
        return self.p05 <= self.measured <= self.p95


@dataclass(frozen=True)
class SobolIndex:
    """First-order and total Sobol indices of one parameter on one quantity's final value."""

    quantity: str
    parameter: str
    S1: float
    S1_conf: float  # half-width of the 95 % bootstrap interval
    ST: float
    ST_conf: float


@dataclass
class UncertaintySet:
    """Bands (and indices) under one state of knowledge: the declared priors, or after calibration."""

    label: str  # "prior", "calibrated" or "predictive"
    parameters: list[UncertainParameter]
    bands: dict[str, Band]  # condition -> bands over time
    finals: list[FinalBand]
    runs: int
    sobol_condition: str | None = None
    sobol: list[SobolIndex] = field(default_factory=list)
    calibration: dict | None = None  # the calibration folder's fit conditions and fitted parameters
    #: The predictive set only: the model error added to the calibrated set's runs (the noise
    #: scale s², and quantity -> standard deviation s·σ in the value's unit).
    model_error: dict | None = None

    @property
    def coverage(self) -> tuple[int, int]:
        """(measured values inside their band, measured values)."""
        judged = [f.inside for f in self.finals if f.inside is not None]
        return sum(judged), len(judged)


@dataclass
class UncertaintyStudy:
    system: str
    settings: dict  # samples, seed, sampler, model, mode, duration_s, band, execution, wall_time_s
    sets: list[UncertaintySet]  # the prior first, then the calibrated set if a calibration was given,
    # then (after a Bayesian update) the predictive set: the calibrated runs with the model error
