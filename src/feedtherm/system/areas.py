"""Contact areas of joints and exposed areas of surfaces, derived from the parts' primitives.

Two parts touch where a face of one lies on a face of the other, facing it:

- two plane faces in one plane with opposite normals (a box's ``-z`` on another's ``+z``, a
  cylinder's end face on a box's face or on another cylinder's end face): the area they share,
  less the holes of either face;
- a cylinder's ``lateral`` face in a coaxial bore of the same diameter (a cylinder's ``bore``,
  or a hole through a box): the circumference times the length they share.

A joint's area, where the description leaves it out, is the sum of these patches between its
two parts, as drawn (the moving group at the middle of the stroke).  A surface's exposed area is
its faces' area less the patches on them that a joined part covers or that another primitive
of the same part is fused to: what the models give to the air (they find the same patches on
their own grids, position by position).  A value given in the description overrides either.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .geometry import surface_area
from .schema import Box, Cylinder, FeedSystem, Part

_AXES = {"x": 0, "y": 1, "z": 2}
#: Two faces closer than this [m] touch (coordinates come from decimal strings in mm).
TOUCH_TOL = 1e-7
#: Midpoints per half turn of the disc-in-rectangle integral over the angle (relative error ~1e-8).
_DISC_SAMPLES = 4000


@dataclass(frozen=True)
class Patch:
    """Where part ``part``'s primitive (``kind`` box or cylinder, index ``index``) touches another
    primitive over ``area`` [m^2] of its face ``face`` (the description's face labels)."""

    part: str
    kind: str
    index: int
    face: str
    area: float


# --------------------------------------------------------------------------- plane faces


@dataclass(frozen=True)
class _Plane:
    kind: str  # "box" or "cylinder"
    index: int
    face: str  # "+x", ..., "-z"
    axis: int
    level: float  # the plane's coordinate along its axis [m]
    sign: int  # +1 or -1: the outward normal
    rect: tuple[tuple[float, float], tuple[float, float]] | None  # (u range, v range) of a box face
    centre: tuple[float, float] | None  # an end face's centre (u, v)
    r_in: float = 0.0
    r_out: float = 0.0
    holes: tuple[tuple[float, float, float], ...] = ()  # (u, v, radius) of holes through a box face


def _others(axis: int) -> tuple[int, int]:
    return tuple(k for k in range(3) if k != axis)  # type: ignore[return-value]


def _box_planes(part: Part, index: int, box: Box) -> list[_Plane]:
    lo = box.origin
    hi = tuple(o + s for o, s in zip(box.origin, box.size))
    planes = []
    for axis in range(3):
        u, v = _others(axis)
        holes = tuple((h.origin[u], h.origin[v], h.outer_diameter / 2.0) for h in part.holes
                      if _AXES[h.axis] == axis and lo[u] <= h.origin[u] <= hi[u] and lo[v] <= h.origin[v] <= hi[v])
        for sign, level in ((-1, lo[axis]), (1, hi[axis])):
            face = f"{'+' if sign > 0 else '-'}{'xyz'[axis]}"
            planes.append(_Plane("box", index, face, axis, level, sign, ((lo[u], hi[u]), (lo[v], hi[v])), None,
                                 holes=holes))
    return planes


def _cylinder_planes(index: int, cyl: Cylinder) -> list[_Plane]:
    axis = _AXES[cyl.axis]
    u, v = _others(axis)
    centre = (cyl.origin[u], cyl.origin[v])
    ends = ((-1, cyl.origin[axis]), (1, cyl.origin[axis] + cyl.length))
    return [_Plane("cylinder", index, f"{'+' if sign > 0 else '-'}{cyl.axis}", axis, level, sign, None, centre,
                   cyl.inner_diameter / 2.0, cyl.outer_diameter / 2.0) for sign, level in ends]


def disc_in_rectangle(cu: float, cv: float, r: float, rect) -> float:
    """Area [m^2] of the disc of radius ``r`` about ``(cu, cv)`` inside ``rect = ((u0, u1), (v0, v1))``.

    The integral over u of the chord's overlap with [v0, v1], by the midpoint rule in the angle
    theta (u = cu + r sin theta, which takes away the chord's square-root ends); exact for a disc
    wholly inside (pi r^2) or outside (0).
    """
    (u0, u1), (v0, v1) = rect
    if r <= 0.0:
        return 0.0
    if cu - r >= u0 and cu + r <= u1 and cv - r >= v0 and cv + r <= v1:
        return math.pi * r * r
    a, b = max(cu - r, u0), min(cu + r, u1)
    if b <= a:
        return 0.0
    t0, t1 = math.asin(max(-1.0, (a - cu) / r)), math.asin(min(1.0, (b - cu) / r))
    n = max(64, int(_DISC_SAMPLES * (t1 - t0) / math.pi))
    step = (t1 - t0) / n
    theta = t0 + step * (np.arange(n) + 0.5)
    half = r * np.cos(theta)
    chord = np.clip(np.minimum(cv + half, v1) - np.maximum(cv - half, v0), 0.0, None)
    return float((chord * half).sum() * step)  # du = r cos(theta) dtheta


def _plane_overlap(a: _Plane, b: _Plane) -> float:
    """Area [m^2] two facing plane faces share, less the holes through either (0 if they do not touch)."""
    if a.axis != b.axis or a.sign == b.sign or abs(a.level - b.level) > TOUCH_TOL:
        return 0.0
    if a.rect is not None and b.rect is not None:
        rect = tuple((max(p[0], q[0]), min(p[1], q[1])) for p, q in zip(a.rect, b.rect))
        if any(hi - lo <= TOUCH_TOL for lo, hi in rect):
            return 0.0
        area = (rect[0][1] - rect[0][0]) * (rect[1][1] - rect[1][0])
        holes = {}
        for u, v, r in a.holes + b.holes:  # coaxial holes of the two faces are one hole: the larger
            key = (round(u, 9), round(v, 9))
            holes[key] = max(holes.get(key, 0.0), r)
        return max(area - sum(disc_in_rectangle(u, v, r, rect) for (u, v), r in holes.items()), 0.0)
    if a.rect is None and b.rect is None:  # two end faces: coaxial annuli
        if math.dist(a.centre, b.centre) > TOUCH_TOL:
            return 0.0
        r_in, r_out = max(a.r_in, b.r_in), min(a.r_out, b.r_out)
        return math.pi * (r_out**2 - r_in**2) if r_out > r_in else 0.0
    box, end = (a, b) if a.rect is not None else (b, a)
    r_in = end.r_in
    for u, v, r in box.holes:  # a hole under the end face, about its axis, widens its bore
        if math.dist((u, v), end.centre) <= TOUCH_TOL:
            r_in = max(r_in, r)
    if r_in >= end.r_out:
        return 0.0
    ring = disc_in_rectangle(*end.centre, end.r_out, box.rect) - disc_in_rectangle(*end.centre, r_in, box.rect)
    return max(ring, 0.0)


# --------------------------------------------------------------------------- cylindrical faces


@dataclass(frozen=True)
class _Round:
    """A cylindrical face: a cylinder's ``lateral`` (outward) or ``bore`` (inward), a box's hole."""

    kind: str
    index: int
    face: str  # "lateral" or "bore"
    axis: int
    centre: tuple[float, float]
    radius: float
    span: tuple[float, float]  # along the axis [m]
    outward: bool


def _rounds(part: Part) -> list[_Round]:
    out = []
    for i, cyl in enumerate(part.cylinders):
        axis = _AXES[cyl.axis]
        u, v = _others(axis)
        span = (cyl.origin[axis], cyl.origin[axis] + cyl.length)
        centre = (cyl.origin[u], cyl.origin[v])
        out.append(_Round("cylinder", i, "lateral", axis, centre, cyl.outer_diameter / 2.0, span, True))
        if cyl.inner_diameter > 0.0:
            out.append(_Round("cylinder", i, "bore", axis, centre, cyl.inner_diameter / 2.0, span, False))
    for i, box in enumerate(part.boxes):
        for hole in part.holes:
            axis = _AXES[hole.axis]
            u, v = _others(axis)
            lo, hi = box.origin, tuple(o + s for o, s in zip(box.origin, box.size))
            if not (lo[u] <= hole.origin[u] <= hi[u] and lo[v] <= hole.origin[v] <= hi[v]):
                continue
            span = (max(hole.origin[axis], lo[axis]), min(hole.origin[axis] + hole.length, hi[axis]))
            if span[1] > span[0]:
                out.append(_Round("box", i, "bore", axis, (hole.origin[u], hole.origin[v]),
                                  hole.outer_diameter / 2.0, span, False))
    return out


def _round_overlap(a: _Round, b: _Round) -> float:
    """Area [m^2] of an outward cylindrical face in a coaxial bore of the same radius."""
    if a.outward == b.outward or a.axis != b.axis or math.dist(a.centre, b.centre) > TOUCH_TOL:
        return 0.0
    if abs(a.radius - b.radius) > TOUCH_TOL:
        return 0.0
    length = min(a.span[1], b.span[1]) - max(a.span[0], b.span[0])
    return 2.0 * math.pi * a.radius * length if length > TOUCH_TOL else 0.0


# --------------------------------------------------------------------------- between parts


def _planes(part: Part) -> list[_Plane]:
    return ([p for i, box in enumerate(part.boxes) for p in _box_planes(part, i, box)]
            + [p for i, cyl in enumerate(part.cylinders) for p in _cylinder_planes(i, cyl)])


#: Patches by the identity of the two Part objects (:func:`_kept`).  Parts are frozen: the boundary
#: conditions, evaluated many times a run, find a part pair's patches once.
_CACHE: dict[tuple[int, ...], tuple[tuple, list[tuple[str, int, str, float, str, int, str]]]] = {}
_CACHE_SIZE = 4096


def _kept(cache: dict, size: int, objects: tuple, make):
    """What ``make()`` gives for ``objects``, kept in ``cache`` under their identities.

    The objects are kept with their entry, so that an id is not reused while it stands; a full
    cache (``size`` entries) starts afresh.
    """
    key = tuple(map(id, objects))
    hit = cache.get(key)
    if hit is None or any(kept is not obj for kept, obj in zip(hit[0], objects)):
        if len(cache) >= size:
            cache.clear()
        hit = cache[key] = (objects, make())
    return hit[1]


def contact_patches(a_name: str, a: Part, b_name: str, b: Part) -> list[Patch]:
    """The patches where parts ``a`` and ``b`` touch, one on each side per touching pair of faces.

    With ``a is b`` (one part), the faces where its own primitives are fused together.
    """
    patches = []
    touching = _kept(_CACHE, _CACHE_SIZE, (a, b), lambda: _touching(a, b))
    for kind_a, index_a, face_a, area, kind_b, index_b, face_b in touching:
        patches.append(Patch(a_name, kind_a, index_a, face_a, area))
        if a is not b:
            patches.append(Patch(b_name, kind_b, index_b, face_b, area))
    return patches


def _touching(a: Part, b: Part) -> list[tuple[str, int, str, float, str, int, str]]:
    """(kind, index, face) on ``a``, the area, (kind, index, face) on ``b``, per touching pair of faces."""
    same = a is b
    patches = []
    for faces, overlap in ((_planes, _plane_overlap), (_rounds, _round_overlap)):
        for fa in faces(a):
            for fb in faces(b):
                if same and (fa.kind, fa.index) == (fb.kind, fb.index):
                    continue
                area = overlap(fa, fb)
                if area > 0.0:
                    patches.append((fa.kind, fa.index, fa.face, area, fb.kind, fb.index, fb.face))
    return patches


def joint_contact_area(system: FeedSystem, index: int) -> float:
    """The contact area [m^2] of ``joints[index]`` as drawn: 0 where its parts have no touching faces."""
    a, b = system.joints[index].between
    return sum(p.area for p in contact_patches(a, system.parts[a], b, system.parts[b]) if p.part == a)


#: Exposed areas by surface, by the identity of the description (:func:`_kept`): a description is
#: frozen, and the boundary conditions take every surface's area at each of the hundreds of
#: evaluations of a coupled run.
_EXPOSED: dict[tuple[int, ...], tuple[tuple, dict[str, float]]] = {}
_EXPOSED_SIZE = 256


def exposed_area(system: FeedSystem, name: str) -> float:
    """Area [m^2] of surface ``name``: its given ``area``, else its faces less what covers them.

    Covered: the patches on the selected faces where a part joined to this one touches it, or
    another primitive of the same part is fused to it (module docstring).
    """
    areas = _kept(_EXPOSED, _EXPOSED_SIZE, (system,), dict)
    if name not in areas:
        areas[name] = _exposed_area(system, name)
    return areas[name]


def _exposed_area(system: FeedSystem, name: str) -> float:
    surface = system.surfaces[name]
    part = system.parts[surface.part]
    faces = surface_area(surface, part)
    if surface.area is not None:
        return faces
    boxes = range(len(part.boxes)) if surface.boxes is None else surface.boxes
    cylinders = range(len(part.cylinders)) if surface.cylinders is None else surface.cylinders
    selected = {("box", i) for i in boxes} | {("cylinder", i) for i in cylinders}
    wanted = set(surface.faces)
    if "ends" in wanted:
        wanted |= {f"{sign}{cyl.axis}" for cyl in part.cylinders for sign in "+-"}
    patches = contact_patches(surface.part, part, surface.part, part)
    for joint in system.joints:
        if surface.part in joint.between:
            other = joint.between[1] if joint.between[0] == surface.part else joint.between[0]
            if other != surface.part:
                patches += [p for p in contact_patches(surface.part, part, other, system.parts[other])
                            if p.part == surface.part]
    covered = sum(p.area for p in patches if (p.kind, p.index) in selected and p.face in wanted)
    return max(faces - covered, 0.0)


def with_joint_areas(system: FeedSystem) -> tuple[FeedSystem, list[int]]:
    """``system`` with every joint that gives no ``area`` given its contact area, and their indices.

    Raises ValueError naming the first such joint whose parts have no touching faces.
    """
    derived, joints = [], list(system.joints)
    for index, joint in enumerate(joints):
        a, b = joint.between
        if joint.area is not None or a == b:  # a joint of a part with itself is check's error
            continue
        area = joint_contact_area(system, index)
        if area <= 0.0:
            raise ValueError(f"joints[{index}].area: not given, and {a!r} and {b!r} have no faces that touch "
                             "(a face on a face, or a cylinder in a bore of its diameter) to derive it from; "
                             "give area = \"... m^2\" or correct the geometry")
        joints[index] = joint.model_copy(update={"area": area})
        derived.append(index)
    if not derived:
        return system, []
    return system.model_copy(update={"joints": joints}), derived
