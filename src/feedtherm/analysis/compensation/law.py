"""A fitted law as the document a controller evaluates (:mod:`.evaluator` reads it back)."""

from __future__ import annotations

import math

from ..candidates import Candidate
from .evaluator import FORMAT, VERSION
from .regression import RegressionLaw


def law_document(law: RegressionLaw, candidates: dict[str, Candidate], provenance: dict | None = None) -> dict:
    """The JSON-able document of ``law``: inputs with their part and position, weights, lags, bias.

    Units are SI: inputs in kelvin, D in metres, weights in m/K, time constants in seconds.
    """
    inputs = []
    for name in law.sensors:
        candidate = candidates.get(name)
        item = {"name": name, "unit": "K"}
        if candidate is not None:
            item["part"] = candidate.part or None
            item["where"] = candidate.where
            item["position_m"] = None if any(math.isnan(v) for v in candidate.position) else list(candidate.position)
        inputs.append(item)
    return {
        "format": FORMAT,
        "version": VERSION,
        "kind": "linear_regression",
        "output": {"name": "D", "unit": "m", "meaning": "the screw's thermal elongation; correct the axis by -D"},
        "inputs": inputs,
        "lags_s": list(law.lags),
        "bias_m": law.bias,
        "weights_m_per_K": law.weights.tolist(),
        "lag_start": "settled at the first reading",
        "provenance": provenance or {},
    }
