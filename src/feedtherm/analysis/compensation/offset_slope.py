"""A stroke law as an offset and a slope: the form controllers' temperature compensation takes.

Controllers compensate a thermal error along an axis as a position-independent offset and a
slope about a reference position, ``E(x) ≈ offset + slope · (x − x_ref)``, both updated from
temperatures (e.g. Siemens SINUMERIK's temperature compensation: an absolute value, a gradient and
a reference position per axis).  A stroke law (:mod:`.stroke`) gives
``E(x) = Σ_m c_m P_m(ξ)`` with Legendre polynomials of ``ξ = 2 (x − x_min)/(x_max − x_min) − 1``.
Since the P_m are orthogonal on [-1, 1], the straight line nearest E in the mean square over the
stroke is the series cut after P_1::

    E_lin(x) = c_0 + c_1 ξ,   slope = 2 c_1 / (x_max − x_min),   offset = c_0 + c_1 ξ_ref

and what it leaves out is ``r(ξ) = Σ_{m≥2} c_m P_m(ξ)``, with ``|r| ≤ Σ_{m≥2} |c_m|`` as |P_m| ≤ 1.
Each ``c_m = b_m + Σ_f w_{f,m} φ_f`` is linear in the features (the readings and their lags, each
between its input's lowest and highest reading), so over a box of inputs its largest magnitude is
``|b_m + Σ_f w_{f,m} mid_f| + Σ_f |w_{f,m}| half_f``: :func:`reduction_bound` sums these over
m ≥ 2.  A law of order 0 or 1 is a line already (bound 0).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class OffsetSlope:
    """The reduction of a stroke law about ``x_ref`` [m] (module notes): ``bound_m`` the largest
    error of the line over the stroke for inputs within ``ranges_K`` [m]."""

    x_ref: float
    bound_m: float
    ranges_K: dict[str, tuple[float, float]]

    def as_dict(self) -> dict:
        return {"x_ref_m": self.x_ref,
                "form": "E(x) ~ offset + slope (x - x_ref): offset = c0 + c1 xi_ref, slope = 2 c1 / (x_max - x_min), "
                        "the Legendre series cut after P1 (the line nearest E in the mean square over the stroke)",
                "reduction_error_bound_m": self.bound_m,
                "bound_for_inputs_K": {k: list(v) for k, v in self.ranges_K.items()},
                "bound_how": "sum over m >= 2 of the largest |c_m| with every reading and lag within its range "
                             "(|P_m| <= 1 on the stroke)"}


def reduction_bound(document: dict, ranges_K: dict[str, tuple[float, float]]) -> float:
    """The largest error [m] of a stroke law's offset-and-slope form over its stroke, for every input
    (its reading and lags) within ``ranges_K`` (module notes); 0 for a law of order ≤ 1."""
    weights = np.asarray(document["weights_m_per_K"], float)  # inputs x features x orders
    bias = np.asarray(document["bias_m"], float)
    if bias.size <= 2:
        return 0.0
    names = [item["name"] for item in document["inputs"]]
    low = np.array([ranges_K[n][0] for n in names])[:, None, None]
    high = np.array([ranges_K[n][1] for n in names])[:, None, None]
    mid, half = (low + high) / 2, (high - low) / 2
    largest = np.abs(bias + (weights * mid).sum(axis=(0, 1))) + (np.abs(weights) * half).sum(axis=(0, 1))
    return float(largest[2:].sum())


def offset_slope(document: dict, x_ref: float, ranges_K: dict[str, tuple[float, float]]) -> OffsetSlope:
    """The reduction of the stroke law ``document`` about ``x_ref`` [m] and its error bound."""
    return OffsetSlope(float(x_ref), reduction_bound(document, ranges_K), dict(ranges_K))
