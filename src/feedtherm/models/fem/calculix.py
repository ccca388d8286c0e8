"""The FE model as a CalculiX input deck: the same mesh, materials, heats, films and joints.

What a deck holds (CalculiX 2.20 keywords, SI units, temperatures in kelvin):

- every vertex (``*NODE``; the moving group's parts shifted to position ``k``) and every
  tetrahedron (``C3D4``, one element set per part, the nodes positively oriented as
  CalculiX expects: node 4 on the side of face 1-2-3's normal);
- each part's material (``*CONDUCTIVITY``, ``*DENSITY``, ``*SPECIFIC HEAT``);
- each joint as a surface-to-surface ``*CONTACT PAIR``: the slave is the facets of the
  integration side (the finer mesh) that touch the other part at position k, the master
  the other part's facets they face; ``*GAP CONDUCTANCE`` is the joint's
  ``A_declared / (R'' A_mesh)`` [W/(m²·K)] as in :mod:`.coupling`.  The pair is *tied*
  (``*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TIED``): its heat flows whatever the gap
  between two faceted cylinders, and in a transient it flows as in a steady state.  With
  the ``LINEAR`` or ``HARD`` behaviours CalculiX 2.20 conducts less across a pair in a
  transient than its conductance says (two isothermal blocks through h = 2 W/(m²·K): the
  effective conductance was about 1.6, and depended on the time step), while its steady
  states were right;
- each surface's exchange with its sink as ``*FILM`` on its exposed facets: the coefficient
  ``h`` of the boundary conditions, times the exposed share of the facet (what a joint
  covers at position k is not exposed) and the declared-over-mesh area factor of
  :meth:`~.bench.FemDiscretization.surface_exposure`;
- the heats as nodal ``*CFLUX``, the model's own heat vector at position k.

The two solvers then differ only in what each does inside an element: CalculiX integrates
films and contacts consistently and may use a consistent capacity, feedtherm lumps them.
``benchmarks/bench_calculix.py`` runs both over the same 3 h.
"""

from __future__ import annotations

import re

import numpy as np

from ...boundary import BoundaryConditions
from .bench import FemDiscretization
from .faces import surface_facets

__all__ = ["calculix_deck", "read_temperatures"]

#: CalculiX's faces of a C3D4 element, as local node indices (F1 … F4).
C3D4_FACES = ((0, 1, 2), (0, 3, 1), (1, 3, 2), (2, 3, 0))


class _FaceIndex:
    """Element and face number (1-based, CalculiX's) of each boundary triangle of the mesh."""

    def __init__(self, tets: np.ndarray):
        self._index: dict[tuple[int, int, int], tuple[int, int]] = {}
        for face, local in enumerate(C3D4_FACES):
            nodes = np.sort(tets[list(local)], axis=0).T
            for element, key in enumerate(map(tuple, nodes)):
                self._index.setdefault(key, (element + 1, face + 1))

    def __call__(self, triangle) -> tuple[int, int]:
        return self._index[tuple(sorted(int(n) for n in triangle))]


def _lines(values: np.ndarray, per_line: int = 8) -> list[str]:
    return [", ".join(str(int(v)) for v in values[i:i + per_line]) for i in range(0, len(values), per_line)]


def calculix_deck(model: FemDiscretization, bc: BoundaryConditions, k: int, *, time_step: float,
                  duration: float, output_interval: float, initial: float) -> str:
    """A CalculiX deck of ``model`` under ``bc`` with the moving group held at position ``k``.

    Parameters
    ----------
    model : FemDiscretization
    bc : BoundaryConditions
        Heats, film coefficients and sinks (frozen: CalculiX takes them as constants).
    k : int
        Grid position of the moving group.
    time_step, duration, output_interval : float
        Fixed increment, length of the transient and interval of the printed temperatures [s].
    initial : float
        Uniform initial temperature [K].
    """
    system = model.system
    mesh = model.mesh
    points = model.points.copy()
    offset = float(model.positions[k])
    for name in mesh.parts:
        if system.parts[name].moving:
            points[0, mesh.part_nodes(name)] += offset
    faces = _FaceIndex(model.tets)
    out = [f"** feedtherm: the FE model of {system.meta.name}, moving group at position {k} "
           f"(offset {offset * 1e3:.3f} mm), {bc.mode} mode", "*NODE, NSET=NALL"]
    out += [f"{i + 1}, {x:.9e}, {y:.9e}, {z:.9e}" for i, (x, y, z) in enumerate(points.T)]

    for i, name in enumerate(mesh.parts):
        tets = mesh.part_tets(name)
        out.append(f"*ELEMENT, TYPE=C3D4, ELSET=E_{name.upper()}")
        out += [f"{e + 1}, {a + 1}, {b + 1}, {c + 1}, {d + 1}" for e, (a, b, c, d) in zip(tets, model.tets[:, tets].T)]
    for material_name in sorted({system.parts[name].material for name in mesh.parts}):
        material = system.materials[material_name]
        out += [f"*MATERIAL, NAME=M_{material_name.upper()}", "*CONDUCTIVITY", f"{material.conductivity:.9e}",
                "*DENSITY", f"{material.density:.9e}", "*SPECIFIC HEAT", f"{material.specific_heat:.9e}"]
    for name in mesh.parts:
        out.append(f"*SOLID SECTION, ELSET=E_{name.upper()}, MATERIAL=M_{system.parts[name].material.upper()}")

    out += _contacts(model, k, faces)
    out += [f"*INITIAL CONDITIONS, TYPE=TEMPERATURE", f"NALL, {initial:.9e}",
            "*STEP, INC=1000000", "*HEAT TRANSFER, DIRECT", f"{time_step:.9e}, {duration:.9e}"]
    out += _films(model, bc, k, faces)
    heat = model.heat_vector(bc, k)
    out.append("*CFLUX")
    out += [f"{n + 1}, 11, {heat[n]:.9e}" for n in np.nonzero(heat)[0]]
    every = max(1, int(round(output_interval / time_step)))
    out += [f"*NODE PRINT, NSET=NALL, FREQUENCY={every}", "NT", "*END STEP", ""]
    return "\n".join(out)


def _contacts(model: FemDiscretization, k: int, faces: _FaceIndex) -> list[str]:
    out = []
    for j in model.joints:
        cq = model._cq(j, k)
        h_c = j.joint.area / (j.joint.tcr * cq.area)
        label = f"J{j.index}"
        for side, nodes in (("S", cq.a_nodes), ("M", cq.b_nodes)):
            out.append(f"*SURFACE, NAME={label}{side}, TYPE=ELEMENT")
            out += [f"{element}, S{face}" for element, face in sorted({faces(tri) for tri in nodes})]
        out += [f"*SURFACE INTERACTION, NAME={label}", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TIED", "1e3",
                "*GAP CONDUCTANCE", f"{h_c:.9e}, -1e30, 0.", f"{h_c:.9e}, 1e30, 0.",
                f"*CONTACT PAIR, INTERACTION={label}, TYPE=SURFACE TO SURFACE", f"{label}S, {label}M"]
    return out


def _films(model: FemDiscretization, bc: BoundaryConditions, k: int, faces: _FaceIndex) -> list[str]:
    """``*FILM`` lines: each exposed facet with its coefficient and its surface's sink."""
    out = ["*FILM"]
    for name, surface in model.system.surfaces.items():
        transfer = bc.surfaces.get(name)
        if transfer is None or transfer.total == 0.0:
            continue
        tri = model.triangles[surface.part]
        mask = surface_facets(surface, model.system.parts[surface.part], model.points, tri)
        _, weights, owner = tri.quadrature(model.points, np.nonzero(mask)[0])
        s = model.surfaces[name]
        covered = np.zeros(weights.size, dtype=bool)
        for other, j in s["partners"]:
            covered |= model._covered(name, other, j, k)
        exposed = np.bincount(owner, weights=weights * ~covered, minlength=tri.size)
        area = np.bincount(owner, weights=weights, minlength=tri.size)
        scale = 1.0
        if surface.area is not None:
            scale = surface.area / exposed.sum()
        for facet in np.nonzero(exposed > 0.0)[0]:
            element, face = faces(tri.nodes[:, facet])
            h = transfer.total * scale * exposed[facet] / area[facet]
            out.append(f"{element}, F{face}, {transfer.sink:.9e}, {h:.9e}")
    return out


_BLOCK = re.compile(r"temperatures for set \S+ and time\s+(\S+)")


def read_temperatures(dat: str, n_nodes: int) -> tuple[np.ndarray, np.ndarray]:
    """Times [s] and nodal temperatures (times, nodes) [K] from a CalculiX ``.dat`` file's ``NT`` blocks."""
    times, states = [], []
    state = None
    for line in dat.splitlines():
        match = _BLOCK.search(line)
        if match:
            times.append(float(match.group(1)))
            state = np.full(n_nodes, np.nan)
            states.append(state)
            continue
        fields = line.split()
        if state is not None and len(fields) == 2:
            state[int(fields[0]) - 1] = float(fields[1])
    return np.array(times), np.array(states)
