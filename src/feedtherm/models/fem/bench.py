"""The finite element discretisation of a whole feed system, for the shared time integrator.

:class:`FemDiscretization` meshes every part of a system with gmsh (:mod:`.geometry`),
couples the parts' separate meshes at their joints with non-conforming interface
conductances (:mod:`.coupling`), and is a :class:`~feedtherm.models.interface.ThermalModel`,
position by position of the moving group: ``capacity`` is lumped [J/K], ``ambient_links`` is
``∫ h N dA`` over each declared surface's exposed facets [W/K] per node, the sensors are read
by interpolation in their tetrahedron, and the screw's section means by volume.

Heat placement (:func:`~feedtherm.models.interface.heat_inputs`): a share of a source into
a part goes in by volume, unless another part receiving the same source is joined to it;
then it enters over that joint's contact (the screw–nut friction half into the nut's bore,
half into the screw under the nut at position k; the guideway friction into the carriages'
bottoms and the rail tops under them). Surfaces lose heat only where no joint covers them
(the screw under the bearings and, at position k, under the nut; the rail tops under the
carriages). See ``docs/fem-model.md``.
"""

from __future__ import annotations

import math
import time

import numpy as np
import scipy.sparse as sp

from ...constants import ELONGATION_PROBE
from ...errors import ModelError
from ...system.geometry import bounds
from ...system.schema import FeedSystem
from ..fields import FieldMesh
from ..interface import AffineParameter, HeatInput, PositionWindow, ThermalModel, cycle_weights, weighted_sum
from .conduction import cell_basis, conduction_matrix
from .coupling import CONTACT_TOLERANCE, Contact, ContactQuadrature, interface_matrix, side_load, touching
from .deformation import Deformation, elastic_constants
from .faces import curvature_sag, surface_facets
from .facets import RULE, NearestFacets, boundary_triangles
from .geometry import mesh_system
from .readout import point_matrix, slab_matrix, tet_volumes

__all__ = ["FemDiscretization"]


class _Joint:
    """One joint: its contact (A = the integration side, the finer one) and how A moves relative to B."""

    def __init__(self, index, joint, a, b, contact: Contact, moves: bool, sign: float):
        self.index, self.joint, self.a, self.b = index, joint, a, b
        self.contact = contact
        self.moves = moves  # one side moves with the group, the other does not
        self.sign = sign  # A's points go into B's frame shifted by sign · offset
        self._cq: dict[int, ContactQuadrature] = {}
        self._K: dict[int, sp.csr_matrix] = {}

    def key(self, k: int) -> int:
        return k if self.moves else 0

    def parts(self) -> tuple[str, str]:
        return self.a, self.b


class FemDiscretization(ThermalModel):
    """FE model of ``system`` at mesh ``density`` (``"coarse"``, ``"medium"``, ``"fine"``).

    Parameters
    ----------
    system : FeedSystem
    density : str
    axial_cells : int
        At least this many screw bins for the section means (and the grid of positions, as
        in the fast model).
    min_positions : int
        At least this many moving steps per stroke (``K``).
    lumped_contact : bool
        Lumped (default, M-matrix) or consistent interface matrices, see :mod:`.coupling`.
    use_cache : bool
        Read and write the mesh cache.
    conductivity_factor : dict, optional
        Part name → factor on its conductivity. A diagnostic: a factor of 1000 makes a part
        nearly isothermal, as the fast model's lumped parts are.

    Attributes for field output: ``points`` (3, N) [m] with every part at rest (the moving
    group at the middle of the stroke, offset 0), ``tets`` (4, M), ``part_id`` (M,) into
    ``part_names``, ``moving_part`` (one flag per part).
    """

    #: a factor per grid position is what holds an FE run's memory: the resolved motion steps by windows
    windowed_motion = True

    def __init__(self, system: FeedSystem, density: str = "coarse", *, axial_cells: int = 100,
                 min_positions: int = 20, lumped_contact: bool = True, use_cache: bool = True,
                 conductivity_factor: dict[str, float] | None = None):
        started = time.perf_counter()
        elastic_constants(system)  # refused before meshing: the run would need them at its first step
        self.system = system
        self.density = density
        self.lumped_contact = lumped_contact
        self.conductivity_factor = dict(conductivity_factor or {})
        self.mesh = mesh = mesh_system(system, density, use_cache=use_cache)
        self.points = mesh.points
        self.tets = mesh.tets
        self.part_id = mesh.part_of_tet
        self.part_names = list(mesh.parts)
        self.moving_part = [system.parts[name].moving for name in mesh.parts]
        self.n_nodes = mesh.points.shape[1]
        self._moving = {name: part.moving for name, part in system.parts.items()}
        self._setup_positions(axial_cells, min_positions)
        self._setup_volumes()
        self.triangles = {name: boundary_triangles(mesh.points, mesh.tets[:, mesh.part_tets(name)]) for name in mesh.parts}
        self._nearest = {name: NearestFacets(mesh.points, tri) for name, tri in self.triangles.items()}
        self.sag = {name: curvature_sag(system.parts[name], mesh.points, self.triangles[name]) for name in mesh.parts}
        self.fixed = self._conduction()
        self._setup_joints()
        for j in self.joints:
            if not j.moves:
                self.fixed = self.fixed + self._joint_matrix(j, 0)
        self.fixed = self.fixed.tocsr()
        self._setup_surfaces()
        self._setup_readout()
        self._conductance: dict[int, sp.csr_matrix] = {}
        self._heat_shares: dict[tuple, np.ndarray] = {}
        self._surface_areas: dict[tuple[str, int], tuple[np.ndarray, np.ndarray]] = {}
        self._coverage: dict[tuple, np.ndarray] = {}
        self._stats = self._summary(time.perf_counter() - started)

    def coarse_space(self) -> sp.csr_matrix:
        """Each part's uniform field (one column per part): the iterative solver balances each part's heat."""
        groups = np.empty(self.n_nodes, dtype=np.intp)
        for index, name in enumerate(self.part_names):
            lo, hi = self.mesh.node_ranges[name]
            groups[lo:hi] = index
        return sp.csr_matrix((np.ones(self.n_nodes), (np.arange(self.n_nodes), groups)),
                             shape=(self.n_nodes, len(self.part_names)))

    # ------------------------------------------------------------------ set-up
    def _setup_positions(self, axial_cells: int, min_positions: int) -> None:
        kin = self.system.kinematics
        if kin is None:  # no feed drive: one position, no screw sections
            self.dx, self.positions = 1.0, np.zeros(1)
            self.screw_edges, self.screw_centres = np.zeros(0), np.zeros(0)
            return
        lo, hi = bounds(self.system.parts[kin.screw])
        length = hi[0] - lo[0]
        count = max(min_positions, math.ceil(kin.stroke / (length / axial_cells)))
        self.dx = kin.stroke / count
        self.positions = -kin.stroke / 2.0 + self.dx * np.arange(count + 1)
        n = max(1, int(round(length / self.dx)))
        edges = lo[0] + self.dx * np.arange(n + 1)
        edges[-1] = hi[0]
        self.screw_edges = edges
        self.screw_centres = 0.5 * (edges[1:] + edges[:-1])

    def _setup_volumes(self) -> None:
        mesh = self.mesh
        vol = tet_volumes(mesh.points, mesh.tets)
        self.tet_volume = vol
        self.node_volume = np.bincount(mesh.tets.ravel(), weights=np.tile(vol / 4.0, 4), minlength=self.n_nodes)
        rho_c = np.empty(mesh.tets.shape[1])
        self.conductivity = np.empty(mesh.tets.shape[1])
        for i, name in enumerate(mesh.parts):
            material = self.system.materials[self.system.parts[name].material]
            sel = mesh.part_of_tet == i
            rho_c[sel] = material.density * material.specific_heat
            self.conductivity[sel] = material.conductivity * self.conductivity_factor.get(name, 1.0)
        self.capacity = np.bincount(mesh.tets.ravel(), weights=np.tile(rho_c * vol / 4.0, 4), minlength=self.n_nodes)
        self.part_volume = {name: float(vol[mesh.part_tets(name)].sum()) for name in mesh.parts}

    def _cell_basis(self):
        from skfem import MeshTet

        if getattr(self, "_basis", None) is None:
            skmesh = MeshTet(np.ascontiguousarray(self.mesh.points), np.ascontiguousarray(self.mesh.tets))
            self._basis = cell_basis(skmesh)
        return self._basis

    def _conduction(self) -> sp.csr_matrix:
        return conduction_matrix(self._cell_basis(), self.conductivity)

    def _setup_joints(self) -> None:
        self.joints: list[_Joint] = []
        for i, joint in enumerate(self.system.joints):
            a, b = joint.between
            if joint.sliding and self._moving[a] == self._moving[b]:
                raise ModelError(f"joints[{i}]: a sliding joint needs one moving and one fixed part ({a}, {b})")
            if not joint.sliding and self._moving[a] != self._moving[b]:
                raise ModelError(f"joints[{i}]: {a} and {b}: a joint between a moving and a fixed part must be sliding")
            if self.mesh.sizes[b] < self.mesh.sizes[a]:
                a, b = b, a  # integrate over the finer side
            tol = CONTACT_TOLERANCE + self.sag[a] + self.sag[b]
            level = 1 + max(0, math.ceil(math.log2(self.mesh.sizes[a] / self.mesh.sizes[b]) - 1e-9))
            contact = Contact(self.points, self.triangles[a], self.triangles[b], tol, name=f"{a}-{b}", level=level)
            self.joints.append(_Joint(i, joint, a, b, contact, moves=joint.sliding,
                                      sign=float(self._moving[a]) - float(self._moving[b])))

    def _setup_surfaces(self) -> None:
        """Per declared surface: quadrature of its facets and the joints that may cover them."""
        self.surfaces = {}
        for name, surface in self.system.surfaces.items():
            part = surface.part
            tri = self.triangles[part]
            mask = surface_facets(surface, self.system.parts[part], self.points, tri, path=f"surfaces.{name}")
            facets = np.nonzero(mask)[0]
            if facets.size == 0:
                raise ModelError(f"surfaces.{name}: no facet of {part}'s mesh lies on the selected faces")
            x, w, owner = tri.quadrature(self.points, facets)
            partners = [(j.b if j.a == part else j.a, j) for j in self.joints if part in j.parts()]
            nodes = tri.nodes[:, owner].T
            self.surfaces[name] = {"x": x, "w": w, "nodes": nodes, "normals": tri.normals[:, owner],
                                   "bary": np.tile(RULE[0], (facets.size, 1)),
                                   "unique": np.unique(nodes.ravel(), return_inverse=True),
                                   "partners": partners, "part": part,
                                   "moves": any(self._moving[q] != self._moving[part] for q, _ in partners)}

    def _setup_readout(self) -> None:
        mesh, system = self.mesh, self.system
        names, rows = [], []
        for name, sensor in system.sensors.items():
            if name == system.room.ambient_sensor:  # reported from the boundary conditions
                continue
            names.append(name)
            tets = mesh.tets[:, mesh.part_tets(sensor.part)]
            try:
                rows.append(point_matrix(mesh.points, tets, [np.array(sensor.position)], self.n_nodes))
            except ValueError as exc:
                raise ModelError(f"sensors.{name}.position: {exc} ({sensor.part})") from None
        self.probe_names = [*names, ELONGATION_PROBE]
        self._probe = sp.vstack(rows).tocsr() if rows else sp.csr_matrix((0, self.n_nodes))
        self._screw_bins = self._screw_sections()
        self.deformation = Deformation(self)
        self._probe_rows = None
        # capacity weights: the volume mean, as a part has one material, and Σ_p C_p T̄_p = C·T exactly
        self._part_weights = {}
        for name in mesh.parts:
            nodes = mesh.part_nodes(name)
            c = self.capacity[nodes]
            self._part_weights[name] = (nodes, c / c.sum())

    def _screw_sections(self) -> sp.csr_matrix:
        """(sections, nodes): the volume-mean of each axial section of the screw; no rows without a feed drive."""
        if self.system.kinematics is None:
            return sp.csr_matrix((0, self.n_nodes))
        screw, mesh = self.system.kinematics.screw, self.mesh
        try:
            return slab_matrix(mesh.points, mesh.tets[:, mesh.part_tets(screw)], self.screw_edges, self.n_nodes)
        except ValueError as exc:  # a screw shorter than a few of its elements: a section without a tetrahedron
            raise ModelError(f"parts.{screw}: the mesh cannot resolve the screw's {len(self.screw_edges) - 1} "
                             f"axial sections of {self.dx * 1e3:.3g} mm ({exc}); use a finer mesh or a longer screw") from None

    # ------------------------------------------------------------------ joints
    def _cq(self, j: _Joint, k: int) -> ContactQuadrature:
        key = j.key(k)
        if key not in j._cq:
            shift = j.sign * self.positions[k] if j.moves else 0.0
            j._cq[key] = j.contact.quadrature(shift)
        return j._cq[key]

    def contact_area(self, j: _Joint, k: int = 0) -> float:
        """Contact area of joint ``j`` in the mesh at position k [m²]."""
        return self._cq(j, k).area

    def _joint_matrix(self, j: _Joint, k: int) -> sp.csr_matrix:
        key = j.key(k)
        if key not in j._K:
            cq = self._cq(j, k)
            h_c = j.joint.area / (j.joint.tcr * cq.area)  # R''_eff = R'' A_geo / A_declared
            j._K[key] = interface_matrix(self.n_nodes, cq, h_c, lumped=self.lumped_contact)
        return j._K[key]

    def joint_matrix(self, index: int, k: int = 0) -> sp.csr_matrix:
        """The interface matrix of ``system.joints[index]`` at position k [W/K]."""
        return self._joint_matrix(self.joints[index], k)

    def joint_sides(self, index: int) -> tuple[np.ndarray, np.ndarray]:
        """Node indices of the two parts of ``system.joints[index]``, in its declared order."""
        a, b = self.system.joints[index].between
        return self.mesh.part_nodes(a), self.mesh.part_nodes(b)

    # ------------------------------------------------------------------ interface
    def conductance(self, k: int) -> sp.csr_matrix:
        """Conduction in every part and every joint's coupling, moving group at position k [W/K]."""
        if k not in self._conductance:
            G = self.fixed
            for j in self.joints:
                if j.moves:
                    G = G + self._joint_matrix(j, k)
            self._conductance[k] = G.tocsr()
        return self._conductance[k]

    def window_conductance(self, window: PositionWindow) -> sp.csr_matrix:
        """:meth:`conductance` weighted over ``window``'s positions, formed from the moving joints' matrices
        alone: the positions' whole matrices (the fixed conduction again in each, 31 MB a position at the
        fine mesh) are never built for a windowed run."""
        return self._weighted_conductance(window.weights, window.positions)

    def averaged_conductance(self) -> sp.csr_matrix:
        """The cycle average of :meth:`conductance`, formed as :meth:`window_conductance` is."""
        weights = cycle_weights(len(self.positions))
        return self._weighted_conductance(weights, range(len(weights)))

    def _weighted_conductance(self, weights, positions) -> sp.csr_matrix:
        G = self.fixed
        for j in self.joints:
            if j.moves:
                G = G + weighted_sum(weights, [self._joint_matrix(j, k) for k in positions])
        return G.tocsr()

    def surface_area(self, name: str, k: int) -> tuple[np.ndarray, np.ndarray]:
        """Nodes and their exposed areas ``∫ N dA`` [m²] of surface ``name`` at position k."""
        s = self.surfaces[name]
        key = (name, k if s["moves"] else 0)
        if key not in self._surface_areas:
            covered = np.zeros(s["w"].size, dtype=bool)
            for other, j in s["partners"]:
                covered |= self._covered(name, other, j, k)
            w = (s["w"] * ~covered)[:, None] * s["bary"]
            nodes, inverse = s["unique"]
            areas = np.bincount(inverse, weights=w.ravel(), minlength=nodes.size)
            self._surface_areas[key] = (nodes, areas)
        return self._surface_areas[key]

    def _covered(self, name: str, other: str, j: _Joint, k: int) -> np.ndarray:
        """Quadrature points of surface ``name`` that part ``other`` covers at position k."""
        s = self.surfaces[name]
        relative = float(self._moving[s["part"]]) - float(self._moving[other])
        key = (name, other, k if relative else 0)
        if key not in self._coverage:
            x = s["x"].copy()
            x[0] += relative * self.positions[k]  # into the other part's mesh frame
            self._coverage[key] = touching(x, s["normals"], self._nearest[other], j.contact.tol)
        return self._coverage[key]

    def surface_exposure(self, name: str, k: int) -> tuple[np.ndarray, np.ndarray]:
        """Nodes and exposed areas of surface ``name`` at position k, scaled to a declared area.

        The description's area is authoritative: the mesh's ``∫N dA`` over the exposed facets
        only shares it out.
        """
        nodes, areas = self.surface_area(name, k)
        declared = self.system.surfaces[name].area
        if declared is not None:
            areas = areas * (declared / areas.sum())
        return nodes, areas

    def heat_distribution(self, heat: HeatInput, k: int) -> np.ndarray:
        """Fractions over the nodes of a heat input at position k: by volume, or over its contact."""
        return self._heat_share(heat.part, heat.over_contact_with, k)

    def _joined(self, a: str, b: str) -> _Joint | None:
        return next((j for j in self.joints if {j.a, j.b} == {a, b}), None)

    def _heat_share(self, part: str, partner: str | None, k: int) -> np.ndarray:
        if partner is None:
            key = (part, None, 0)
        else:
            j = self._joined(part, partner)
            key = (part, partner, j.key(k))
        if key not in self._heat_shares:
            if partner is None:  # by volume
                nodes = self.mesh.part_nodes(part)
                share = np.zeros(self.n_nodes)
                v = np.bincount(self.mesh.tets[:, self.mesh.part_tets(part)].ravel(),
                                weights=np.tile(self.tet_volume[self.mesh.part_tets(part)] / 4.0, 4),
                                minlength=self.n_nodes)
                share[nodes] = v[nodes] / v[nodes].sum()
            else:  # over the contact
                share = side_load(self.n_nodes, self._cq(j, k), "a" if part == j.a else "b")
            self._heat_shares[key] = share
        return self._heat_shares[key]

    # ------------------------------------------------------------------ affine parameters
    def _parts_of_material(self) -> dict[str, list[str]]:
        out: dict[str, list[str]] = {}
        for name in self.part_names:
            out.setdefault(self.system.parts[name].material, []).append(name)
        return out

    def affine_parameters(self) -> list[AffineParameter]:
        """Every material's conductivity and expansion and every joint's conductance ``1/tcr``:
        conduction is linear in each tetrahedron's conductivity, a joint's interface matrix in its
        conductance, the thermal load of the elastic solve in each part's expansion (and a part's
        nodes are its own: the parts' meshes meet only through the joints)."""
        materials = self.system.materials
        out = [AffineParameter(f"materials.{m}.conductivity", "conductance", float(materials[m].conductivity))
               for m in self._parts_of_material()]
        out += [AffineParameter(f"joints[{j.index}].conductance", "conductance", 1.0 / float(j.joint.tcr), moves=j.moves)
                for j in self.joints]
        out += [AffineParameter(f"materials.{m}.expansion", "expansion", float(materials[m].expansion))
                for m in self._parts_of_material()]
        return out

    def conductance_term(self, name: str, k: int) -> sp.csr_matrix:
        head, _, field = name.rpartition(".")
        if head.startswith("materials.") and field == "conductivity":
            material = head.removeprefix("materials.")
            terms = self.__dict__.setdefault("_material_terms", {})
            if material not in terms:
                per_tet = np.zeros(self.tets.shape[1])
                for part in self._parts_of_material()[material]:
                    per_tet[self.mesh.part_tets(part)] = self.conductivity_factor.get(part, 1.0)
                terms[material] = conduction_matrix(self._cell_basis(), per_tet)
            return terms[material]
        if head.startswith("joints[") and field == "conductance":
            j = self.joints[int(head[len("joints["):-1])]
            return self._joint_matrix(j, k) * float(j.joint.tcr)
        return super().conductance_term(name, k)

    def displacement_term(self, name: str) -> tuple[np.ndarray, np.ndarray]:
        head, _, field = name.rpartition(".")
        if not (head.startswith("materials.") and field == "expansion"):
            return super().displacement_term(name)
        material = head.removeprefix("materials.")
        rows, _ = self.displacement_rows()
        nodes = np.concatenate([self.mesh.part_nodes(p) for p in self._parts_of_material()[material]])
        term = np.zeros_like(rows)
        term[:, nodes] = rows[:, nodes] / float(self.system.materials[material].expansion)
        return term, -self.system.temperatures.reference * term.sum(axis=1)

    # ------------------------------------------------------------------ readout
    def screw_mean(self, states: np.ndarray) -> np.ndarray:
        """Volume mean screw temperature per axial bin, shape ``(..., bins)``."""
        states = np.asarray(states)
        return (self._screw_bins @ states.reshape(-1, self.n_nodes).T).T.reshape(*states.shape[:-1], -1)

    def displacement_rows(self) -> tuple[np.ndarray, np.ndarray]:
        return self.deformation.rows()

    def displacement_field(self, state: np.ndarray) -> np.ndarray:
        return self.deformation.field(state)

    def probe(self, T: np.ndarray, k: int | None = None) -> np.ndarray:
        """Sensor temperatures [K] (system order, without the ambient), then D [m].

        ``k`` is accepted for the shared integrator; the moving group's sensors sit at fixed
        points of its own mesh, so the values do not depend on it.
        """
        rows, offset = self.probe_rows()
        return rows @ T + offset

    def probe_rows(self, k: int | None = None) -> tuple[sp.csr_matrix, np.ndarray]:
        """The sensors' rows and D's (:meth:`probe` as ``rows @ T + offset``), the same at every position."""
        if self._probe_rows is None:
            d_rows, d_offset = self.displacement_rows()
            rows = sp.vstack([self._probe, sp.csr_matrix(d_rows[:1])]).tocsr()
            offset = np.zeros(rows.shape[0])
            offset[-1] = d_offset[0]
            self._probe_rows = (rows, offset)
        return self._probe_rows

    def part_means(self, states: np.ndarray) -> dict[str, np.ndarray]:
        """Capacity-weighted (= volume) mean temperature of every part, shape ``(...)`` per part."""
        states = np.asarray(states)
        return {name: states[..., nodes] @ w for name, (nodes, w) in self._part_weights.items()}

    def part_capacities(self) -> dict[str, float]:
        """ρcV [J/K] of every part: its vertices' lumped capacities summed."""
        return {name: float(self.capacity[nodes].sum()) for name, (nodes, _) in self._part_weights.items()}

    def field_mesh(self) -> FieldMesh:
        """The vertices (every part at rest, the moving group mid-stroke) and tetrahedra."""
        return FieldMesh(points=np.ascontiguousarray(self.points.T), tets=np.ascontiguousarray(self.tets.T),
                         part_id=np.asarray(self.part_id), part_names=tuple(self.part_names),
                         moving_part=tuple(bool(m) for m in self.moving_part))

    @property
    def stats(self) -> dict:
        return {**self._stats, **self.deformation.stats}

    def _summary(self, seconds: float) -> dict:
        mesh = self.mesh
        return {
            "density": self.density,
            "vertices": int(self.n_nodes),
            "tetrahedra": int(mesh.tets.shape[1]),
            "parts": {name: {"vertices": int(mesh.node_ranges[name][1] - mesh.node_ranges[name][0]),
                             "tetrahedra": int(mesh.part_tets(name).size),
                             "size_mm": round(mesh.sizes[name] * 1e3, 3)} for name in mesh.parts},
            "mesh_seconds": round(mesh.seconds, 2),
            "mesh_cached": mesh.cached,
            "mesh_file": str(mesh.path) if mesh.path else None,
            "setup_seconds": round(seconds, 2),
            "positions": len(self.positions),
            "screw_bins": len(self.screw_centres),
        }
