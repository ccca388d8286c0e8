"""A fitted law as the document a controller evaluates (:mod:`.evaluator` reads it back)."""

from __future__ import annotations

import math

import numpy as np

from ..candidates import Candidate
from .adapt import AdaptedLaw
from .conditioning import regression_conditioning
from .evaluator import FORMAT, STROKE_VERSION, VERSION
from .regression import RegressionLaw
from .stroke import StrokeLaw


def _inputs(law, candidates: dict[str, Candidate]) -> list[dict]:
    inputs = []
    for name in law.sensors:
        candidate = candidates.get(name)
        item = {"name": name, "unit": "K"}
        if candidate is not None:
            item["part"] = candidate.part or None
            item["where"] = candidate.where
            item["position_m"] = None if any(math.isnan(v) for v in candidate.position) else list(candidate.position)
        inputs.append(item)
    return inputs


def reference_block(law, reference: float | None) -> dict:
    """What the law gives for a machine at the reference temperature (every input and lag there)."""
    if reference is None:
        return {}
    k = len(law.sensors) * (1 + len(law.lags))
    value = np.asarray(law.bias, float) + reference * np.asarray(law.weights, float).reshape(k, -1).sum(axis=0)
    return {"reference": {"temperature_K": float(reference),
                          "output_m": float(value[0]) if value.size == 1 else [float(v) for v in value],
                          "constraint": "through the reference state: the regressors are taken from temperature_K "
                                        "with no free intercept (bias_m = -temperature_K x the sum of the weights), "
                                        "so a machine with every input at temperature_K reads 0"}}


def law_document(law: RegressionLaw, candidates: dict[str, Candidate], provenance: dict | None = None,
                 reference: float | None = None, envelope: dict | None = None,
                 offsets: dict[str, float] | None = None) -> dict:
    """The JSON-able document of ``law``: inputs with their part and position, weights, lags, bias.

    Units are SI: inputs in kelvin, D in metres, weights in m/K, time constants in seconds; the
    ``conditioning`` block (:mod:`.conditioning`) in µm/K and µm, for people.  A law of D stays a
    document of version 1, which every evaluator reads.  ``reference``: the temperature [K] the law
    passes through (its ``reference`` block states what it gives there); ``envelope``: its training
    envelope (:mod:`.envelope`), which ``feedtherm correct`` checks every sample against; ``offsets``:
    each input's declared offset [K], what the conditioning prices it at (:mod:`.conditioning`).
    """
    inputs = _inputs(law, candidates)
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
        "conditioning": regression_conditioning(law, offsets),
        **reference_block(law, reference),
        **({"envelope": envelope} if envelope else {}),
        "provenance": provenance or {},
    }


def adapted_law_document(adapted: AdaptedLaw, candidates: dict[str, Candidate], provenance: dict | None = None,
                         reference: float | None = None, envelope: dict | None = None,
                         offsets: dict[str, float] | None = None) -> dict:
    """The document of an adapted law (:mod:`.adapt`): the posterior mean as in :func:`law_document`,
    and a ``posterior`` block from which :meth:`.evaluator.CompensationLaw.update_with_sd` gives the
    predictive standard deviation ``sqrt(φᵀ Σ φ + σ²)``, ``φ = [1, features − centre]``.
    """
    document = law_document(adapted.law, candidates, provenance, reference, envelope, offsets)
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


def stroke_law_document(law: StrokeLaw, candidates: dict[str, Candidate], provenance: dict | None = None,
                        choice: dict | None = None, conditioning: dict | None = None,
                        reference: float | None = None, envelope: dict | None = None) -> dict:
    """The JSON-able document of a stroke law (:mod:`.stroke`, format version 2): E(x, t) [m] at a
    table position x [m] from the inputs [K], their lags and a Legendre basis in the normalised x.

    ``weights_m_per_K[s][f][m]``: input ``s``, feature ``f`` (its reading, then each lag), basis
    order ``m`` [m/K]; ``bias_m[m]`` [m].  ``controller_cost``: multiply-adds per sample
    (:func:`.stroke.controller_cost`); ``choice``: the order and ridge chosen on validation.
    """
    k, m = len(law.sensors), 1 + len(law.lags)
    return {
        "format": FORMAT,
        "version": STROKE_VERSION,
        "kind": "linear_regression_stroke",
        "output": {"name": "E", "unit": "m",
                   "meaning": "the positioning error at table position x (the screw's displacement under the nut, "
                              "relative to [mechanics] positioning); correct the axis at x by -E(x)"},
        "inputs": _inputs(law, candidates),
        "position": {"name": "x", "unit": "m", "x_min_m": law.x_min, "x_max_m": law.x_max,
                     "meaning": "table position: the nut's centre along x, the frame of positioning_error.csv; "
                                "a law is valid for x_min_m <= x <= x_max_m only",
                     "normalised": "xi = 2 (x - x_min_m) / (x_max_m - x_min_m) - 1"},
        "basis": {"kind": "legendre", "order": law.order,
                  "evaluation": "E = sum_m P_m(xi) (bias_m[m] + sum_s sum_f weights_m_per_K[s][f][m] feature[s][f])"},
        "lags_s": list(law.lags),
        "lag_start": "settled at the first reading",
        "bias_m": [float(b) for b in law.bias],
        "weights_m_per_K": law.weights.reshape(k, m, law.order + 1).tolist(),
        "ridge_K": float(law.ridge) ** 0.5,
        "controller_cost": {"multiply_adds_per_sample": law.cost["total"], **law.cost},
        **({"choice": choice} if choice else {}),
        **({"conditioning": conditioning} if conditioning else {}),
        **reference_block(law, reference),
        **({"envelope": envelope} if envelope else {}),
        "provenance": provenance or {},
    }
