"""What a law on a machine needs and its file cannot say: the guards of an exported law.

A law file (:mod:`.evaluator`) says how to compute D or E(x) from readings.  Running it in a
controller also needs three decisions, declared at export (``feedtherm export``) and compiled into
the code (:mod:`feedtherm.outputs.controller`):

- **valid inputs**: each input's valid range [K].  A reading outside it, or not a number, is a
  failed sensor: the output holds its last valid value, a flag is raised, the lags do not move,
  and the time runs on, so that when every input is valid again the lags take the whole time
  since their last move in one step (what ``feedtherm correct`` gives on the log with the failed
  samples left out).  Default: the law's training envelope (``envelope``, :mod:`.envelope`)
  widened by :data:`DEFAULT_MARGIN_K` on each side;
- **the output's rate**: the guarded output moves towards the law's value by at most
  ``max_rate`` × Δt a step (for a stroke law: the change of E at any x, the sum of the Legendre
  coefficients' changes, since |P_m| ≤ 1).  The axis never jumps: a step in an input, a sensor's
  return or power-up becomes a ramp.  Default :data:`DEFAULT_MAX_RATE_M_PER_S`;
- **power-up**: ``first-sample`` (the lags settle at the first valid reading, as ``feedtherm
  correct`` does) or ``reference`` (the lags start at the law's reference temperature: a machine
  switched on after soaking at it).  In both the guarded output starts at 0, no correction applied,
  and ramps to the law's value at the rate limit.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ...errors import FeedthermError

#: The margin [K] by which the default valid range exceeds the training envelope on each side: a
#: failed thermocouple or PT100 reads far outside (an open PT100 reads hundreds of degrees, a
#: shorted one about -240 °C), while a machine a few kelvin beyond its training is still measured
#: right (``feedtherm correct`` flags such samples; they are not failures).
DEFAULT_MARGIN_K = 10.0
#: The largest margin [K]: beyond it a failed sensor's reading would pass as valid.
MAX_MARGIN_K = 100.0
#: The default rate limit [m/s], 1 µm/s: a feed drive's thermal error changes by tens of µm an hour
#: (0.01 µm/s; the paper's screw, 30-40 µm in its first hour), so the limit never clips a thermal
#: change, while a 30 µm step becomes a 30 s ramp.
DEFAULT_MAX_RATE_M_PER_S = 1e-6
#: The power-up choices (module notes).
STARTS = ("first-sample", "reference")


@dataclass(frozen=True)
class Guards:
    """The declared guards of an exported law (module notes): ``valid_K[i]`` the (low, high) range of
    input ``i`` [K]; ``max_rate`` [m/s]; ``start`` one of :data:`STARTS`; ``reference_K`` the
    temperature the ``reference`` start sets the lags to [K] (None with ``first-sample``);
    ``valid_from`` how the ranges were set, for the export's summary."""

    valid_K: tuple[tuple[float, float], ...]
    max_rate: float
    start: str
    reference_K: float | None
    valid_from: str

    def as_dict(self, inputs: list[str]) -> dict:
        return {"valid_range_K": {name: list(r) for name, r in zip(inputs, self.valid_K)},
                "valid_range_from": self.valid_from,
                "on_invalid_input": "the output holds its last valid value, flag INVALID_INPUT is raised, the lags "
                                    "hold and take the elapsed time in one step when every input is valid again",
                "max_rate_m_per_s": self.max_rate,
                "start": self.start,
                **({"start_lags_K": self.reference_K} if self.reference_K is not None else {}),
                "output_at_power_up_m": 0.0}


def resolve_guards(document: dict, valid_range_K: tuple[float, float] | None = None,
                   margin_K: float = DEFAULT_MARGIN_K, max_rate: float = DEFAULT_MAX_RATE_M_PER_S,
                   start: str = "first-sample") -> Guards:
    """The guards of the law ``document`` (a checked regression law) from the export's options.

    Parameters
    ----------
    document : dict
        The law's document (:mod:`.law_files` has checked it).
    valid_range_K : (float, float), optional
        One valid range [K] for every input; default: the law's training envelope ± ``margin_K``.
    margin_K : float
        The envelope's widening [K] (≥ 0).
    max_rate : float
        The output's largest change [m/s] (> 0).
    start : str
        ``first-sample`` or ``reference``.

    Raises
    ------
    FeedthermError
        One line naming the option (``--valid-range``, ``--margin``, ``--max-rate``, ``--start``)
        and the reason.
    """
    inputs = [item["name"] for item in document["inputs"]]
    if not (math.isfinite(max_rate) and max_rate > 0):
        raise FeedthermError(f"--max-rate: {max_rate:g} m/s is not a positive rate")
    if not (math.isfinite(margin_K) and 0 <= margin_K <= MAX_MARGIN_K):
        raise FeedthermError(f"--margin: {margin_K:g} K is not a margin: a difference of 0 to {MAX_MARGIN_K:g} K "
                             "(\"10 K\"; \"10 degC\" reads as the temperature 283.15 K)")
    if start not in STARTS:
        raise FeedthermError(f"--start: {start!r} is not a start; allowed: {', '.join(STARTS)}")
    reference = document.get("reference")
    if start == "reference" and not reference:
        raise FeedthermError("--start: reference: the law has no reference block (no temperature it passes through "
                             "0 at); use --start first-sample")
    if valid_range_K is not None:
        low, high = valid_range_K
        if not (math.isfinite(low) and math.isfinite(high) and 0 < low < high):
            raise FeedthermError(f"--valid-range: {low:g} K to {high:g} K is not a range of temperatures "
                                 "(low below high, both above 0 K)")
        ranges = tuple((float(low), float(high)) for _ in inputs)
        source = "--valid-range"
    else:
        envelope = document.get("envelope")
        if not envelope:
            raise FeedthermError("--valid-range: the law carries no training envelope to take its inputs' valid "
                                 "range from; declare it (e.g. --valid-range \"5 degC,45 degC\")")
        ranges = tuple((envelope["inputs"][n]["min_K"] - margin_K, envelope["inputs"][n]["max_K"] + margin_K)
                       for n in inputs)
        source = f"the law's training envelope widened by {margin_K:g} K"
    return Guards(ranges, float(max_rate), start, float(reference["temperature_K"]) if start == "reference" else None,
                  source)
