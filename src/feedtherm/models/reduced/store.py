"""Projected models kept on disk, so that a run of a cached reduced model never builds the full one.

On the fine mesh the FE model takes about 29 s to build with its 41 positions, and its basis
read back and projected another 3 s; the run itself takes a few.  A :class:`~.projection.Projection`
holds everything the reduced model runs and reads with (operators per position and their affine
terms, readouts, the cycle-averaged boundary basis, the field mesh, the basis itself for the
fields), so it is saved under ``cache_root()/projections/<key>-<domain>.npz`` and read back instead.

The key names what the projection's operators are built from, without building the full model
(a key made of its operators, as :func:`~.basis.basis_key` is, would cost the build it saves),
and nothing else:

- ``inputs``, given by whoever knows how the full model is built (the registry): the
  description's :func:`~.training.structure` (its geometry, materials' capacities, joints,
  where heat enters and surfaces are — not the conductivities, contact resistances, fixed
  coefficients and expansions the projection takes as parameters, nor what only the boundary
  conditions read), the mesh file's digest, the full model's name and arguments;
- the tolerance of the basis;
- the digest of the code that builds operators, bases and projections (:data:`OPERATOR_CODE`:
  the FE and reduced models, the model interface, the solvers, the geometry they read);
- the versions of Python and of the libraries that build them (:data:`LIBRARIES`).

``<domain>`` is the digest of the ranges its basis was trained over (:mod:`.training`): a
description of the same key whose parameters lie inside a file's ranges runs on it
(:class:`~.model.ProjectedModel` weighs the terms by its values); one outside builds a
projection of its own.  The last projection read or built stays in memory, so the runs of a
calibration or an uncertainty study read the file once per process.

What a projection built here is trained over is the caller's choice
(:attr:`~feedtherm.models.options.ModelOptions.reduced_training`):

- a batch (calibration, uncertainty, compensation) prepares one trained over the ranges the
  description declares, and takes only such a one from the cache: its runs at other numbers
  then find it (``"batch"``);
- a single run (``feedtherm run``, a validation's runs) builds one trained at the description's
  own numbers (``"description"``): the basis of one point, not of the eight a declared domain
  trains at, so the paper bench's coarse projection takes 10 s to build, not 26 s (one thread),
  and it is exact where it runs;
- either takes a cached projection that holds the description, whatever it was trained over,
  and so does the default (``"declared"``, which trains over the declared ranges when it builds).

Files are written atomically, a damaged one is rebuilt, and the directory keeps the most
recently used within the basis cache's budget (:mod:`.disk`).
"""

from __future__ import annotations

import hashlib
import math
import json
import platform
import time
from dataclasses import replace
from collections import OrderedDict
from functools import lru_cache
from importlib import metadata
from pathlib import Path
from typing import Callable

import numpy as np
import scipy.sparse as sp

from ...constants import cache_root
from ...system.schema import FeedSystem
from ..fields import FieldMesh
from ..interface import BoundaryBasis, ThermalModel
from .basis import CHECK_CANDIDATES, Basis, film_parameters, moment_basis, steady_check
from .disk import read_npz, write_npz
from .model import ProjectedModel
from .projection import Projection, project
from .training import (CHECK_SEED, declared_domain, domain_digest, inside, omitted_values, random_points,
                       training_points)

__all__ = ["cached_projected_model", "file_digest", "operator_code_digest", "projection_key", "projection_cache_path"]

#: Changes whenever the file layout below changes.
STORE_VERSION = 8
#: The distributions whose code builds a full model, its basis or its projection.
LIBRARIES = ("numpy", "scipy", "scikit-fem", "gmsh", "meshio", "pymor")
_PACKAGE = Path(__file__).resolve().parents[2]  # src/feedtherm
#: The package's files (or folders) whose code makes a projection: the key's code digest.
OPERATOR_CODE = ("models/fem", "models/reduced", "models/interface.py", "models/direct.py", "models/pardiso.py",
                 "models/fields.py", "system/geometry.py", "system/mechanics.py", "system/surfaces.py", "constants.py")
#: Projections kept in memory (the last ones read or built) for the runs of a batch.
IN_MEMORY = 1
_in_memory: OrderedDict[Path, tuple[Projection, tuple[int, int]]] = OrderedDict()  # path → (projection, its file's identity)


@lru_cache(maxsize=1)
def operator_code_digest() -> str:
    """Digest of the files of :data:`OPERATOR_CODE`, by relative path."""
    h = hashlib.blake2b(digest_size=20)
    files = set()
    for entry in OPERATOR_CODE:
        root = _PACKAGE / entry
        files.update(p for p in (root.rglob("*.py") if root.is_dir() else [root]) if p.is_file())
    for path in sorted(files):
        h.update(str(path.relative_to(_PACKAGE)).encode() + b"\0")
        h.update(path.read_bytes())
        h.update(b"\0")
    return h.hexdigest()


def library_versions() -> dict[str, str]:
    """The installed versions of :data:`LIBRARIES` and of Python ("absent" for one not installed)."""
    versions = {"python": platform.python_version(), "machine": platform.machine()}
    for name in LIBRARIES:
        try:
            versions[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            versions[name] = "absent"
    return versions


def file_digest(path: Path) -> str | None:
    """Digest of a file's bytes, or None when it does not exist."""
    try:
        with open(path, "rb") as f:
            return hashlib.file_digest(f, "blake2b").hexdigest()
    except FileNotFoundError:
        return None


def projection_key(inputs: dict, tolerance: float) -> str:
    """Digest of the module notes' key: ``inputs`` (JSON-able), the tolerance, the code and the libraries."""
    data = {"store_version": STORE_VERSION, "inputs": inputs, "tolerance": float(tolerance),
            "code": operator_code_digest(), "libraries": library_versions()}
    return hashlib.blake2b(json.dumps(data, sort_keys=True).encode(), digest_size=20).hexdigest()


def projection_cache_path(key: str, domain: dict | None = None) -> Path:
    """The file of the projection of ``key`` trained over ``domain``."""
    return cache_root() / "projections" / f"{key}-{domain_digest(domain or {})}.npz"


def full_domain(system: FeedSystem, trained: dict[str, tuple[float, float]], kinds: dict[str, str]) -> dict:
    """Where a projection holds, for every number :func:`~.training.structure` leaves out: the
    ranges its basis was trained over; any expansion (the displacements are linear in it, the
    basis does not depend on it); the description's own value for a number the full model's
    operators are not linear in (a fast model's conductivity: another value is another model)."""
    domain = {}
    for name, value in omitted_values(system).items():
        if name in trained:
            domain[name] = trained[name]
        elif kinds.get(name) == "expansion":
            domain[name] = (0.0, math.inf)
        else:
            domain[name] = (value, value)
    return domain


def _holds(domain: dict, system: FeedSystem) -> bool:
    """Whether ``system``'s numbers lie where a projection of ``domain`` holds (:func:`full_domain`)."""
    values = omitted_values(system)
    return set(values) == set(domain) and inside(domain, values)


def _identity(path: Path) -> tuple[int, int] | None:
    """The file's inode and size (an atomic rewrite or a damaged file changes one), None when it is gone."""
    try:
        status = path.stat()
    except OSError:
        return None
    return status.st_ino, status.st_size


def _last_used(path: Path) -> float:
    """When the file was last read or written (0 for one another process has just pruned)."""
    try:
        return path.stat().st_mtime
    except OSError:
        return 0.0


def _remember(path: Path, projection: Projection) -> None:
    identity = _identity(path)
    if identity is None:  # not written (an unwritable cache): nothing to remember it by
        return
    _in_memory[path] = (projection, identity)
    _in_memory.move_to_end(path)
    while len(_in_memory) > IN_MEMORY:
        _in_memory.popitem(last=False)


def _find(key: str, system: FeedSystem, declared_only: bool = False) -> Projection | None:
    """A projection of ``key`` whose domain holds ``system``'s parameters (with ``declared_only``, one
    trained over the declared ranges): from memory, or from disk (the most recently used file first)."""
    directory = projection_cache_path(key).parent
    for path, (projection, identity) in reversed(_in_memory.items()):
        if path.parent == directory and path.name.startswith(f"{key}-") and _identity(path) == identity \
                and _holds(projection.domain or {}, system) \
                and not (declared_only and projection.trained_over != "declared"):
            _in_memory.move_to_end(path)
            return projection
    files = sorted(directory.glob(f"{key}-*.npz"), key=_last_used, reverse=True)
    for path in files:
        stem = path.stem
        projection = read_npz(path, lambda data: _from_arrays(data, stem, system, declared_only))
        if projection is not None:
            _remember(path, projection)
            return projection
    return None


def cached_projected_model(system: FeedSystem, tolerance: float, build_full: Callable[[], ThermalModel],
                           inputs: Callable[[], dict | None], training: str = "declared") -> ProjectedModel:
    """The reduced model of ``build_full()``'s full model, from the cache when it holds one that fits.

    ``inputs()`` gives what the full model is built from (module notes), or None when it cannot
    be said before building it (its mesh file does not exist yet): the model is then built and
    saved under the inputs the build leaves.  ``training`` (module notes): "declared" and "batch"
    train a basis built here over the ranges ``system`` declares for its parameters
    (:mod:`.training`), "description" at ``system``'s own numbers; "batch" takes from the cache
    only a projection trained over declared ranges.
    """
    if training not in ("declared", "description", "batch"):
        raise ValueError(f"reduced_training: no training {training!r}")
    started = time.perf_counter()
    known = inputs()
    if known is not None:
        projection = _find(projection_key(known, tolerance), system, declared_only=training == "batch")
        if projection is not None:
            return ProjectedModel.from_projection(projection, system, build_full, projection_cached=True,
                                                  projection_seconds=round(time.perf_counter() - started, 2))
    full = build_full()
    kinds = {p.name: p.kind for p in full.affine_parameters()}
    declared = declared_domain(system, [n for n, kind in kinds.items() if kind == "conductance"] + list(film_parameters(full)))
    # at the description's own numbers: its declared ranges left out (a description that declares none
    # trains alike either way, and its projection serves a batch too)
    own = training == "description" and any(high > low for low, high in declared.values())
    trained = {} if own else declared
    basis = moment_basis(full, tolerance=tolerance, points=training_points(trained, {}))
    projection = project(full, basis)
    candidates = random_points(trained, CHECK_CANDIDATES, CHECK_SEED)
    check = steady_check(full, basis, tuple(candidates)) if candidates else {}
    projection = replace(projection, domain=full_domain(system, trained, kinds), trained_over="description" if own
                         else "declared", full_stats={**projection.full_stats, **check})
    known = inputs()  # the full model's build has written its mesh file
    if known is not None:
        key = projection_key(known, tolerance)
        path = projection_cache_path(key, projection.domain)
        write_npz(path, _to_arrays(projection, path.stem))
        _remember(path, projection)
    return ProjectedModel.from_projection(projection, system, lambda: full, projection_cached=False,
                                          projection_seconds=round(time.perf_counter() - started, 2))


# ---------------------------------------------------------------------------- file layout
_ARRAYS = ("full_capacity", "stored", "conductance", "exposure", "moving_surfaces", "exposure_change",
           "exposure_rows", "exposure_areas", "entries", "probe_rows", "probe_offsets", "screw", "positions",
           "screw_edges", "screw_centres", "displacement_rows", "displacement_offsets",
           "conductance_values", "conductance_terms", "conductance_moving", "conductance_term_change",
           "expansion_values", "displacement_terms", "displacement_offset_terms")


def _sparse(prefix: str, matrix: sp.csr_matrix) -> dict[str, np.ndarray]:
    matrix = sp.csr_matrix(matrix)
    return {f"{prefix}_data": matrix.data, f"{prefix}_indices": matrix.indices, f"{prefix}_indptr": matrix.indptr,
            f"{prefix}_shape": np.array(matrix.shape)}


def _read_sparse(data, prefix: str) -> sp.csr_matrix:
    return sp.csr_matrix((data[f"{prefix}_data"], data[f"{prefix}_indices"], data[f"{prefix}_indptr"]),
                         shape=tuple(data[f"{prefix}_shape"]))


def _to_arrays(p: Projection, key: str) -> dict[str, np.ndarray]:
    b = p.basis
    arrays = {name: getattr(p, name) for name in _ARRAYS}
    arrays |= {"store_version": STORE_VERSION, "key": key, "dx": p.dx,
               "surfaces": np.array(p.surfaces), "sources": np.array(p.sources),
               "probe_names": np.array(p.probe_names), "full_stats": json.dumps(p.full_stats),
               "part_names": np.array(list(p.parts)), "part_rows": np.array(list(p.parts.values())),
               "has_part_capacity": p.part_capacity is not None,
               "part_capacity": np.array([(p.part_capacity or {}).get(name, np.nan) for name in p.parts]),
               "basis_vectors": b.vectors, "basis_singular_values": b.singular_values,
               "basis_tolerance": b.tolerance, "basis_snapshots": b.snapshots, "basis_seconds": b.seconds,
               "basis_cached": b.cached,
               "conductance_parameters": np.array(p.conductance_parameters, dtype=str),
               "expansion_parameters": np.array(p.expansion_parameters, dtype=str),
               "domain_names": np.array(list(p.domain or {}), dtype=str), "trained_over": np.array(p.trained_over),
               "domain_bounds": np.array(list((p.domain or {}).values()), dtype=float).reshape(-1, 2)}
    arrays |= _sparse("averaged_exposure", p.averaged.exposure) | _sparse("averaged_distribution", p.averaged.distribution)
    arrays["has_film"] = p.averaged.film is not None
    arrays["averaged_film"] = np.zeros(0) if p.averaged.film is None else np.asarray(p.averaged.film, dtype=float)
    arrays["has_displacement_fields"] = p.displacement_basis is not None
    if p.displacement_basis is not None:
        arrays |= {"displacement_basis": p.displacement_basis, "displacement_origin": p.displacement_origin}
    mesh = p.field_mesh
    arrays["has_field_mesh"] = mesh is not None
    if mesh is not None:
        arrays |= {"mesh_points": mesh.points, "mesh_tets": mesh.tets, "mesh_part_id": mesh.part_id,
                   "mesh_part_names": np.array(mesh.part_names), "mesh_moving_part": np.array(mesh.moving_part)}
    return arrays


def _from_arrays(data, key: str, system: FeedSystem | None = None, declared_only: bool = False) -> Projection | None:
    """The projection in ``data``; None when it is another layout or another file's, (with ``system``)
    when ``system``'s parameters lie outside the ranges it was trained over, or (``declared_only``)
    when it was not trained over declared ranges."""
    if int(data["store_version"]) != STORE_VERSION or str(data["key"]) != key:
        return None  # another layout, or a file copied under another name: not this model's
    if declared_only and str(data["trained_over"]) != "declared":
        return None
    names = lambda name: tuple(str(s) for s in data[name])  # noqa: E731
    domain = {name: (float(low), float(high)) for name, (low, high) in zip(names("domain_names"), data["domain_bounds"])}
    if system is not None and not _holds(domain, system):
        return None
    surfaces, sources = names("surfaces"), names("sources")
    mesh = None
    if bool(data["has_field_mesh"]):
        mesh = FieldMesh(points=data["mesh_points"], tets=data["mesh_tets"], part_id=data["mesh_part_id"],
                         part_names=names("mesh_part_names"),
                         moving_part=tuple(bool(m) for m in data["mesh_moving_part"]))
    basis = Basis(data["basis_vectors"], data["basis_singular_values"], float(data["basis_tolerance"]),
                  int(data["basis_snapshots"]), float(data["basis_seconds"]), bool(data["basis_cached"]))
    return Projection(
        basis=basis, surfaces=surfaces, sources=sources, dx=float(data["dx"]), probe_names=names("probe_names"),
        parts=dict(zip(names("part_names"), data["part_rows"])),
        part_capacity=(dict(zip(names("part_names"), (float(c) for c in data["part_capacity"])))
                       if bool(data["has_part_capacity"]) else None),
        averaged=BoundaryBasis(list(surfaces), list(sources), _read_sparse(data, "averaged_exposure"),
                               _read_sparse(data, "averaged_distribution"),
                               np.array(data["averaged_film"], dtype=float) if bool(data["has_film"]) else None),
        field_mesh=mesh, full_stats=json.loads(str(data["full_stats"])),
        displacement_basis=data["displacement_basis"] if bool(data["has_displacement_fields"]) else None,
        displacement_origin=data["displacement_origin"] if bool(data["has_displacement_fields"]) else None,
        conductance_parameters=names("conductance_parameters"), expansion_parameters=names("expansion_parameters"),
        domain=domain, trained_over=str(data["trained_over"]), **{name: data[name] for name in _ARRAYS},
    )
