"""What a Kalman estimator's file may hold: the typed schema of ``law_kalman.json``
(:meth:`.kalman.KalmanLaw.document` writes it, :meth:`.kalman.KalmanLaw.from_document` reads it).

As for the regression laws (:mod:`.law_schema`): unknown keys are errors, every number finite and
never a boolean or text, names sensor names, and every matrix of the shape the reduced model's
order ``r``, its surfaces, sources and outputs give it.  Besides the shapes:

- the reduced model is symmetric (``A0`` and each ``A_surface``, to rounding: a Galerkin
  projection in the symmetric coordinates, :mod:`.state_space`), so that it is stable at every
  operating point of its table when it is at the table's own entries; the validation checks
  that it is (the largest eigenvalue of ``A0 + Σ h_s A_s`` negative at every entry): an unstable
  model's estimate grows without bound;
- the table's speeds increase strictly (it is interpolated between them), its coefficients are
  not negative;
- exactly one input is the ambient (the model's input), every other a sensor among the model's
  outputs with a positive σ [K]; ``D`` is an output;
- the declared noise's standard deviations are not negative and at most 100 K (temperatures) or
  10 (relative heat errors): a larger one says the reading or the model says nothing.
"""

from __future__ import annotations

from typing import Annotated, Any, Literal

import numpy as np
from pydantic import AfterValidator, Field, model_validator

from ...constants import ELONGATION_PROBE
from .law_schema import (
    FORMAT,
    Coordinate,
    Finite,
    NonNegative,
    Output,
    SensorName,
    StrictDocument,
    Temperature,
    Text,
    entries,
    positive,
    versions,
)

#: The role of the ambient among a Kalman document's inputs (:data:`.kalman.AMBIENT_ROLE`).
AMBIENT_ROLE = "ambient (model input)"
SYMMETRY_TOLERANCE = 1e-9

KelvinSigma = Annotated[float, positive(100.0, "K", "a reading known to no better than 100 K reads nothing", zero=True)]
RelativeSigma = Annotated[float, positive(10.0, "", "a heat known to no better than 10 times itself is not known",
                                           zero=True)]
Matrix = list[list[Finite]]
Vector = list[Finite]
# Surfaces and sources are named as the description names them (letters, digits, underscores).
Names = list[SensorName]


class KalmanInput(StrictDocument):
    name: SensorName
    unit: Literal["K"] = "K"
    sigma_K: Annotated[KelvinSigma, AfterValidator(lambda v: _nonzero(v, "sigma_K"))] | None = None
    role: Literal[AMBIENT_ROLE] | None = None


def _nonzero(value: float, what: str) -> float:
    if value == 0:
        raise ValueError(f"{what} 0 K: a reading with no uncertainty at all cannot be weighed against the model")
    return value


class KalmanModel(StrictDocument):
    surfaces: Names
    sources: Names
    outputs: Names
    A0: Annotated[Matrix, Field(min_length=1)]
    A_surface: list[Matrix]
    f_surface: Matrix
    Bq: Matrix
    Cy: Matrix
    dy: Vector
    uniform: Vector
    hankel: Vector


class KalmanTable(StrictDocument):
    screw_rpm: Annotated[list[NonNegative], Field(min_length=1)]
    relative_rpm: Annotated[list[NonNegative], Field(min_length=1)]
    dual: bool
    h_W_per_m2K: list[list[list[NonNegative]]]
    q_W: list[list[Vector]]
    h_stopped_W_per_m2K: list[NonNegative]
    q_stopped_W: Vector
    ambient_K: Temperature


class KalmanNoiseBlock(StrictDocument):
    contact_K: KelvinSigma
    infrared_K: KelvinSigma
    heat_prior: RelativeSigma
    heat_drift_per_sqrt_h: RelativeSigma
    heat_noise: RelativeSigma
    air_noise_K: KelvinSigma
    initial_K: KelvinSigma
    contact_offset_K: KelvinSigma = 0.0
    infrared_offset_K: KelvinSigma = 0.0


class KalmanStroke(StrictDocument):
    x_m: Annotated[list[Coordinate], Field(min_length=1)]
    C: Matrix
    d_m: Vector
    meaning: Text | None = None
    multiply_adds_per_sample: Annotated[int, Field(ge=0)] | None = None
    cost: Text | None = None


def _rows(path: str, matrix: list, rows: int, columns: int | None, what: str) -> None:
    if len(matrix) != rows:
        raise ValueError(f"{path}: {entries(len(matrix))}, expected {rows} ({what})")
    if columns is not None:
        for i, row in enumerate(matrix):
            if len(row) != columns:
                raise ValueError(f"{path}[{i}]: {entries(len(row))}, expected {columns} (the model's order)")


def _increasing(path: str, values: list[float]) -> None:
    for i in range(1, len(values)):
        if not values[i] > values[i - 1]:
            raise ValueError(f"{path}[{i}]: {values[i]:g} does not lie above {path}[{i - 1}] ({values[i - 1]:g}); "
                             "the table is interpolated between increasing values")


def _symmetric(path: str, matrix: np.ndarray) -> None:
    largest = float(np.abs(matrix).max()) if matrix.size else 0.0
    asymmetry = np.abs(matrix - matrix.T)
    if asymmetry.size and float(asymmetry.max()) > SYMMETRY_TOLERANCE * largest:
        i, j = np.unravel_index(int(np.argmax(asymmetry)), asymmetry.shape)
        raise ValueError(f"{path}[{i}][{j}]: {matrix[i, j]:.6g}, but [{j}][{i}] is {matrix[j, i]:.6g}; the reduced "
                         "model is symmetric (state_space)")


class KalmanLawDocument(StrictDocument):
    """The Kalman estimator's document (:class:`.kalman.KalmanLaw`)."""

    format: Literal[FORMAT]
    version: versions(1)
    kind: Literal["kalman"]
    output: Output | None = None
    inputs: Annotated[list[KalmanInput], Field(min_length=1)]
    speeds: Text | None = None
    model: KalmanModel
    table: KalmanTable
    noise: KalmanNoiseBlock
    stroke: KalmanStroke | None = None
    conditioning: dict[str, Any] | None = None
    provenance: dict[str, Any] | None = None

    @model_validator(mode="after")
    def _consistent(self) -> "KalmanLawDocument":
        self._check_inputs()
        m, t = self.model, self.table
        r, s, k = len(m.A0), len(m.surfaces), len(m.sources)
        _rows("model.A0", m.A0, r, r, "a square matrix")
        _rows("model.A_surface", m.A_surface, s, None, "one matrix per surface")
        for i, block in enumerate(m.A_surface):
            _rows(f"model.A_surface[{i}]", block, r, r, "a square matrix of the model's order")
        _rows("model.f_surface", m.f_surface, s, r, "one row per surface")
        _rows("model.Bq", m.Bq, r, None, "one row per state")
        for i, row in enumerate(m.Bq):
            if len(row) != k:
                raise ValueError(f"model.Bq[{i}]: {entries(len(row))}, expected {k} (one per source)")
        _rows("model.Cy", m.Cy, len(m.outputs), r, "one row per output")
        _rows("model.dy", m.dy, len(m.outputs), None, "one per output")
        _rows("model.uniform", m.uniform, r, None, "one per state")
        a, b = len(t.screw_rpm), len(t.relative_rpm)
        _increasing("table.screw_rpm", t.screw_rpm)
        _increasing("table.relative_rpm", t.relative_rpm)
        for name, grid, width in (("h_W_per_m2K", t.h_W_per_m2K, s), ("q_W", t.q_W, k)):
            _rows(f"table.{name}", grid, a, None, "one per screw speed")
            for i, plane in enumerate(grid):
                _rows(f"table.{name}[{i}]", plane, b, None, "one per relative speed")
                for j, row in enumerate(plane):
                    _rows(f"table.{name}[{i}][{j}]", row, width, None,
                          "one per surface" if width == s else "one per source")
        _rows("table.h_stopped_W_per_m2K", t.h_stopped_W_per_m2K, s, None, "one per surface")
        _rows("table.q_stopped_W", t.q_stopped_W, k, None, "one per source")
        if self.stroke is not None:
            x = self.stroke.x_m
            _increasing("stroke.x_m", x)
            _rows("stroke.C", self.stroke.C, len(x), r, "one row per position")
            _rows("stroke.d_m", self.stroke.d_m, len(x), None, "one per position")
        self._check_stable()
        return self

    def _check_inputs(self) -> None:
        ambient = [i for i, item in enumerate(self.inputs) if item.role is not None]
        if len(ambient) != 1:
            raise ValueError(f"inputs: {len(ambient)} inputs have the role {AMBIENT_ROLE!r}; exactly one is the "
                             "ambient")
        seen: dict[str, int] = {}
        for i, item in enumerate(self.inputs):
            if item.name in seen:
                raise ValueError(f"inputs[{i}]: {item.name!r} is inputs[{seen[item.name]}] already; a law reads each "
                                 "sensor once")
            seen[item.name] = i
            if item.role is None:
                if item.sigma_K is None:
                    raise ValueError(f"inputs[{i}].sigma_K: missing (required for a sensor)")
                if item.name not in self.model.outputs:
                    raise ValueError(f"inputs[{i}]: {item.name!r} is not among model.outputs "
                                     f"({', '.join(self.model.outputs)})")
        outputs: dict[str, int] = {}
        for i, name in enumerate(self.model.outputs):
            if name in outputs:
                raise ValueError(f"model.outputs[{i}]: {name!r} is model.outputs[{outputs[name]}] already")
            outputs[name] = i
        if ELONGATION_PROBE not in outputs:
            raise ValueError(f"model.outputs: no {ELONGATION_PROBE!r}; the estimator's output is D")

    def _check_stable(self) -> None:
        """Symmetric, and negative definite at every entry of the table (module notes)."""
        m, t = self.model, self.table
        a0 = np.array(m.A0, dtype=float)
        _symmetric("model.A0", a0)
        surface = np.array(m.A_surface, dtype=float).reshape(len(m.surfaces), len(a0), len(a0))
        for i, block in enumerate(surface):
            _symmetric(f"model.A_surface[{i}]", block)
        entries = [("table.h_stopped_W_per_m2K", np.array(t.h_stopped_W_per_m2K, dtype=float))]
        for i, plane in enumerate(t.h_W_per_m2K):
            entries += [(f"table.h_W_per_m2K[{i}][{j}]", np.array(row, dtype=float)) for j, row in enumerate(plane)]
        for path, h in entries:
            with np.errstate(all="ignore"):  # an overflow is an unstable model, reported below
                matrix = a0 + np.tensordot(h, surface, axes=1)
                try:
                    largest = float(np.linalg.eigvalsh(matrix).max()) if np.all(np.isfinite(matrix)) else np.inf
                except np.linalg.LinAlgError:
                    largest = float("inf")
            if not largest < 0:
                raise ValueError(f"{path}: the reduced model is not stable there (its largest eigenvalue is "
                                 f"{largest:.3g} 1/s, not negative): its estimate would grow without bound")
