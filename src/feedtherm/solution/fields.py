"""Full temperature fields of a run on its mesh (FE runs): the typed series a Solution carries."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ..constants import KELVIN_OFFSET
from ..models.fields import FieldMesh

@dataclass(frozen=True, eq=False)
class FieldSeries:
    """The FE temperature field at a few instants, with the moving parts where they were.

    Parameters
    ----------
    points : ndarray, shape (n, 3)
        Mesh vertices with every part at rest [m].
    tets : ndarray of int, shape (m, 4)
        Linear tetrahedra (vertex indices).
    part_id : ndarray of int, shape (m,)
        The part of each tetrahedron, an index into ``part_names``.
    part_names : sequence of str
        Part names, e.g. ``["base", "screw", "worktable", ...]``.
    moving_part : sequence of bool
        Per part: does it move with the worktable group?  A node of a moving part is drawn
        at ``points + [offset, 0, 0]``; a node may not belong to a moving and a fixed part.
    snapshot_times : ndarray, shape (k,)
        Time of each snapshot [s], increasing.
    temperatures : ndarray, shape (k, n)
        Nodal temperatures [K].
    offsets : ndarray, shape (k,)
        Displacement of the moving group along x at each snapshot [m].
    screw_x : ndarray, shape (b,)
        Axial positions along the screw at which its displacement is given [m], increasing.
    screw_displacement : ndarray, shape (k, b)
        The screw's axial thermal displacement at ``screw_x`` [m].
    title : str
        What the run was, e.g. ``"condition <name>, physics mode, fem model (medium mesh)"``.
    displacements : ndarray, shape (k, n, 3), optional
        Thermal displacement of every vertex [m] from the reference temperature (the
        thermoelastic solution), or None.
    """

    points: np.ndarray
    tets: np.ndarray
    part_id: np.ndarray
    part_names: Sequence[str]
    moving_part: Sequence[bool]
    snapshot_times: np.ndarray
    temperatures: np.ndarray
    offsets: np.ndarray
    screw_x: np.ndarray
    screw_displacement: np.ndarray
    title: str = ""
    displacements: np.ndarray | None = None

    def __post_init__(self) -> None:
        fix = lambda name, value: object.__setattr__(self, name, value)  # noqa: E731
        fix("points", np.asarray(self.points, dtype=float))
        fix("tets", np.asarray(self.tets))
        fix("part_id", np.asarray(self.part_id))
        fix("part_names", tuple(str(name) for name in self.part_names))
        fix("moving_part", tuple(bool(flag) for flag in self.moving_part))
        for name in ("snapshot_times", "temperatures", "offsets", "screw_x", "screw_displacement"):
            fix(name, np.asarray(getattr(self, name), dtype=float))
        if self.displacements is not None:
            fix("displacements", np.asarray(self.displacements, dtype=float))
        self._check()

    def _check(self) -> None:
        n = len(self.points)
        k = len(self.snapshot_times)
        b = len(self.screw_x)
        problems = []

        def expect(name: str, shape: tuple[int, ...]) -> None:
            actual = getattr(self, name).shape
            if actual != shape:
                problems.append(f"{name} has shape {actual}, expected {shape}")

        expect("points", (n, 3))
        if self.tets.ndim != 2 or self.tets.shape[1] != 4:
            problems.append(f"tets has shape {self.tets.shape}, expected (m, 4)")
        elif not np.issubdtype(self.tets.dtype, np.integer):
            problems.append("tets must hold integers")
        elif self.tets.size and (self.tets.min() < 0 or self.tets.max() >= n):
            problems.append(f"tets refer to vertices outside 0…{n - 1}")
        expect("part_id", (len(self.tets),))
        if not np.issubdtype(self.part_id.dtype, np.integer):
            problems.append("part_id must hold integers")
        elif self.part_id.size and (self.part_id.min() < 0 or self.part_id.max() >= len(self.part_names)):
            problems.append(f"part_id outside 0…{len(self.part_names) - 1} (one per part name)")
        if len(self.moving_part) != len(self.part_names):
            problems.append(f"{len(self.moving_part)} moving_part flags for {len(self.part_names)} parts")
        expect("snapshot_times", (k,))
        if k == 0:
            problems.append("no snapshot")
        elif np.any(np.diff(self.snapshot_times) <= 0):
            problems.append("snapshot_times must increase")
        expect("temperatures", (k, n))
        expect("offsets", (k,))
        expect("screw_x", (b,))
        if b and np.any(np.diff(self.screw_x) <= 0):
            problems.append("screw_x must increase")
        expect("screw_displacement", (k, b))
        checked = ["points", "snapshot_times", "temperatures", "offsets", "screw_x", "screw_displacement"]
        if self.displacements is not None:
            expect("displacements", (k, n, 3))
            checked.append("displacements")
        for name in checked:
            if not np.all(np.isfinite(getattr(self, name))):
                problems.append(f"{name} holds NaN or infinite values")
        if problems:
            raise ValueError("invalid FieldSeries: " + "; ".join(problems))
        self.moving_nodes  # noqa: B018 (raises if a node is shared by a moving and a fixed part)

    @cached_property
    def moving_nodes(self) -> np.ndarray:
        """Per node: does it belong to a moving part (bool)?"""
        return _moving_nodes(self)

    @property
    def n_snapshots(self) -> int:
        return len(self.snapshot_times)

    def celsius(self, snapshot: int) -> np.ndarray:
        """Nodal temperatures of one snapshot [°C]."""
        return self.temperatures[snapshot] - KELVIN_OFFSET

    def displaced_points(self, snapshot: int) -> np.ndarray:
        """Vertices with the moving parts at their position of that snapshot [m]."""
        moved = self.points.copy()
        moved[self.moving_nodes, 0] += self.offsets[snapshot]
        return moved


def _moving_nodes(series: FieldSeries) -> np.ndarray:
    moving = np.asarray(series.moving_part, dtype=bool)[series.part_id]
    n = len(series.points)
    in_moving = np.zeros(n, dtype=bool)
    in_fixed = np.zeros(n, dtype=bool)
    in_moving[series.tets[moving].ravel()] = True
    in_fixed[series.tets[~moving].ravel()] = True
    shared = np.flatnonzero(in_moving & in_fixed)
    if shared.size:
        raise ValueError(
            f"invalid FieldSeries: {shared.size} mesh nodes belong to both a moving and a fixed part "
            f"(e.g. node {shared[0]}); moving parts must own their nodes "
            "(the mesh of each part owns its nodes)"
        )
    return in_moving


# --------------------------------------------------------------------------- ParaView files


def field_series(mesh: FieldMesh, snapshots, screw_x, screw_displacement, title: str = "",
                 displacements: np.ndarray | None = None) -> FieldSeries:
    """A FieldSeries from a model's mesh and its ``(time, nodal temperatures, offset)`` snapshots."""
    return FieldSeries(points=mesh.points, tets=mesh.tets, part_id=mesh.part_id, part_names=mesh.part_names,
                       moving_part=mesh.moving_part, snapshot_times=np.array([t for t, _, _ in snapshots]),
                       temperatures=np.array([state for _, state, _ in snapshots]),
                       offsets=np.array([offset for _, _, offset in snapshots]),
                       screw_x=screw_x, screw_displacement=screw_displacement, title=title,
                       displacements=displacements)
