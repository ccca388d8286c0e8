"""The FE model's displacements: the description's mechanics on the thermoelastic solve (:mod:`.elastic`).

What is read, as rows on the nodal temperatures (``rows @ T + offset``, zero at the
reference temperature):

- **D**, the displacement sensor ``mechanics.elongation``: the displacement at the target
  point (in the tetrahedron of its part holding it) minus the mount point's (none for a mount
  on the ground), along the sensor's direction;
- **the screw's profile**: the axial displacement averaged over each axial slab of the screw
  (the screw's sections, as its temperature profile; of the displacements at the mesh's
  nodes, interpolated linearly, in either space), minus the positioning reference point's.

The elastic system is built and factorised on first use (a run that never reads a
displacement does not pay for it).
"""

from __future__ import annotations

import math
import time

import numpy as np
import scipy.sparse as sp

from ...errors import ModelError
from ...system.geometry import drive_point
from ...system.mechanics import GROUND, joint_holds
from .. import pardiso
from .elastic import ElasticPart, PointTie, ThermoElastic, Tie
from .elastic_space import DisplacementSpace
from .readout import locate

__all__ = ["Deformation", "elastic_constants", "KEEP_SHARE"]

#: The factorisation is kept for the run's displacement fields when it holds at most this share of
#: the memory budget of the time loop's factors (models/pardiso.py); a larger one (the fine mesh's,
#: 2.8 GB) is dropped after the readings and built again for the fields, after the time loop.
KEEP_SHARE = 0.25


def elastic_constants(system) -> dict[str, ElasticPart]:
    """Each part's E, ν and α; a ModelError naming the field when a part's material lacks E or ν."""
    constants = {}
    for name, part in system.parts.items():
        material = system.materials[part.material]
        for field in ("youngs_modulus", "poisson_ratio"):
            if getattr(material, field) is None:
                raise ModelError(f"materials.{part.material}.{field}: not declared; the FE model computes the "
                                 f"displacements in 3D and needs it for every part's material ({name})")
        constants[name] = ElasticPart(material.youngs_modulus, material.poisson_ratio, material.expansion)
    return constants


def _facet_owner(tets: np.ndarray, facets: np.ndarray) -> np.ndarray:
    """Index (into ``tets`` (4, m)) of the tetrahedron each boundary facet (q, 3 node indices) belongs to."""
    n = int(max(tets.max(), facets.max())) + 1
    faces = np.sort(np.concatenate([tets[[0, 1, 2]], tets[[0, 1, 3]], tets[[0, 2, 3]], tets[[1, 2, 3]]], axis=1).T, axis=1)
    keys = (faces[:, 0].astype(np.int64) * n + faces[:, 1]) * n + faces[:, 2]
    order = np.argsort(keys)
    wanted = np.sort(facets, axis=1)
    query = (wanted[:, 0].astype(np.int64) * n + wanted[:, 1]) * n + wanted[:, 2]
    at = np.searchsorted(keys[order], query)
    if np.any(keys[order][np.minimum(at, keys.size - 1)] != query):
        raise ModelError("a contact facet is not a face of its part's tetrahedra (mesh inconsistent)")
    return order[at] % tets.shape[1]


class Deformation:
    """Displacement readings and fields of a :class:`~.bench.FemDiscretization`."""

    def __init__(self, fem):
        self.fem = fem
        self._elastic: ThermoElastic | None = None
        self._rows: tuple[np.ndarray, np.ndarray] | None = None
        self.stats: dict = {}

    # ------------------------------------------------------------------ set-up
    def elastic(self) -> ThermoElastic:
        if self._elastic is None:
            fem = self.fem
            by_part = elastic_constants(fem.system)
            constants = [by_part[name] for name in fem.part_names]
            started = time.perf_counter()
            self.space = DisplacementSpace(fem.points, fem.tets, fem.system.mechanics.elements)
            self._elastic = ThermoElastic(self.space, constants, np.asarray(fem.part_id), self._ties(constants),
                                          self._supports())
            self.stats = {"elastic_elements": self.space.elements, "elastic_unknowns": int(self._elastic.unknowns),
                          "elastic_assembly_seconds": round(time.perf_counter() - started, 2)}
        return self._elastic

    def _ties(self, constants: list[ElasticPart]) -> list[Tie]:
        fem = self.fem
        penalty = fem.system.mechanics.tie_penalty
        modulus = {name: constants[i].youngs_modulus for i, name in enumerate(fem.part_names)}
        ties = []
        for j in fem.joints:
            axes = joint_holds(j.joint.release)
            if not axes:
                continue
            quadrature = j.contact.quadrature(0.0)  # the moving group where its mesh is: mid-stroke
            stiffness = penalty * max(modulus[j.a], modulus[j.b]) / fem.mesh.sizes[j.a]
            x = np.einsum("qk,iqk->qi", quadrature.a_bary, fem.points[:, quadrature.a_nodes])  # (q, 3)
            a_nodes, a_values = self.space.shape(*self._under_facets(j.a, quadrature.a_nodes, x))
            b_nodes, b_values = self.space.shape(*self._under_facets(j.b, quadrature.b_nodes, x))
            ties.append(Tie(a_nodes, a_values, b_nodes, b_values, quadrature.weights, axes, stiffness,
                            name=f"joints[{j.index}]"))
        kin = fem.system.kinematics
        point = drive_point(fem.system)
        if point is not None:
            stiffness = penalty * max(modulus[kin.screw], modulus[kin.nut]) * fem.mesh.sizes[kin.screw]
            ties.append(PointTie(self._point(kin.nut, point, "kinematics.nut"),
                                 self._point(kin.screw, point, "kinematics.screw"), [0], stiffness, name="the drive"))
        return ties

    def _under_facets(self, part: str, facets: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The part's tetrahedron each facet (q, 3 node indices) bounds, and the barycentric
        coordinates in it of the points ``x`` (q, 3) [m].

        Returns the tetrahedra (q,; indices into the mesh's) and the coordinates (q, 4; a point
        off the facet by a chord's height lies just outside, so they may be slightly negative).
        """
        fem = self.fem
        in_part = fem.mesh.part_tets(part)
        tets = fem.mesh.tets[:, in_part]
        owner = _facet_owner(tets, facets)
        corners = fem.points[:, tets[:, owner].T]  # (3, q, 4)
        J = (corners[:, :, 1:] - corners[:, :, :1]).transpose(1, 0, 2)  # (q, 3, 3): edges from vertex 0
        lam = np.linalg.solve(J, (x - corners[:, :, 0].T)[:, :, None])[:, :, 0]
        return in_part[owner], np.column_stack([1.0 - lam.sum(axis=1), lam])

    def _supports(self) -> list[tuple[int, int]]:
        fem = self.fem
        held = []
        for support in fem.system.mechanics.supports:
            nodes = fem.mesh.part_nodes(support.part)
            gaps = np.linalg.norm(fem.points[:, nodes] - np.asarray(support.point)[:, None], axis=0)
            node = int(nodes[np.argmin(gaps)])
            held.extend((node, "xyz".index(axis)) for axis in support.fix)
        return held

    def _point(self, part: str, point, path: str) -> sp.csr_matrix:
        """The row (1, size) of the displacement space's basis at a point of ``part``."""
        fem = self.fem
        in_part = fem.mesh.part_tets(part)
        try:
            best, bary = locate(fem.points, fem.mesh.tets[:, in_part], np.asarray(point, dtype=float))
        except ValueError as exc:
            raise ModelError(f"{path}: {exc} ({part})") from None
        return self.space.rows(in_part[[best]], bary[None, :])

    @staticmethod
    def _along(row: sp.csr_matrix, direction) -> sp.csr_matrix:
        """A scalar reading row (1, N) of the nodes as a reading (1, 3N) of the displacement along ``direction``."""
        return sp.kron(row, sp.csr_matrix(np.asarray(direction, dtype=float)[None, :]), format="csr")

    def readings(self) -> sp.csr_matrix:
        """(1 + sections, 3 size): D, then the screw's section-mean axial displacement less the reference's."""
        fem, mech = self.fem, self.fem.system.mechanics
        sensor = mech.elongation
        d = self._along(self._point(sensor.target.part, sensor.target.point, "mechanics.elongation.target.point"),
                        sensor.direction)
        if sensor.mount != GROUND:
            d = d - self._along(self._point(sensor.mount.part, sensor.mount.point, "mechanics.elongation.mount.point"),
                                sensor.direction)
        if mech.positioning is None:  # no feed drive: D alone
            return sp.csr_matrix(d)
        reference = mech.positioning.reference
        ref = self._point(reference.part, reference.point, "mechanics.positioning.reference.point")
        bins = self.space.on_nodes(fem._screw_bins)
        ones = sp.csr_matrix(np.ones((bins.shape[0], 1)))
        axial = self._along(bins - ones @ ref, (1.0, 0.0, 0.0))
        return sp.vstack([d, axial]).tocsr()

    # ------------------------------------------------------------------ readout
    def rows(self) -> tuple[np.ndarray, np.ndarray]:
        """``(rows, offset)`` reading D and the screw's profile [m] from nodal temperatures [K]."""
        if self._rows is None:
            elastic = self.elastic()
            started = time.perf_counter()
            rows = elastic.reading_rows(self.readings())
            offset = -self.fem.system.temperatures.reference * rows.sum(axis=1)
            self._rows = (rows, offset)
            if elastic.factor_memory > KEEP_SHARE * pardiso.memory_budget():
                elastic.release()  # the time loop's factors need the room; the fields factorise again
                self.stats["elastic_factor_released"] = True
            self.stats.update(elastic_factor_seconds=round(elastic.factor_seconds, 2),
                              elastic_readings_seconds=round(time.perf_counter() - started, 2),
                              elastic_factor_MB=round(elastic.factor_memory / 2**20, 1))
        return self._rows

    def field(self, temperatures: np.ndarray) -> np.ndarray:
        """Displacement (N, 3) [m] of every node at nodal temperatures [K]."""
        rise = np.asarray(temperatures, dtype=float) - self.fem.system.temperatures.reference
        if not math.isfinite(float(rise.sum())):
            raise ModelError("a displacement field was asked for a state with NaN or infinite temperatures")
        return self.elastic().displacement(rise)
