"""A checked law document as the numbers a code generator prints (:mod:`.c_code`, :mod:`.linuxcnc`).

Only the regression laws export: a law of D (with or without lags), an adapted law (its
posterior gives the predictive standard deviation as well) and a stroke law.  A Kalman
estimator is refused (:data:`KALMAN_REFUSAL`).
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from ...errors import FeedthermError

#: Why a Kalman estimator does not export: one line, as ``feedtherm export`` prints it.
KALMAN_REFUSAL = ("a Kalman estimator does not export: it needs the motor speeds and the ambient beside the "
                  "readings, and a state model with a matrix exponential per speed; `feedtherm correct` does not run "
                  "it either. Export a regression law (law*.json, law_stroke*.json, law_adapted*.json)")

_IDENTIFIER = re.compile(r"[a-z][a-z0-9_]{0,39}\Z")


@dataclass(frozen=True)
class LawSpec:
    """A regression law's numbers in the evaluator's order (:mod:`feedtherm.analysis.compensation.evaluator`).

    ``bias`` [m] and ``weights`` [m/K]: a law of D, ``bias`` one number and ``weights[i][f]`` input
    ``i``, feature ``f`` (its reading, then each lag); a stroke law, ``bias[m]`` and
    ``weights[i][f][m]`` per Legendre order ``m``.  ``posterior``: (centre [K], covariance, σ [m])
    of an adapted law, else None.
    """

    inputs: tuple[str, ...]
    lags: tuple[float, ...]
    stroke: bool
    bias: object
    weights: list
    x_min: float | None = None
    x_max: float | None = None
    order: int = 0
    posterior: tuple | None = None
    reference_K: float | None = None

    @property
    def terms(self) -> int:
        """The number of coefficients the law computes: order + 1 (1 for a law of D)."""
        return self.order + 1


def law_spec(document: dict, origin: str) -> LawSpec:
    """The :class:`LawSpec` of a checked law document; a Kalman estimator refused in one line naming ``origin``."""
    if document.get("kind") == "kalman":
        raise FeedthermError(f"{origin}: {KALMAN_REFUSAL}")
    inputs = tuple(item["name"] for item in document["inputs"])
    lags = tuple(float(t) for t in document["lags_s"])
    reference = document.get("reference")
    reference_K = float(reference["temperature_K"]) if reference else None
    if document["kind"] == "linear_regression_stroke":
        position = document["position"]
        return LawSpec(inputs, lags, True, [float(b) for b in document["bias_m"]],
                       [[[float(w) for w in row] for row in block] for block in document["weights_m_per_K"]],
                       float(position["x_min_m"]), float(position["x_max_m"]), int(document["basis"]["order"]),
                       reference_K=reference_K)
    block = document.get("posterior")
    posterior = None if block is None else ([float(c) for c in block["centre_K"]],
                                            [[float(v) for v in row] for row in block["covariance"]],
                                            float(block["noise_sigma_m"]))
    return LawSpec(inputs, lags, False, float(document["bias_m"]),
                   [[float(w) for w in row] for row in document["weights_m_per_K"]], posterior=posterior,
                   reference_K=reference_K)


def c_identifier(text: str, option: str = "--name") -> str:
    """``text`` as the prefix of every C name and the HAL component's name: lower-case letters, digits
    and underscores, a letter first, at most 40 characters.

    Raises
    ------
    FeedthermError
        One line naming ``option`` and the rule.
    """
    if not _IDENTIFIER.match(text):
        raise FeedthermError(f"{option}: {text[:60]!r} is not a name for the generated code: lower-case letters, "
                             "digits and underscores, a letter first, at most 40 characters")
    return text


def default_name(stem: str) -> str:
    """A code name from a law file's stem (``law_stroke`` → ``ft_law_stroke``), short enough for HAL's names."""
    cleaned = re.sub(r"[^a-z0-9_]+", "_", stem.lower()).strip("_")[:20].strip("_") or "law"
    return f"ft_{cleaned}"


def pin_names(inputs: tuple[str, ...]) -> list[str]:
    """The HAL pin (and C comment) name of each input: lower-case, ``_`` for anything else, unique."""
    out: list[str] = []
    for name in inputs:
        base = re.sub(r"[^a-z0-9]+", "_", name.lower()).strip("_") or "input"
        candidate, n = base, 2
        while candidate in out:
            candidate, n = f"{base}_{n}", n + 1
        out.append(candidate)
    return out


def comment_text(text: str) -> str:
    """``text`` safe inside a C comment and a halcompile doc string: printable ASCII, no ``*/``, no quotes."""
    cleaned = "".join(c if 32 <= ord(c) < 127 and c not in '"\\' else "?" for c in text)
    return cleaned.replace("*/", "*?")
