"""Valid law documents of every kind, written by feedtherm's own writers (as `feedtherm compensate`
writes them): a law of D with lags and a static one, an adapted law (its posterior), a stroke law,
and a Kalman estimator on a two-state model made by hand; each through JSON text, as a file holds it.

The inputs are T1, T2 (and T3 for the stroke law); :data:`LOG` is a measurement file that logs them
and D, which `feedtherm correct` reads beside any of the regression laws.
"""

from __future__ import annotations

import json

import numpy as np

from feedtherm.analysis.candidates import Candidate
from feedtherm.analysis.compensation.adapt import adapt_law
from feedtherm.analysis.compensation.data import CycleRecord, CycleSet
from feedtherm.analysis.compensation.envelope import training_envelope
from feedtherm.analysis.compensation.kalman import KalmanLaw, KalmanNoise
from feedtherm.analysis.compensation.law import adapted_law_document, law_document, stroke_law_document
from feedtherm.analysis.compensation.operating_table import OperatingTable
from feedtherm.analysis.compensation.pairs import Pairs
from feedtherm.analysis.compensation.regression import features, fit_regression, lagged
from feedtherm.analysis.compensation.state_space import ReducedModel
from feedtherm.analysis.compensation.stroke import fit_stroke, stroke_conditioning

NAMES = ("T1", "T2", "T3")
REFERENCE = 293.15
LAGS = (900.0, 3600.0)
X_MIN, X_MAX = 0.1, 0.3
POSITIONS = np.linspace(X_MIN, X_MAX, 5)

#: A measurement log of T1-T3 and D over 40 min, time series (docs/measurements.md).
LOG = "".join(["condition,time [min],quantity,value,unit\n"]
              + [f"run1,{t},{name},{20 + 0.1 * t + i:.2f},degC\n" for t in range(0, 41, 5)
                 for i, name in enumerate(NAMES)]
              + [f"run1,{t},D,{0.8 * t:.1f},um\n" for t in range(0, 41, 10)])


def _cycles(seed: int = 3, count: int = 2, n: int = 120):
    """Smooth random readings [K] every 60 s, D and E(x) [m] from known weights on them."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(count):
        times = np.arange(n) * 60.0
        readings = REFERENCE + 5 * lagged(times, np.cumsum(rng.normal(0, 0.3, (n, 3)), axis=0), 600.0)
        F = features(times, readings - REFERENCE, LAGS)
        d = F @ np.array([4e-6, -1e-6, 0.5e-6, 2e-6, 0.0, 1e-6, 0.0, 0.0, 0.0])
        xi = 2 * (POSITIONS - X_MIN) / (X_MAX - X_MIN) - 1
        e = d[:, None] * (1 + 0.3 * xi[None, :])
        out.append((times, readings, d, e))
    return out


def _candidates() -> dict[str, Candidate]:
    return {n: Candidate(n, "part", (0.1 * i, 0.0, 0.0), "declared") for i, n in enumerate(NAMES)}


def _envelope(cycles, sensors) -> dict:
    columns = [NAMES.index(s) for s in sensors]
    return training_envelope(((t, r[:, columns]) for t, r, *_ in cycles), sensors)


def _text(document: dict) -> dict:
    return json.loads(json.dumps(document))


def regression_documents() -> dict[str, dict]:
    """``law.json`` (T1, T2 with two lags), ``law_static.json`` and ``law_adapted.json`` as compensate writes them."""
    cycles = _cycles()
    out = {}
    for name, lags in (("law", LAGS), ("law_static", ())):
        law = fit_regression([(t, r[:, :2], d) for t, r, d, _ in cycles], NAMES[:2], lags, ridge=1e-4,
                             reference=REFERENCE)
        out[name] = _text(law_document(law, _candidates(), {"system": "synthetic"}, REFERENCE,
                                       _envelope(cycles, NAMES[:2])))
    prior = fit_regression([(t, r[:, :2], d) for t, r, d, _ in cycles], NAMES[:2], LAGS, ridge=1e-4, reference=REFERENCE)
    times, readings, d, _ = cycles[0]
    rows = features(times, readings[:, :2], LAGS)[::10]
    pairs = Pairs(rows, d[::10] + 3e-6, np.full(len(rows), 1e-6), tuple("run1" for _ in rows))
    adapted = adapt_law(prior, pairs, np.ones(rows.shape[1]), reference=REFERENCE)
    out["law_adapted"] = _text(adapted_law_document(adapted, _candidates(), {"system": "synthetic"}, REFERENCE,
                                                    _envelope(cycles, NAMES[:2])))
    return out


def stroke_document() -> dict:
    """``law_stroke.json``: E(x) on T1-T3 with two lags, order 2."""
    cycles = _cycles()
    records = [CycleRecord(f"train-{i}", t, r, d, np.zeros(len(t)), np.zeros(len(t)), positions=POSITIONS.copy(),
                           stroke_error=e) for i, (t, r, d, e) in enumerate(cycles)]
    law = fit_stroke(CycleSet("train", list(NAMES), records, REFERENCE), NAMES, LAGS, order=2, ridge=1e-4)
    return _text(stroke_law_document(law, _candidates(), {"system": "synthetic"}, {"order": 2},
                                     stroke_conditioning(law), REFERENCE, _envelope(cycles, NAMES)))


def kalman_document() -> dict:
    """``law_kalman.json`` of a two-state model: ζ = [uniform, one mode], one surface, one source,
    T1 and D its outputs, the ambient its input; stable at every h > 0 (A0 + h A_s, A_s = -1e-4 I)."""
    a0 = np.array([[0.0, 0.0], [0.0, -1e-3]])
    a_surface = np.array([-1e-4 * np.eye(2)])
    uniform = np.array([1.0, 0.0])
    f_surface = -(a_surface @ uniform)  # the machine at the ambient stays there
    model = ReducedModel(["skin"], ["motor"], ["T1", "D"], a0, a_surface, f_surface, np.array([[1e-3], [5e-4]]),
                         np.array([[1.0, 0.5], [1e-5, 2e-5]]), np.array([0.0, -1e-5 * REFERENCE]), uniform,
                         np.array([1.0, 0.1]), "ambient", stroke_x=np.array([X_MIN, X_MAX]),
                         C_stroke=np.array([[1e-5, 1e-5], [1e-5, 3e-5]]), d_stroke=np.array([-1e-5, -1e-5]) * REFERENCE)
    table = OperatingTable(np.array([0.0, 1000.0]), np.array([0.0]), False, np.array([[[5.0]], [[10.0]]]),
                           np.array([[[0.0]], [[50.0]]]), np.array([5.0]), np.array([0.0]), REFERENCE)
    law = KalmanLaw(model, table, ("T1",), (0.2,), KalmanNoise())
    return _text(law.document({"system": "synthetic"}))


def every_document() -> dict[str, dict]:
    """Every kind, by its file's name."""
    return {**regression_documents(), "law_stroke": stroke_document(), "law_kalman": kalman_document()}
