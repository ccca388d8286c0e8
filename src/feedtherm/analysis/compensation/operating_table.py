"""Heats and surface coefficients on a grid of motor speeds: what the estimator knows of the loads.

A controller knows its motor speeds, not the loss models.  The state-space estimator therefore
carries a table of each source's heat [W] and each surface's coefficient [W/(m²·K)] from the
nominal description's boundary-condition step (frozen coefficients, at the reference ambient),
on a grid over the speed envelope of the description's conditions, interpolated bilinearly in
(screw speed, screw-nut relative speed) and held at the grid's edge beyond it; a standstill
(both motors below :data:`STANDSTILL_RPM`) has its own entry.  The same table goes into the
exported law, so the controller's evaluation and the fitted estimator are the same function.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...boundary import boundary_conditions_at
from ...boundary.operating import OperatingPoint
from ...system.overlay import Overlay
from ...system.schema import FeedSystem
from ..random_cycles import SpeedEnvelope
from .state_space import coefficients

#: Grid points along the screw speed and the relative speed.  Heats and coefficients vary
#: smoothly with speed (powers of 0.5-1.5, physics/), so 6 × 4 points over the paper bench's
#: envelope (396-2214 rpm, 36-54 rpm) interpolate them within about 1 % (checked in the tests).
GRID = (6, 4)
#: Below this speed [rpm] of both motors the axis is at a standstill.
STANDSTILL_RPM = 1.0


@dataclass(frozen=True)
class OperatingTable:
    """``h`` (surfaces) and ``q`` (sources) at a standstill and on the speed grid."""

    screw_rpm: np.ndarray  # (a,)
    relative_rpm: np.ndarray  # (b,); a single drive: (1,) with the nut at rest
    dual: bool
    h: np.ndarray  # (a, b, surfaces): from the nodes to the air (in series with the conduction to the face)
    q: np.ndarray  # (a, b, sources)
    h_stopped: np.ndarray
    q_stopped: np.ndarray
    ambient: float  # [K] where the table was evaluated

    def at(self, screw_rpm: float, nut_rpm: float) -> tuple[np.ndarray, np.ndarray]:
        """``h``, ``q`` at the commanded speeds [rpm] (signs do not matter: the table reverses)."""
        screw, relative = abs(screw_rpm), abs(screw_rpm - nut_rpm)
        if abs(screw_rpm) < STANDSTILL_RPM and abs(nut_rpm) < STANDSTILL_RPM:
            return self.h_stopped, self.q_stopped
        i, a = _bracket(self.screw_rpm, screw)
        j, b = _bracket(self.relative_rpm, relative if self.dual else 0.0)

        def blend(v):
            if len(self.relative_rpm) == 1:
                return (1 - a) * v[i, 0] + a * v[i + 1, 0] if len(self.screw_rpm) > 1 else v[0, 0]
            return ((1 - a) * (1 - b) * v[i, j] + a * (1 - b) * v[i + 1, j]
                    + (1 - a) * b * v[i, j + 1] + a * b * v[i + 1, j + 1])

        return blend(self.h), blend(self.q)

    def as_dict(self) -> dict:
        return {"screw_rpm": self.screw_rpm.tolist(), "relative_rpm": self.relative_rpm.tolist(), "dual": self.dual,
                "h_W_per_m2K": self.h.tolist(), "q_W": self.q.tolist(), "h_stopped_W_per_m2K": self.h_stopped.tolist(),
                "q_stopped_W": self.q_stopped.tolist(), "ambient_K": self.ambient}

    @classmethod
    def from_dict(cls, d: dict) -> "OperatingTable":
        return cls(np.array(d["screw_rpm"], float), np.array(d["relative_rpm"], float), bool(d["dual"]),
                   np.array(d["h_W_per_m2K"], float), np.array(d["q_W"], float), np.array(d["h_stopped_W_per_m2K"], float),
                   np.array(d["q_stopped_W"], float), float(d["ambient_K"]))


def _bracket(axis: np.ndarray, value: float) -> tuple[int, float]:
    """Index ``i`` and weight ``a`` of ``value`` between ``axis[i]`` and ``axis[i + 1]`` (held at the ends)."""
    if len(axis) == 1:
        return 0, 0.0
    value = min(max(value, axis[0]), axis[-1])
    i = int(min(np.searchsorted(axis, value, side="right") - 1, len(axis) - 2))
    return i, float((value - axis[i]) / (axis[i + 1] - axis[i]))


def build_table(system: FeedSystem, surfaces: list[str], sources: list[str], ambient: float, *,
                overlay: Overlay | None = None, grid: tuple[int, int] = GRID,
                film: np.ndarray | None = None) -> OperatingTable:
    """Evaluate the boundary conditions on the grid (see the module's notes)."""
    envelope = SpeedEnvelope.of(system)
    lead = system.kinematics.lead
    screws = np.unique(np.linspace(*envelope.screw, grid[0]))
    relatives = np.unique(np.linspace(*envelope.relative, grid[1])) if envelope.dual else np.array([0.0])
    h = np.zeros((len(screws), len(relatives), len(surfaces)))
    q = np.zeros((len(screws), len(relatives), len(sources)))
    for i, screw in enumerate(screws):
        for j, relative in enumerate(relatives):
            nut = screw - relative if envelope.dual else 0.0
            bc = boundary_conditions_at(system, OperatingPoint(screw, nut, ambient, lead), overlay)
            h[i, j], q[i, j] = coefficients(bc, surfaces, sources, film)
    bc = boundary_conditions_at(system, OperatingPoint(0.0, 0.0, ambient, lead), overlay)
    h0, q0 = coefficients(bc, surfaces, sources, film)
    return OperatingTable(screws, relatives, envelope.dual, h, q, h0, q0, ambient)
