"""What a regression law's file may hold: the typed schema of ``law*.json`` (:mod:`.law` writes them).

A law file is input a user hands over (``feedtherm correct``, :meth:`.evaluator.CompensationLaw.from_file`),
so it is validated at the boundary as a description is: every key known (unknown keys are errors,
with the closest valid name), every number a finite JSON number (no boolean, no text, no NaN),
every shape consistent, every magnitude within what a thermal law of a machine tool can be.  One
model per kind: :class:`RegressionLawDocument` (a law of D, an adapted one with its ``posterior``)
and :class:`StrokeLawDocument` (E(x) along the stroke); the Kalman estimator's document is
:mod:`.kalman_schema`'s.  :mod:`.law_files` reads a file and reports the first violation in one line.

The bounds and why:

- a weight [m/K] lies within ±:data:`MAX_WEIGHT_M_PER_K` (0.01 m/K): aluminium's 23e-6/K over the
  longest machine feedtherm accepts (100 m, :data:`~feedtherm.system.quantities.LENGTH_LIMIT`)
  is 2.3 mm/K; a law that reads a difference of two sensors through large opposite weights
  (the worst a study has fitted: ±0.9 mm/K) stays far within;
- a bias [m], the law's output with every input and lag at 0 K, lies within ±:data:`MAX_BIAS_M`
  (10 m): that 100 m aluminium part contracts by 0.7 m from room temperature to 0 K;
- a lag's time constant lies in (0, :data:`MAX_LAG_S`]: a lag of 0 s divides by zero and a
  negative one grows without bound; 1e7 s (116 days) is longer than a machine's foundation
  takes to follow its hall;
- temperatures (a reference, an envelope, a posterior's centre) lie in the range of
  :data:`~feedtherm.system.quantities.TEMPERATURE_LIMIT`, positions within ±100 m;
- a stroke law's Legendre order is at most :data:`MAX_ORDER` (the study chooses among 0-3);
- a posterior's covariance is square, symmetric to rounding and its variances are not negative;
  its standard deviations, like the noise σ, are at most the bounds above (1 m on D, 0.01 m/K on a
  weight).

Input names follow the description's rule for sensors: a letter, then letters, digits and
underscores (no spaces, no control characters, which would split an error message).
"""

from __future__ import annotations

import math
import re
from typing import Annotated, Any, Literal

from pydantic import AfterValidator, BaseModel, ConfigDict, Field, model_validator

from ...system.quantities import LENGTH_LIMIT, TEMPERATURE_LIMIT
from .evaluator import FORMAT
#: |weight| [m/K] (module notes).
MAX_WEIGHT_M_PER_K = 1e-2
#: |bias| [m] (module notes).
MAX_BIAS_M = 10.0
#: A standard deviation of D [m]: an uncertainty of a metre says the law says nothing.
MAX_SIGMA_M = 1.0
#: Longest lag time constant [s] (module notes).
MAX_LAG_S = 1e7
#: Highest Legendre order of a stroke law.
MAX_ORDER = 10
#: Shortest stroke [m]: a target is matched to 1 µm (measurement files), so a shorter stroke has no x.
MIN_STROKE_M = 1e-6
#: Relative asymmetry of a covariance left by rounding (a written one: about 1e-15).
SYMMETRY_TOLERANCE = 1e-9
#: Every name a law reads: the description's rule for sensor names (``\\Z``: no trailing newline).
NAME = re.compile(r"[A-Za-z][A-Za-z0-9_]*\Z")
#: ISO 1's reference temperature for geometrical measurements [K]: a law without a ``reference``
#: block is checked there.
ISO_REFERENCE_K = 293.15


class StrictDocument(BaseModel):
    """Base of every block: unknown keys are errors, numbers finite and never booleans or text."""

    model_config = ConfigDict(extra="forbid", frozen=True, strict=True, allow_inf_nan=False)


def within(limit: float, unit: str, reason: str):
    """A validator: ``|value| <= limit`` [``unit``], else a ValueError saying why (``reason``)."""

    def check(value: float) -> float:
        if abs(value) > limit:
            raise ValueError(f"{value:.6g} {unit} lies beyond ±{limit:g} {unit} ({reason})")
        return value
    return AfterValidator(check)


def positive(limit: float, unit: str, reason: str, zero: bool = False):
    """A validator: ``0 < value <= limit`` (``0 <= value`` with ``zero``) [``unit``], else a ValueError."""

    def check(value: float) -> float:
        if value < 0 or (value == 0 and not zero):
            what = "must not be negative" if zero else "must be above 0"
            raise ValueError(f"{value:.6g} {unit} {what} ({reason})")
        if value > limit:
            raise ValueError(f"{value:.6g} {unit} lies above {limit:g} {unit} ({reason})")
        return value
    return AfterValidator(check)


def _temperature(value: float) -> float:
    if TEMPERATURE_LIMIT.violated_by(value):
        raise ValueError(f"{value:.6g} K lies outside {TEMPERATURE_LIMIT.low:g} to {TEMPERATURE_LIMIT.high:g} K "
                         f"({TEMPERATURE_LIMIT.reason})")
    return value


def versions(*allowed: int):
    """A format version: a whole number among ``allowed`` (strict: ``true`` and ``1.0`` are not 1)."""

    def check(value: int) -> int:
        if value not in allowed:
            raise ValueError(f"{value} is not allowed; allowed values: {', '.join(map(str, allowed))}")
        return value
    return Annotated[int, AfterValidator(check)]


def _name(value: str) -> str:
    if not NAME.match(value):
        raise ValueError(f"{value!r} is not a sensor name (a letter, then letters, digits and underscores)")
    return value


Weight = Annotated[float, within(MAX_WEIGHT_M_PER_K, "m/K", "a kelvin moving the axis by more than 1 cm is no "
                                                             "thermal law; aluminium over 100 m moves 2.3 mm/K")]
Bias = Annotated[float, within(MAX_BIAS_M, "m", "the law's output with every input at 0 K; a 100 m aluminium part "
                                                 "contracts 0.7 m from room temperature to 0 K")]
Lag = Annotated[float, positive(MAX_LAG_S, "s", "a lag's time constant: 0 divides by zero, a negative one grows "
                                                 "without bound, and no machine takes 116 days to follow its hall")]
Temperature = Annotated[float, AfterValidator(_temperature)]
Coordinate = Annotated[float, within(LENGTH_LIMIT.high, "m", LENGTH_LIMIT.reason)]
Sigma = Annotated[float, positive(MAX_SIGMA_M, "m", "a standard deviation of D beyond 1 m says nothing", zero=True)]
Finite = float  # finite by the config (allow_inf_nan=False), never a boolean or text (strict)
NonNegative = Annotated[float, Field(ge=0.0)]
SensorName = Annotated[str, AfterValidator(_name)]
Text = Annotated[str, Field(max_length=10_000)]


class LawInput(StrictDocument):
    """One input: a sensor's reading [K]."""

    name: SensorName
    unit: Literal["K"] = "K"
    part: Text | None = None
    where: Text | None = None
    position_m: Annotated[list[Coordinate], Field(min_length=3, max_length=3)] | None = None


class Output(StrictDocument):
    name: Literal["D", "E"]
    unit: Literal["m"]
    meaning: Text | None = None


class Reference(StrictDocument):
    """What the law gives with every input and lag at ``temperature_K``."""

    temperature_K: Temperature
    output_m: Bias | list[Bias]
    constraint: Text | None = None


class EnvelopeEntry(StrictDocument):
    min_K: Temperature
    max_K: Temperature
    max_rate_K_per_s: NonNegative

    @model_validator(mode="after")
    def _ordered(self) -> "EnvelopeEntry":
        if self.min_K > self.max_K:
            raise ValueError(f"min_K ({self.min_K:g} K) lies above max_K ({self.max_K:g} K)")
        return self


class Envelope(StrictDocument):
    """The training envelope (:mod:`.envelope`): each input's range and fastest rate."""

    inputs: dict[str, EnvelopeEntry]
    rate_window_s: Annotated[float, positive(MAX_LAG_S, "s", "the span a rate is taken over")]
    meaning: Text | None = None


class Posterior(StrictDocument):
    """An adapted law's posterior (:mod:`.adapt`)."""

    centre_K: list[Temperature]
    covariance: list[list[Finite]]
    noise_sigma_m: Sigma
    covariance_order: Text | None = None
    prior_width_m: NonNegative | None = None
    scale_K: list[NonNegative] | None = None
    prior_bias_m: Bias | None = None
    prior_weights_m_per_K: list[list[Weight]] | None = None
    samples: Annotated[int, Field(ge=0)] | None = None
    method: Text | None = None


class Position(StrictDocument):
    """A stroke law's stroke: the table positions it holds for [m]."""

    x_min_m: Coordinate
    x_max_m: Coordinate
    name: Literal["x"] = "x"
    unit: Literal["m"] = "m"
    meaning: Text | None = None
    normalised: Text | None = None

    @model_validator(mode="after")
    def _a_stroke(self) -> "Position":
        if not self.x_max_m - self.x_min_m >= MIN_STROKE_M:
            raise ValueError(f"x_max_m ({self.x_max_m:g} m) must lie at least 1 µm above x_min_m ({self.x_min_m:g} m)")
        return self


class Basis(StrictDocument):
    kind: Literal["legendre"]
    order: Annotated[int, Field(ge=0, le=MAX_ORDER)]
    evaluation: Text | None = None


class _LawDocument(StrictDocument):
    """What every regression law's document holds; the informational blocks are free-form."""

    format: Literal[FORMAT]
    output: Output | None = None
    inputs: Annotated[list[LawInput], Field(min_length=1)]
    lags_s: list[Lag]
    lag_start: Text | None = None
    ridge_K: NonNegative | None = None
    conditioning: dict[str, Any] | None = None
    reference: Reference | None = None
    envelope: Envelope | None = None
    provenance: dict[str, Any] | None = None

    @property
    def names(self) -> list[str]:
        return [item.name for item in self.inputs]

    def _check_common(self, output: str) -> None:
        """Distinct inputs; the envelope's entries exactly the inputs; the ``output`` named as the kind's."""
        if self.output is not None and self.output.name != output:
            raise ValueError(f"output.name: {self.output.name!r}, but a law of this kind gives {output!r}")
        seen: dict[str, int] = {}
        for i, name in enumerate(self.names):
            if name in seen:
                raise ValueError(f"inputs[{i}]: {name!r} is inputs[{seen[name]}] already; a law reads each sensor once")
            seen[name] = i
        if self.envelope is not None:
            missing = [n for n in self.names if n not in self.envelope.inputs]
            if missing:
                raise ValueError(f"envelope.inputs: no entry for the input {missing[0]!r}")
            extra = [n for n in self.envelope.inputs if n not in seen]
            if extra:
                raise ValueError(f"envelope.inputs: {extra[0]!r} is not an input of the law ({', '.join(self.names)})")


def _shape(path: str, items: list, expected: int, what: str) -> None:
    if len(items) != expected:
        raise ValueError(f"{path}: {entries(len(items))}, expected {expected} ({what})")


def entries(n: int) -> str:
    return f"{n} entr{'y' if n == 1 else 'ies'}"


def _features(lags: int) -> str:
    """What a row of weights holds: ``the reading and its 2 lags``."""
    return "the reading" + ("" if not lags else " and its lag" if lags == 1 else f" and its {lags} lags")


class RegressionLawDocument(_LawDocument):
    """A law of D: ``D = bias_m + Σ_s Σ_f weights_m_per_K[s][f] feature[s][f]``, features each
    input's reading and then its lags; an adapted law carries a ``posterior``."""

    kind: Literal["linear_regression"]
    version: versions(1, 2)
    bias_m: Bias
    weights_m_per_K: list[list[Weight]]
    posterior: Posterior | None = None

    @model_validator(mode="after")
    def _consistent(self) -> "RegressionLawDocument":
        self._check_common("D")
        features = 1 + len(self.lags_s)
        _shape("weights_m_per_K", self.weights_m_per_K, len(self.inputs), "one row per input")
        for i, row in enumerate(self.weights_m_per_K):
            _shape(f"weights_m_per_K[{i}]", row, features, _features(len(self.lags_s)))
        if self.reference is not None and isinstance(self.reference.output_m, list):
            raise ValueError("reference.output_m: a law of D gives one number, not a list")
        if self.posterior is not None:
            _check_posterior(self.posterior, len(self.inputs) * features)
        return self


def _check_posterior(posterior: Posterior, n: int) -> None:
    """The posterior's shapes for ``n`` features, and its covariance a covariance."""
    _shape("posterior.centre_K", posterior.centre_K, n, "one per feature: each input's reading, then its lags")
    if posterior.scale_K is not None:
        _shape("posterior.scale_K", posterior.scale_K, n, "one per feature")
    covariance = posterior.covariance
    _shape("posterior.covariance", covariance, n + 1, "the law's D at the centre, then each weight")
    for i, row in enumerate(covariance):
        _shape(f"posterior.covariance[{i}]", row, n + 1, "a square matrix")
    largest = max((abs(v) for row in covariance for v in row), default=0.0)
    for i in range(n + 1):
        variance = covariance[i][i]
        if variance < 0:
            raise ValueError(f"posterior.covariance[{i}][{i}]: {variance:.6g} is a negative variance")
        limit = MAX_SIGMA_M if i == 0 else MAX_WEIGHT_M_PER_K
        if math.sqrt(variance) > limit:
            unit = "m" if i == 0 else "m/K"
            raise ValueError(f"posterior.covariance[{i}][{i}]: a standard deviation of {math.sqrt(variance):.3g} "
                             f"{unit}, above {limit:g} {unit}: an uncertainty that large says nothing")
        for j in range(i):
            if abs(covariance[i][j] - covariance[j][i]) > SYMMETRY_TOLERANCE * largest:
                raise ValueError(f"posterior.covariance[{i}][{j}]: {covariance[i][j]:.6g}, but [{j}][{i}] is "
                                 f"{covariance[j][i]:.6g}; a covariance is symmetric")


class StrokeLawDocument(_LawDocument):
    """A law of E(x): ``E = Σ_m P_m(ξ) (bias_m[m] + Σ_s Σ_f weights_m_per_K[s][f][m] feature[s][f])``."""

    kind: Literal["linear_regression_stroke"]
    version: versions(2)
    position: Position
    basis: Basis
    bias_m: list[Bias]
    weights_m_per_K: list[list[list[Weight]]]
    controller_cost: dict[str, Any] | None = None
    choice: dict[str, Any] | None = None

    @model_validator(mode="after")
    def _consistent(self) -> "StrokeLawDocument":
        self._check_common("E")
        q = self.basis.order + 1
        features = 1 + len(self.lags_s)
        _shape("bias_m", self.bias_m, q, f"one per Legendre order 0..{self.basis.order}")
        _shape("weights_m_per_K", self.weights_m_per_K, len(self.inputs), "one block per input")
        for i, block in enumerate(self.weights_m_per_K):
            _shape(f"weights_m_per_K[{i}]", block, features, _features(len(self.lags_s)))
            for j, row in enumerate(block):
                _shape(f"weights_m_per_K[{i}][{j}]", row, q, f"one per Legendre order 0..{self.basis.order}")
        if self.reference is not None:
            _shape("reference.output_m", self.reference.output_m if isinstance(self.reference.output_m, list) else [0],
                   q, "one per Legendre order")
        return self


#: The regression laws' models by kind, and the versions each kind is written in.
MODELS: dict[str, type[_LawDocument]] = {"linear_regression": RegressionLawDocument,
                                         "linear_regression_stroke": StrokeLawDocument}
