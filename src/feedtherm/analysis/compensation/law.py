"""A fitted law as the document a controller evaluates (:mod:`.evaluator` reads it back)."""

from __future__ import annotations

import math

from ..candidates import Candidate
from .adapt import AdaptedLaw
from .conditioning import regression_conditioning
from .evaluator import FORMAT, VERSION
from .regression import RegressionLaw


def law_document(law: RegressionLaw, candidates: dict[str, Candidate], provenance: dict | None = None) -> dict:
    """The JSON-able document of ``law``: inputs with their part and position, weights, lags, bias.

    Units are SI: inputs in kelvin, D in metres, weights in m/K, time constants in seconds; the
    ``conditioning`` block (:mod:`.conditioning`) in µm/K and µm, for people.
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
        "ridge_K": float(law.ridge) ** 0.5,
        "conditioning": regression_conditioning(law),
        "provenance": provenance or {},
    }


def adapted_law_document(adapted: AdaptedLaw, candidates: dict[str, Candidate], provenance: dict | None = None) -> dict:
    """The document of an adapted law (:mod:`.adapt`): the posterior mean as in :func:`law_document`,
    and a ``posterior`` block from which :meth:`.evaluator.CompensationLaw.update_with_sd` gives the
    predictive standard deviation ``sqrt(φᵀ Σ φ + σ²)``, ``φ = [1, features − centre]``.
    """
    document = law_document(adapted.law, candidates, provenance)
    document["posterior"] = {
        "centre_K": adapted.centre.tolist(),
        "covariance": adapted.covariance.tolist(),
        "covariance_order": "the law's D at the centre [m], then weights_m_per_K row by row [m/K]; "
                            "entries in m², m²/K, m²/K²",
        "noise_sigma_m": adapted.noise_sigma,
        "prior_width_m": adapted.width,
        "scale_K": None if adapted.scale is None else adapted.scale.tolist(),
        "prior_bias_m": adapted.prior.bias,
        "prior_weights_m_per_K": adapted.prior.weights.tolist(),
        "samples": adapted.samples,
        "method": "conjugate Gaussian update of the simulation-trained law (Bishop 2006, §3.3); prior width by "
                  "maximum evidence on the adaptation data (§3.5)",
    }
    return document
