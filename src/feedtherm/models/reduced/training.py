"""What a parametric reduced model is trained over, and what its projection depends on.

The FE model's conductances are linear in each material's conductivity and each joint's
conductance ``1/tcr``, its displacements in each material's expansion
(:meth:`~feedtherm.models.interface.ThermalModel.affine_parameters`); a surface with a fixed
coefficient (a foundation) enters the boundary conditions, which the reduced model takes
exactly anyway.  What the projection cannot take exactly is a basis built at one description
for another: the answers to the inputs change with the conductances and coefficients.  So
the basis is trained over a **domain**, the range of each such number that the description
itself declares plausible:

- every ``[uncertainty.parameters]`` range (a normal or lognormal without one: ±3σ) and every
  ``[calibration.parameters]`` bound that reaches it, with the declared value;
- a number nothing declares stays at its value (a degenerate range).

The training points (:func:`training_points`) are the domain's two corners (every number at
its low end, every one at its high end), each fixed coefficient's two ends alone (the
foundation's range spans three orders of magnitude) and :data:`RANDOM_POINTS` points of a
Latin hypercube (log-uniform where a range spans more than a factor 2), from a fixed seed.
A description whose numbers lie inside a projection's domain runs on it
(:func:`inside`); one outside is another model and builds its own.

:func:`structure` is the description without those numbers and without what only the
boundary conditions read (conditions, loss models' parameters, film correlations, the
declared ranges themselves): the projection's cache key (:mod:`.store`).
"""

from __future__ import annotations

import hashlib
import itertools
import json
import math

import numpy as np

from ...system.paths import expand_path, get_path
from ...system.quantities import to_base_si
from ...system.schema import FeedSystem
from ...system.surfaces import FixedConvection
from ..interface import affine_value

__all__ = ["RANDOM_POINTS", "declared_domain", "domain_digest", "inside", "omitted_values", "structure",
           "training_points"]

#: Latin-hypercube training points besides the corners and the fixed coefficients' ends.
RANDOM_POINTS = 3
#: Seed of the Latin hypercube: a domain always gives the same points (and the same cached basis).
SEED = 36
#: Seed of the points a built basis is checked at (models/reduced/basis.py, ``steady_check``).
CHECK_SEED = 37
#: A range wider than this factor is sampled log-uniformly.
LOG_SPAN = 2.0
#: Relative slack of :func:`inside` (a value written to a description and read back differs in
#: its last bits).
SLACK = 1e-9


def omitted_values(system: FeedSystem) -> dict[str, float]:
    """The numbers :func:`structure` leaves out that the operators or the basis read
    (:func:`~feedtherm.models.interface.affine_value`'s names): every material's conductivity and
    expansion, every joint's conductance, every fixed coefficient."""
    names = [f"materials.{m}.{field}" for m in system.materials for field in ("conductivity", "expansion")]
    names += [f"joints[{i}].conductance" for i in range(len(system.joints))]
    names += [f"surfaces.{s}.coefficient" for s, surface in system.surfaces.items()
              if isinstance(surface.convection, FixedConvection)]
    return {name: affine_value(system, name) for name in names}


def _parameter_of(system: FeedSystem, path: str) -> str | None:
    """The affine parameter (or fixed coefficient) a description path sets, or None."""
    parts = path.split(".")
    if len(parts) == 3 and parts[0] == "materials" and parts[2] == "conductivity":
        return path
    if len(parts) == 2 and parts[0].startswith("joints[") and parts[1] == "tcr":
        return f"{parts[0]}.conductance"
    if parts[0] == "surfaces" and len(parts) >= 3 and parts[1] in system.surfaces:
        surface = system.surfaces[parts[1]]
        if isinstance(surface.convection, FixedConvection) and parts[2:] in (["convection", "coefficient"],
                                                                              ["chtc_factor"]):
            return f"surfaces.{parts[1]}.coefficient"
    return None


def _paths_of(system: FeedSystem, name: str) -> list[str]:
    """The description paths a parameter's value is made of (:func:`affine_value`)."""
    head, _, field = name.rpartition(".")
    if field == "conductance":
        return [f"{head}.tcr"]
    if head.startswith("surfaces."):
        return [f"{head}.convection.coefficient", f"{head}.chtc_factor"]
    return [name]


def _value_of(system: FeedSystem, name: str, values: dict[str, float]) -> float:
    """The parameter at the path values ``values`` (those not given as declared)."""
    head, _, field = name.rpartition(".")
    own = lambda path: float(values.get(path, get_path(system, path)))  # noqa: E731
    if field == "conductance":
        return 1.0 / own(f"{head}.tcr")
    if head.startswith("surfaces."):
        return own(f"{head}.convection.coefficient") * own(f"{head}.chtc_factor")
    return own(name)


def _declared_ranges(system: FeedSystem) -> list[tuple[str, list[str], float, float]]:
    """Every declared range as (kind, paths, low, high) in SI or as factors."""
    out = []
    for spec in (system.uncertainty.parameters.values() if system.uncertainty else ()):
        paths = [p for path in spec.paths for p in expand_path(system, path)]
        centre = float(get_path(system, paths[0])) if spec.kind == "value" else 1.0
        if spec.range is not None:
            low, high = (to_base_si(b) for b in spec.range)
        elif spec.distribution == "lognormal":
            sigma = to_base_si(spec.sigma)
            low, high = centre * math.exp(-3.0 * sigma), centre * math.exp(3.0 * sigma)
        else:
            sigma = to_base_si(spec.sigma)
            low, high = centre - 3.0 * sigma, centre + 3.0 * sigma
        out.append((spec.kind, paths, low, high))
    for spec in (system.calibration.parameters.values() if system.calibration else ()):
        paths = [p for path in spec.paths for p in expand_path(system, path)]
        low, high = (to_base_si(b) for b in spec.bounds)
        out.append((spec.kind, paths, low, high))
    return out


def declared_domain(system: FeedSystem, names: list[str]) -> dict[str, tuple[float, float]]:
    """Each parameter of ``names`` → (low, high) [SI]: its value and the declared ranges that reach it
    (module notes)."""
    path_ranges: dict[str, list[float]] = {}
    for kind, paths, low, high in _declared_ranges(system):
        for path in paths:
            if _parameter_of(system, path) is None:
                continue
            declared = float(get_path(system, path))
            ends = [low, high] if kind == "value" else [declared * low, declared * high]
            path_ranges.setdefault(path, [declared]).extend(e for e in ends if e > 0.0)
    domain = {}
    for name in names:
        paths = _paths_of(system, name)
        ends = [sorted({min(path_ranges[p]), max(path_ranges[p])}) if p in path_ranges else [float(get_path(system, p))]
                for p in paths]
        corners = itertools.product(*ends)
        values = [_value_of(system, name, dict(zip(paths, corner))) for corner in corners]
        own = affine_value(system, name)
        domain[name] = (min(own, *values), max(own, *values))
    return domain


def training_points(domain: dict[str, tuple[float, float]], values: dict[str, float]) -> tuple[dict[str, float], ...]:
    """The training points (module notes) of ``domain``, the other parameters at ``values``; only the
    parameters a point changes are in it."""
    spread = [name for name, (low, high) in domain.items() if math.isfinite(high) and high > low]
    if not spread:
        return ()
    lows = {name: domain[name][0] for name in spread}
    highs = {name: domain[name][1] for name in spread}
    points = [lows, highs]
    for name in spread:
        if name.startswith("surfaces."):
            points += [{name: domain[name][0]}, {name: domain[name][1]}]
    points += random_points(domain, RANDOM_POINTS, SEED)
    unique = {tuple(sorted(p.items())): p for p in points}  # one spread parameter: its ends are the corners
    return tuple(unique.values())


def random_points(domain: dict[str, tuple[float, float]], count: int, seed: int) -> list[dict[str, float]]:
    """``count`` points of a Latin hypercube over the domain's spread ranges (log-uniform over a range
    wider than :data:`LOG_SPAN`)."""
    spread = [name for name, (low, high) in domain.items() if math.isfinite(high) and high > low]
    if not spread or count == 0:
        return []
    rng = np.random.default_rng(seed)
    strata = np.array([rng.permutation(count) for _ in spread])  # (dims, points)
    u = (strata + rng.random(strata.shape)) / count
    points = []
    for j in range(count):
        point = {}
        for i, name in enumerate(spread):
            low, high = domain[name]
            if high / low > LOG_SPAN:
                point[name] = float(low * (high / low) ** u[i, j])
            else:
                point[name] = float(low + (high - low) * u[i, j])
        points.append(point)
    return points


def inside(domain: dict[str, tuple[float, float]], values: dict[str, float]) -> bool:
    """Whether every parameter of ``values`` lies in ``domain`` (one it does not name: outside)."""
    for name, value in values.items():
        if name not in domain:
            return False
        low, high = domain[name]
        if not low * (1.0 - SLACK) <= value <= high * (1.0 + SLACK):
            return False
    return True


def domain_digest(domain: dict[str, tuple[float, float]]) -> str:
    text = json.dumps({name: [float(f"{v:.12g}") for v in bounds] for name, bounds in sorted(domain.items())})
    return hashlib.blake2b(text.encode(), digest_size=8).hexdigest()


#: Per section of the description: the fields only the boundary conditions (or nothing in a model)
#: read.  Everything else — geometry, materials' density, heat capacity and elastic constants,
#: joints' contacts, where sources put their heat, where surfaces and sensors are, the
#: kinematics and mechanics, the reference temperature — names the projection.
_NOT_STRUCTURE = {
    "materials": ("conductivity", "expansion", "name"),
    "joints": ("tcr", "description"),
    "surfaces": ("convection", "emissivity", "chtc_factor", "sink_temperature", "description"),
    "sensors": ("method", "description"),
}
_SECTIONS_OUT = ("meta", "conditions", "duty_cycles", "calibration", "uncertainty", "provenance")


def structure(system: FeedSystem) -> dict:
    """``system`` without its affine parameters' values and what only the boundary conditions read
    (JSON-able; module notes)."""
    data = system.model_dump(mode="json")
    for section in _SECTIONS_OUT:
        data.pop(section, None)
    for section, fields in _NOT_STRUCTURE.items():
        items = data.get(section) or {}
        for item in (items.values() if isinstance(items, dict) else items):
            for name in fields:
                item.pop(name, None)
    for name, surface in system.surfaces.items():  # which surfaces have a fixed coefficient: the basis's reference
        data["surfaces"][name]["fixed"] = isinstance(surface.convection, FixedConvection)
    data["sources"] = {name: {"into": source.get("into"), "through": source.get("through")}
                       for name, source in data.get("sources", {}).items()}
    for section, kept in (("temperatures", "reference"), ("room", "ambient_sensor")):  # either may be absent
        if data.get(section) is not None:
            data[section] = {kept: data[section].get(kept)}
    return data
