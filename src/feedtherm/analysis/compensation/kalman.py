"""The model-based estimator: a Kalman filter on the reduced state-space model, D as its output.

State ``x = [ζ, δ]``: the reduced temperature field ``ζ`` (:mod:`.state_space`) and one relative
heat error ``δ_j`` per source (the heat is ``q_j (1 + δ_j)``): another machine of the design
differs from the model by its losses first, and a persistent error is what a filter must learn
rather than treat as noise.  Over each sample interval ``Δt`` the motor speeds and the ambient
(the ambient sensor, an input) are held; the operating point gives ``h`` and ``q`` from the law's
table (:mod:`.operating_table`), and the step is exact for held inputs:

.. math:: ζ^+ = A_d ζ + Γ (B_q q + T_∞ f) + Γ B_q \\mathrm{diag}(q)\\, δ, \\qquad δ^+ = δ + w_δ,

with ``A_d = e^{AΔt}`` and ``Γ = A^{-1}(A_d - I)``.  The sensors read ``y = C_y ζ + d_y + v``;
the standard Kalman recursion [1]_ (prediction, then the update with the readings) runs at each
sample, and the estimate of D is ``C_D ζ + d_D`` with its variance ``C_D P_ζζ C_Dᵀ``.  The gains
depend on the operating point (a standstill leaves ``δ`` unobservable), so they are computed
online from the declared noise (:class:`KalmanNoise`); for ~40 states that is a few
40 × 40 products per reading.

References
----------
.. [1] R. E. Kalman, "A new approach to linear filtering and prediction problems", J. Basic
   Eng. 82(1), 35-45 (1960); the discrete form as in D. Simon, Optimal State Estimation,
   Wiley (2006), §5.1.
.. [2] J. Mayr et al., "Thermal issues in machine tools", CIRP Annals 61(2) (2012), §4.3:
   model-based (observer) compensation with few sensors.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
import scipy.linalg as sl

from ...constants import ELONGATION_PROBE
from ...errors import FeedthermError
from .evaluator import FORMAT, table_position
from .law_files import check_law, one_line, parse_law_file
from .kalman_schema import AMBIENT_ROLE
from .operating_table import OperatingTable
from .state_space import ReducedModel


@dataclass(frozen=True)
class KalmanNoise:
    """The filter's declared uncertainties (standard deviations), with their reasons.

    - ``contact`` 0.1 K: a PT100 of IEC 60751 class A is within ±(0.15 + 0.002|t|) K, about
      ±0.2 K at 30 °C; taken as a uniform bound, its standard uncertainty is 0.12 K;
    - ``infrared`` 0.3 K: an infrared reading of a turning screw (emissivity, reflections);
      a pyrometer's repeatability is 0.1-0.5 K;
    - ``contact_offset``, ``infrared_offset``: a sensor's fixed bias (0 by default here; a study
      passes the declared offsets, :mod:`.noise`).  The filter has no state for it: it adds the
      offset's variance to the reading's (:func:`sensor_sigma`), which makes it trust the reading
      less, though an offset, unlike white noise, does not average out;
    - ``heat_prior`` 0.115: the relative heat error of another machine, ±20 % uniform
      (:mod:`..machine_variants`) has a standard deviation of 0.2/√3;
    - ``heat_drift`` 0.05 per √h: the losses drift as lubricant and seals warm and age, and the
      frozen coefficients miss the coupling of the heats to temperature (a few % per 10 K);
    - ``heat_noise`` 0.1: a white relative heat error held over each sample (load changes within
      a sample that the commanded speeds do not show);
    - ``air_noise`` 1 K: the surfaces' coefficients are ±20 % uncertain too; on a surface 5 K
      above the air that is the heat flow of a 1 K error of the air it sees, held over a sample;
    - ``initial`` 1 K: the machine starts at the ambient, known to within 1 K throughout.
    """

    contact: float = 0.1
    infrared: float = 0.3
    heat_prior: float = 0.2 / np.sqrt(3.0)
    heat_drift: float = 0.05
    heat_noise: float = 0.1
    air_noise: float = 1.0
    initial: float = 1.0
    contact_offset: float = 0.0
    infrared_offset: float = 0.0

    def as_dict(self) -> dict:
        return {"contact_K": self.contact, "infrared_K": self.infrared, "heat_prior": self.heat_prior,
                "heat_drift_per_sqrt_h": self.heat_drift, "heat_noise": self.heat_noise, "air_noise_K": self.air_noise,
                "initial_K": self.initial, "contact_offset_K": self.contact_offset,
                "infrared_offset_K": self.infrared_offset}


class KalmanEstimator:
    """The filter on ``sensors`` (names among ``model.outputs``; ``model.ambient`` is the ambient input, not a reading).

    Parameters
    ----------
    model : ReducedModel
    table : OperatingTable
    sensors : sequence of str
    sigma : sequence of float
        Each sensor's standard uncertainty [K] (:class:`KalmanNoise`).
    noise : KalmanNoise
    steps : dict, optional
        The discrete steps already formed for this model, table and noise (shared between the
        estimators of one model: a step depends on neither the sensors nor their noise).
    """

    def __init__(self, model: ReducedModel, table: OperatingTable, sensors, sigma, noise: KalmanNoise = KalmanNoise(),
                 steps: dict | None = None):
        self.model, self.table, self.noise = model, table, noise
        self.sensors = [s for s in sensors if s != model.ambient]
        self.sigma = np.array([sg for s, sg in zip(sensors, sigma) if s != model.ambient], dtype=float)
        rows = [model.outputs.index(s) for s in self.sensors]
        d = model.outputs.index(ELONGATION_PROBE)
        self.r, self.m = model.order, len(model.sources)
        self.H = np.hstack([model.Cy[rows], np.zeros((len(rows), self.m))])
        self.h_offset = model.dy[rows]
        self.c_d = model.Cy[d]
        self.d_offset = float(model.dy[d])
        self._steps: dict = {} if steps is None else steps
        self._R = np.diag(self.sigma ** 2)
        self.reset()

    def reset(self) -> None:
        self.x: np.ndarray | None = None
        self.P: np.ndarray | None = None
        self.time: float | None = None

    def _step(self, dt: float, screw_rpm: float, nut_rpm: float):
        key = (round(dt, 9), round(screw_rpm, 6), round(nut_rpm, 6))
        if key not in self._steps:
            h, q = self.table.at(screw_rpm, nut_rpm)
            A, f = self.model.matrices(h)
            Ad = sl.expm(A * dt)
            Gamma = np.linalg.solve(A, Ad - np.eye(self.r))
            F = np.eye(self.r + self.m)
            F[:self.r, :self.r] = Ad
            F[:self.r, self.r:] = Gamma @ (self.model.Bq * q[None, :])
            n = self.noise
            heat = Gamma @ (self.model.Bq * (n.heat_noise * q)[None, :])
            air = (Gamma @ f) * n.air_noise
            Q = np.zeros_like(F)
            Q[:self.r, :self.r] = heat @ heat.T + np.outer(air, air)
            Q[self.r:, self.r:] = np.eye(self.m) * n.heat_drift ** 2 * dt / 3600.0
            pad = np.zeros(self.m)
            self._steps[key] = (F, np.concatenate([Gamma @ (self.model.Bq @ q), pad]),
                                np.concatenate([Gamma @ f, pad]), Q)
        return self._steps[key]

    def initial(self, ambient: float) -> tuple[np.ndarray, np.ndarray]:
        """The state and covariance before the first reading: a machine at the ``ambient`` [K], no heat error."""
        zeta = self.model.uniform * ambient
        x = np.concatenate([zeta, np.zeros(self.m)])
        u = self.model.uniform[:, None] * self.noise.initial
        P = np.zeros((self.r + self.m, self.r + self.m))
        P[:self.r, :self.r] = u @ u.T + np.eye(self.r) * (1e-6 * self.noise.initial ** 2)
        P[self.r:, self.r:] = np.eye(self.m) * self.noise.heat_prior ** 2
        return x, P

    def states(self, times: np.ndarray, readings: np.ndarray, ambient: np.ndarray, screw_rpm: np.ndarray,
               nut_rpm: np.ndarray) -> np.ndarray:
        """The temperature states [K] ``(b, n, order)`` of ``b`` recorded cycles filtered side by side.

        Every cycle is read at the same ``times`` [s] ``(n,)``; ``readings`` [K] ``(b, n, sensors)`` in
        the order of :attr:`sensors`, ``ambient`` [K] and the speeds [rpm] ``(b, n)``.  The time and
        measurement updates of :meth:`update` (:meth:`_predict`, :meth:`_correct`) on stacked matrices,
        one call for every cycle, so equal to :meth:`update` sample by sample up to rounding.
        """
        b, n = readings.shape[0], len(times)
        start = [self.initial(float(a)) for a in ambient[:, 0]]
        x = np.stack([s[0] for s in start])
        P = np.stack([s[1] for s in start])
        out = np.zeros((b, n, self.r))
        held = None  # (Δt, speeds) of the previous update and its stacked steps: a segment's samples share them
        for j in range(n):
            if j:
                dt = float(times[j]) - float(times[j - 1])
                if not dt > 0:
                    raise ValueError(f"readings must come in increasing time, got {times[j]} after {times[j - 1]}")
                screw, nut = screw_rpm[:, j], nut_rpm[:, j]
                if held is None or not (dt == held[0] and np.array_equal(screw, held[1]) and np.array_equal(nut, held[2])):
                    steps = [self._step(dt, screw[i], nut[i]) for i in range(b)]
                    held = (dt, screw, nut, tuple(np.stack(part) for part in zip(*steps)))
                x, P = self._predict(x, P, *held[3], ambient[:, j, None])
            if self.sensors:
                x, P = self._correct(x, P, readings[:, j, :])
            out[:, j] = x[:, :self.r]
        return out

    @staticmethod
    def _predict(x, P, F, heat, air, Q, ambient):
        """The time update of a state ``x`` ``(..., n)`` and its covariance ``P`` ``(..., n, n)`` by the
        step ``(F, heat, air, Q)`` of :meth:`_step` (stacked along the leading axis for several cycles)."""
        x = (F @ x[..., None])[..., 0] + heat + air * ambient
        return x, F @ P @ np.swapaxes(F, -1, -2) + Q

    def _correct(self, x, P, y):
        """The measurement update of ``x`` ``(..., n)`` and ``P`` ``(..., n, n)`` by the readings ``y``
        ``(..., k)`` [K]: the Joseph form ``(I - K H) P (I - K H)^T + K R K^T``, expanded so that no
        product is of two full matrices, ``P - K H P - (K H P)^T + K S K^T`` with ``S = H P H^T + R``
        (k x k, k the sensors), and made symmetric to rounding."""
        HP = self.H @ P
        S = HP @ self.H.T + self._R
        gain = np.swapaxes(np.linalg.solve(S, HP), -1, -2)
        x = x + (gain @ (y - x @ self.H.T - self.h_offset)[..., None])[..., 0]
        KHP = gain @ HP
        P = P - KHP - np.swapaxes(KHP, -1, -2) + gain @ S @ np.swapaxes(gain, -1, -2)
        return x, 0.5 * (P + np.swapaxes(P, -1, -2))

    def update(self, time: float, readings: dict[str, float], screw_rpm: float, nut_rpm: float) -> tuple[float, float]:
        """D [m] and its standard deviation [m] after the readings [K] at ``time`` [s].

        ``screw_rpm``, ``nut_rpm``: the speeds commanded since the previous reading; ``readings``
        must hold every sensor and the ambient (``model.ambient``).
        """
        ambient = float(readings[self.model.ambient])
        if self.x is None:
            self.x, self.P = self.initial(ambient)
        else:
            dt = float(time) - self.time
            if not dt > 0:
                raise ValueError(f"readings must come in increasing time, got {time} after {self.time}")
            self.x, self.P = self._predict(self.x, self.P, *self._step(dt, screw_rpm, nut_rpm), ambient)
        self.time = float(time)
        if self.sensors:
            self.x, self.P = self._correct(self.x, self.P, np.array([readings[s] for s in self.sensors], dtype=float))
        zeta = self.x[:self.r]
        var = float(self.c_d @ self.P[:self.r, :self.r] @ self.c_d)
        return float(self.c_d @ zeta + self.d_offset), float(np.sqrt(max(var, 0.0)))

    def stroke_error(self, x: float) -> float:
        """E [m] at the table position ``x`` [m] from the present state (after :meth:`update`): the
        model's rows along the stroke (:attr:`.state_space.ReducedModel.C_stroke`), linear between them.

        Raises
        ------
        ValueError
            One line naming x: no rows along the stroke, no update yet, x not finite or outside the stroke.
        """
        m = self.model
        if m.C_stroke is None:
            raise ValueError("x: this law has no rows along the stroke (a law of D only)")
        if self.x is None:
            raise ValueError("no readings yet: call update() first")
        x = table_position(x, float(m.stroke_x[0]), float(m.stroke_x[-1]))
        return float(np.interp(x, m.stroke_x, m.C_stroke @ self.x[:self.r] + m.d_stroke))

    @property
    def heat_errors(self) -> np.ndarray:
        """The estimated relative heat errors ``δ`` per source."""
        return self.x[self.r:] if self.x is not None else np.zeros(self.m)


def sensor_sigma(names, methods: dict[str, str], noise: KalmanNoise = KalmanNoise()) -> list[float]:
    """Each sensor's standard uncertainty [K] from its method (``contact`` or ``infrared``): its
    white noise and its offset combined, ``√(σ² + σ_offset²)``."""
    return [float(np.hypot(noise.infrared, noise.infrared_offset)) if methods.get(n) == "infrared"
            else float(np.hypot(noise.contact, noise.contact_offset)) for n in names]


def run_filter(estimator: KalmanEstimator, times, readings: np.ndarray, names: list[str], screw_rpm, nut_rpm):
    """D [m] and its standard deviation [m] at every sample of a recorded cycle (columns ``names``)."""
    estimator.reset()
    needed = [*estimator.sensors, estimator.model.ambient]
    columns = {n: names.index(n) for n in needed}
    out = np.zeros((len(times), 2))
    for n, t in enumerate(times):
        values = {name: readings[n, j] for name, j in columns.items()}
        out[n] = estimator.update(t, values, screw_rpm[n], nut_rpm[n])
    return out[:, 0], out[:, 1]


# --------------------------------------------------------------------------- the law and its document

VERSION = 1


def _require_kalman(document, origin: str) -> None:
    if not isinstance(document, dict) or document.get("format") != FORMAT or document.get("kind") != "kalman":
        raise FeedthermError(f"{one_line(origin)}: not a feedtherm Kalman law document (format "
                             f"{FORMAT!r}, kind 'kalman')")


#: Records whose filtered states a law keeps (a study's law asks for about 40: its validation and test
#: cycles, the conditioning's shifted copies and the out-of-range cycles; 7.6 MB at 480 samples and 31 states).
KEPT_RECORDS = 64


@dataclass(frozen=True)
class KalmanLaw:
    """A fitted estimator: the reduced model read at ``sensors``, its table and its noise.

    ``sigma`` [K] per sensor: the sensor's own uncertainty (:class:`KalmanNoise`) combined with
    the reduced model's RMS error at that output over the training cycles run open loop
    (:func:`model_errors`): the filter is told how far its model is from the (nonlinear) machine
    it was fitted on, so it does not trust a reading its model cannot explain.
    """

    model: ReducedModel
    table: OperatingTable
    sensors: tuple[str, ...]
    sigma: tuple[float, ...]
    noise: KalmanNoise = KalmanNoise()
    #: The discrete steps formed so far, shared by every law of one model, table and noise
    #: (:class:`KalmanEstimator`); None: each estimator forms its own.
    steps: dict | None = field(default=None, compare=False, repr=False)
    #: The state estimates of the records filtered last (a study asks for D and E of one record in
    #: several places): ``id(record) -> (record, names, states)``, the record kept so its id stays
    #: its own; at most :data:`KEPT_RECORDS`, the oldest dropped first.
    _runs: dict = field(default_factory=dict, init=False, compare=False, repr=False)

    def estimator(self) -> KalmanEstimator:
        return KalmanEstimator(self.model, self.table, self.sensors, self.sigma, self.noise, self.steps)

    def _states(self, record, names: list[str]) -> np.ndarray:
        """The filter's temperature state [K] ``(n, order)`` after each sample of a recorded cycle (columns ``names``)."""
        names = tuple(names)
        if not self._kept(record, names):
            self.filter_records([record], names)
        return self._runs[id(record)][2]

    def filter_records(self, records, names: list[str]) -> None:
        """Filter ``records`` (columns ``names``) side by side and keep their states for
        :meth:`predict_record` and :meth:`predict_stroke_record`: the cycles read at the same times
        go through :meth:`KalmanEstimator.states` together, a few stacked products per sample
        instead of a filter per cycle."""
        names = tuple(names)
        todo = [r for r in records if not self._kept(r, names)]
        groups: dict[tuple, list] = {}
        for record in todo:
            groups.setdefault((len(record.times), np.asarray(record.times, float).tobytes()), []).append(record)
        estimator = self.estimator()
        sensors = [names.index(s) for s in estimator.sensors]
        ambient = names.index(self.model.ambient)
        for group in groups.values():
            states = estimator.states(np.asarray(group[0].times, float),
                                      np.stack([r.sensors[:, sensors] for r in group]),
                                      np.stack([r.sensors[:, ambient] for r in group]),
                                      np.stack([r.screw_rpm for r in group]), np.stack([r.nut_rpm for r in group]))
            for record, state in zip(group, states):
                self._keep(record, names, state)

    def _keep(self, record, names: tuple[str, ...], states: np.ndarray) -> None:
        self._runs.pop(id(record), None)
        self._runs[id(record)] = (record, names, states)
        while len(self._runs) > KEPT_RECORDS:
            self._runs.pop(next(iter(self._runs)))

    def _kept(self, record, names: tuple[str, ...]) -> bool:
        hit = self._runs.get(id(record))
        return hit is not None and hit[0] is record and hit[1] == names

    def predict_record(self, record, names: list[str]) -> np.ndarray:
        """D [m] at every sample of a recorded cycle (columns ``names``)."""
        m = self.model
        d = m.outputs.index(ELONGATION_PROBE)
        return self._states(record, names) @ m.Cy[d] + float(m.dy[d])

    def predict_stroke_record(self, record, names: list[str]) -> np.ndarray | None:
        """E [m] ``(n, len(record.positions))`` at every sample of a recorded cycle: the filter's state read
        along the stroke (:attr:`.state_space.ReducedModel.C_stroke`, linear between its positions);
        None when the model has no such rows."""
        m = self.model
        if m.C_stroke is None or record.positions is None:
            return None
        out = self._states(record, names) @ m.C_stroke.T + m.d_stroke
        return np.array([np.interp(record.positions, m.stroke_x, row) for row in out])

    def document(self, provenance: dict | None = None) -> dict:
        """The JSON-able document (SI units) that :meth:`from_document` reads back."""
        m = self.model
        keep = [m.outputs.index(s) for s in (*self.sensors, ELONGATION_PROBE) if s != m.ambient]
        return {
            "format": FORMAT, "version": VERSION, "kind": "kalman",
            "output": {"name": "D", "unit": "m", "meaning": "the screw's thermal elongation; correct the axis by -D"},
            "inputs": [{"name": s, "unit": "K", "sigma_K": sg} for s, sg in zip(self.sensors, self.sigma)
                       if s != m.ambient]
                      + [{"name": m.ambient, "unit": "K", "role": AMBIENT_ROLE}],
            "speeds": "screw_rpm and nut_rpm commanded over the interval ending at each reading",
            "model": {"surfaces": m.surfaces, "sources": m.sources,
                      "outputs": [m.outputs[i] for i in keep],
                      "A0": m.A0.tolist(), "A_surface": m.A_surface.tolist(), "f_surface": m.f_surface.tolist(),
                      "Bq": m.Bq.tolist(), "Cy": m.Cy[keep].tolist(), "dy": m.dy[keep].tolist(),
                      "uniform": m.uniform.tolist(), "hankel": m.hankel.tolist()},
            "table": self.table.as_dict(),
            "noise": self.noise.as_dict(),
            **({} if m.C_stroke is None else {"stroke": {
                "x_m": m.stroke_x.tolist(), "C": m.C_stroke.tolist(), "d_m": m.d_stroke.tolist(),
                "meaning": "the positioning error at table position x_m[j]: E_j = C[j] . state + d_m[j] [m] (the state's "
                           "first len(A0) entries); linear in x between two positions; no x outside [x_m[0], x_m[-1]]",
                "multiply_adds_per_sample": 2 * m.order + 1,
                "cost": "the two rows around x (2 x order) and the interpolation (1), besides the filter's own step"}}),
            "provenance": provenance or {},
        }

    @classmethod
    def from_document(cls, document: dict, origin: str = "the Kalman law document") -> "KalmanLaw":
        """The estimator of ``document``, checked first (:func:`.law_files.check_law`: a one-line
        ``FeedthermError`` naming ``origin``, the key and the reason for anything that is not one)."""
        _require_kalman(document, origin)
        check_law(document, origin)
        return cls.build(document)

    @classmethod
    def from_file(cls, path) -> "KalmanLaw":
        """The estimator of the law file ``path`` (``law_kalman.json``), checked as :meth:`from_document`."""
        return cls.from_document(parse_law_file(path), str(path))

    @classmethod
    def build(cls, document: dict) -> "KalmanLaw":
        """The estimator of a document already checked (:meth:`from_document`)."""
        d = document["model"]
        ambient = next(i["name"] for i in document["inputs"] if i.get("role") == AMBIENT_ROLE)
        r, s = len(d["A0"]), len(d["surfaces"])  # shaped, so that a model without surfaces or sources keeps its axes
        model = ReducedModel(d["surfaces"], d["sources"], d["outputs"], np.array(d["A0"]),
                             np.array(d["A_surface"], dtype=float).reshape(s, r, r),
                             np.array(d["f_surface"], dtype=float).reshape(s, r),
                             np.array(d["Bq"], dtype=float).reshape(r, len(d["sources"])), np.array(d["Cy"]),
                             np.array(d["dy"]), np.array(d["uniform"]), np.array(d["hankel"]), ambient)
        stroke = document.get("stroke")  # optional: a law of D only before issue 34's item 3
        if stroke is not None:
            model = replace(model, stroke_x=np.array(stroke["x_m"], dtype=float), C_stroke=np.array(stroke["C"], dtype=float),
                            d_stroke=np.array(stroke["d_m"], dtype=float))
        n = document["noise"]
        noise = KalmanNoise(n["contact_K"], n["infrared_K"], n["heat_prior"], n["heat_drift_per_sqrt_h"],
                            n["heat_noise"], n["air_noise_K"], n["initial_K"], n.get("contact_offset_K", 0.0),
                            n.get("infrared_offset_K", 0.0))
        inputs = [i for i in document["inputs"] if i.get("role") != AMBIENT_ROLE]
        return cls(model, OperatingTable.from_dict(document["table"]), tuple(i["name"] for i in inputs),
                   tuple(float(i["sigma_K"]) for i in inputs), noise)


def model_errors(model: ReducedModel, table: OperatingTable, cycles, names: list[str]) -> dict[str, float]:
    """RMS difference [K, or m for D] between the reduced model run open loop (only the ambient
    read) and each output of the training cycles."""
    estimator = KalmanEstimator(model, table, [], [])
    squares = np.zeros(len(model.outputs))
    count = 0
    columns = [names.index(o) if o != ELONGATION_PROBE else None for o in model.outputs]
    ambient = names.index(model.ambient)
    for record in cycles:
        estimator.reset()
        for n, t in enumerate(record.times):
            estimator.update(t, {model.ambient: record.sensors[n, ambient]}, record.screw_rpm[n], record.nut_rpm[n])
            y = model.Cy @ estimator.x[:estimator.r] + model.dy
            truth = np.array([record.elongation[n] if j is None else record.sensors[n, j] for j in columns])
            squares += (y - truth) ** 2
            count += 1
    return dict(zip(model.outputs, np.sqrt(squares / max(count, 1))))
