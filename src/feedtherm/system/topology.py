"""Checks that a description draws a machine that can exist: solids that do not overlap, holes in
their boxes, each face declared once, selections that name primitives the part has.

What no machine can be is an error (``feedtherm check`` lists them, every command refuses them):

- two solids whose interiors intersect, within a part or between parts, at any position of the
  moving group along the stroke (the table travels ``±stroke/2`` along x from where it is
  drawn); a part is a union of non-overlapping primitives less its holes, so a cylinder in a
  box's hole does not overlap the box.  Parts that a joint declares a press fit (``fit =
  true``) may overlap each other;
- a hole outside its box, longer than it, or reaching out of its end or its side, and a hole on
  a part without boxes (holes are cut from the boxes);
- the same face of the same primitive declared twice, in two surfaces or twice in one (it would
  be cooled twice);
- a surface's ``boxes`` or ``cylinders`` index that the part does not have.

What is odd but possible is a warning: a part joined to nothing (it reads the ambient and its
own heat only), a surface ``area`` more than ten times or less than a tenth of its faces'
geometric area.

Overlaps are measured, not guessed: box against box exactly, coaxial cylinders exactly (their
radial annuli and axial ranges), anything else by counting the points of a regular grid over
the two solids' common bounding box that lie inside both, which estimates the overlap volume
(a sliver thinner than the grid's cell can be missed; a cylinder coaxial with a hole is checked
against the hole's radius exactly).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .finding import Finding
from .geometry import BOX_FACES, surface_area
from .schema import Cylinder, FeedSystem

_AXES = {"x": 0, "y": 1, "z": 2}
#: Two solids overlap when their common region is deeper than this [m] along every axis and holds
#: a point of the grid: descriptions are written in mm and decimals, so touching faces agree far
#: closer, while a real overlap is a fraction of a mm at least.
DEPTH_TOL = 1e-6
#: Grid points per axis over two solids' common bounding box (GRID**3 points per pair).
GRID = 24
#: Positions of the moving group checked between the two ends of its travel over a fixed part
#: (the ends included).
POSITIONS = 9
#: A surface's stated area outside [1/AREA_RATIO, AREA_RATIO] times its faces' area is a warning.
AREA_RATIO = 10.0


@dataclass(frozen=True)
class _Solid:
    """One primitive of a part, with the holes cut from the part."""

    part: str
    label: str  # "boxes[0]", "cylinders[1]"
    kind: str  # "box" or "cylinder"
    lo: np.ndarray  # bounding box, drawn position [m]
    hi: np.ndarray
    moving: bool
    axis: int = 0  # a cylinder's
    origin: np.ndarray = field(default_factory=lambda: np.zeros(3))
    length: float = 0.0
    r_in: float = 0.0
    r_out: float = 0.0
    holes: tuple[Cylinder, ...] = ()


def _solids(system: FeedSystem) -> list[_Solid]:
    solids = []
    for name, part in system.parts.items():
        holes = tuple(part.holes)
        for i, box in enumerate(part.boxes):
            lo = np.array(box.origin, float)
            solids.append(_Solid(name, f"boxes[{i}]", "box", lo, lo + np.array(box.size, float), part.moving,
                                 holes=holes))
        for i, cyl in enumerate(part.cylinders):
            k, origin, r = _AXES[cyl.axis], np.array(cyl.origin, float), cyl.outer_diameter / 2.0
            lo, hi = origin - r, origin + r
            lo[k], hi[k] = origin[k], origin[k] + cyl.length
            solids.append(_Solid(name, f"cylinders[{i}]", "cylinder", lo, hi, part.moving, k, origin, cyl.length,
                                 cyl.inner_diameter / 2.0, r, holes))
    return solids


def _in_cylinder(points: np.ndarray, axis: int, origin: np.ndarray, length: float, r_in: float, r_out: float,
                 pad: float) -> np.ndarray:
    """Points within a (hollow) cylinder grown by ``pad`` [m] (shrunk where ``pad`` < 0)."""
    u, v = (k for k in range(3) if k != axis)
    along = points[:, axis] - origin[axis]
    radial = np.hypot(points[:, u] - origin[u], points[:, v] - origin[v])
    inside = (along > -pad) & (along < length + pad) & (radial < r_out + pad)
    if r_in > 0.0:
        inside &= radial > r_in - pad
    return inside


def _inside(solid: _Solid, points: np.ndarray, shift: float) -> np.ndarray:
    """Points strictly inside the solid's material (shifted ``shift`` [m] along x): in the primitive
    shrunk by DEPTH_TOL, outside every hole grown by it."""
    p = points - np.array([shift, 0.0, 0.0])
    if solid.kind == "box":
        inside = np.all((p > solid.lo + DEPTH_TOL) & (p < solid.hi - DEPTH_TOL), axis=1)
    else:
        inside = _in_cylinder(p, solid.axis, solid.origin, solid.length, solid.r_in, solid.r_out, -DEPTH_TOL)
    for hole in solid.holes:
        inside &= ~_in_cylinder(p, _AXES[hole.axis], np.array(hole.origin, float), hole.length, 0.0,
                                hole.outer_diameter / 2.0, DEPTH_TOL)
    return inside


def overlap_volume(a: _Solid, b: _Solid, shift_a: float = 0.0, shift_b: float = 0.0) -> float:
    """Volume [m^3] that the interiors of two solids share (each shifted along x): exact for two
    boxes without holes and for coaxial cylinders, else estimated on a grid; 0 when they only touch."""
    da, db = np.array([shift_a, 0.0, 0.0]), np.array([shift_b, 0.0, 0.0])
    lo, hi = np.maximum(a.lo + da, b.lo + db), np.minimum(a.hi + da, b.hi + db)
    extent = hi - lo
    if np.any(extent <= DEPTH_TOL):
        return 0.0
    if a.kind == b.kind == "box" and not a.holes and not b.holes:
        return float(np.prod(extent))
    if a.kind == b.kind == "cylinder" and not a.holes and not b.holes and a.axis == b.axis \
            and np.allclose(np.delete(a.origin, a.axis), np.delete(b.origin, b.axis), atol=DEPTH_TOL):
        ring = math.pi * (min(a.r_out, b.r_out) ** 2 - max(a.r_in, b.r_in) ** 2)
        return float(extent[a.axis] * ring) if min(a.r_out, b.r_out) - max(a.r_in, b.r_in) > DEPTH_TOL else 0.0
    cell = extent / GRID
    axes = [lo[k] + cell[k] * (np.arange(GRID) + 0.5) for k in range(3)]
    points = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    count = int(np.count_nonzero(_inside(a, points, shift_a) & _inside(b, points, shift_b)))
    volume = count * float(np.prod(cell))
    return max(volume, _fat_in_hole(a, b, shift_a, shift_b), _fat_in_hole(b, a, shift_b, shift_a))


def _fat_in_hole(cyl: _Solid, box: _Solid, shift_c: float, shift_b: float) -> float:
    """A cylinder coaxial with a hole of a box but wider than it: the ring between the two radii
    over the length they share inside the box (a sliver the grid may miss) [m^3]."""
    if cyl.kind != "cylinder" or box.kind != "box":
        return 0.0
    k = cyl.axis
    worst = 0.0
    for hole in box.holes:
        h_origin = np.array(hole.origin, float)
        if _AXES[hole.axis] != k or not np.allclose(np.delete(h_origin, k), np.delete(cyl.origin, k), atol=DEPTH_TOL):
            continue
        r_hole = hole.outer_diameter / 2.0
        if cyl.r_out <= r_hole + DEPTH_TOL:
            continue
        shift_k = np.array([shift_c, 0.0, 0.0])[k]
        shift_bk = np.array([shift_b, 0.0, 0.0])[k]
        start = max(cyl.origin[k] + shift_k, h_origin[k] + shift_bk, box.lo[k] + shift_bk)
        end = min(cyl.origin[k] + cyl.length + shift_k, h_origin[k] + hole.length + shift_bk, box.hi[k] + shift_bk)
        if end - start > DEPTH_TOL:
            worst = max(worst, (end - start) * math.pi * (cyl.r_out**2 - max(r_hole, cyl.r_in) ** 2))
    return worst


def _fits(system: FeedSystem) -> set[frozenset[str]]:
    return {frozenset(j.between) for j in system.joints if j.fit}


def _shifts(a: _Solid, b: _Solid, stroke: float) -> list[float]:
    """Shifts of the moving ``a`` against the fixed ``b`` to check: where their x ranges overlap
    within the travel ±stroke/2, the ends of that range and evenly between."""
    low = max(-stroke / 2.0, b.lo[0] - a.hi[0])
    high = min(stroke / 2.0, b.hi[0] - a.lo[0])
    if high - low <= DEPTH_TOL:
        return []
    inset = min(DEPTH_TOL * 2.0, (high - low) / 4.0)
    shifts = np.linspace(low + inset, high - inset, POSITIONS)
    return sorted({*shifts.tolist(), *(s for s in (-stroke / 2.0, 0.0, stroke / 2.0) if low < s < high)})


def overlaps(system: FeedSystem) -> list[Finding]:
    """Solids whose interiors intersect (within a part, between parts, along the stroke)."""
    solids, fits = _solids(system), _fits(system)
    stroke = system.kinematics.stroke if system.kinematics is not None else 0.0
    findings, reported = [], set()
    for i, a in enumerate(solids):
        for b in solids[i + 1:]:
            pair = frozenset((a.part, b.part))
            if pair in fits or pair in reported and a.part != b.part:
                continue
            if a.moving == b.moving or stroke == 0.0:
                volume, where = overlap_volume(a, b), ""
            else:
                moving, fixed = (a, b) if a.moving else (b, a)
                volume, where = 0.0, ""
                for shift in _shifts(moving, fixed, stroke):
                    v = overlap_volume(moving, fixed, shift, 0.0)
                    if v > volume:
                        volume, where = v, f" with the moving group {shift * 1e3:+.4g} mm from its drawn position"
            if volume <= 0.0:
                continue
            reported.add(pair)
            mm3 = f"{volume * 1e9:.4g} mm^3"
            if a.part == b.part:
                findings.append(Finding(f"parts.{a.part}", f"{a.label} and {b.label} overlap by {mm3}: a part is a "
                                        "union of solids that touch, not overlap (shorten one, or draw the union "
                                        "as solids that meet at a face)", "error"))
            else:
                findings.append(Finding(f"parts.{a.part}.{a.label}", f"overlaps part {b.part!r} ({b.label}) by {mm3}"
                                        f"{where}: two parts cannot fill the same space (move or resize one; a press "
                                        "fit is declared with fit = true on their joint)", "error"))
    return findings


def parts_overlap(system: FeedSystem, a: str, b: str) -> bool:
    """True when solids of parts ``a`` and ``b`` share interior as drawn (a press fit's parts)."""
    solids = _solids(system)
    return any(overlap_volume(s, t) > 0.0 for s in solids if s.part == a for t in solids if t.part == b)


def holes(system: FeedSystem) -> list[Finding]:
    """Every hole lies in a box of its part: along its axis within the box, its disc inside the
    box's cross-section."""
    findings = []
    for name, part in system.parts.items():
        for j, hole in enumerate(part.holes):
            path = f"parts.{name}.holes[{j}]"
            if not part.boxes:
                findings.append(Finding(path, f"{name!r} has no boxes, and holes are cut from a part's boxes "
                                        "(a hollow cylinder has an inner_diameter)", "error"))
                continue
            k, r = _AXES[hole.axis], hole.outer_diameter / 2.0
            u, v = (m for m in range(3) if m != k)
            centre = hole.origin
            hosts = [b for b in part.boxes
                     if all(b.origin[m] < centre[m] < b.origin[m] + b.size[m] for m in (u, v))]
            if not hosts:
                findings.append(Finding(path, f"its axis lies outside every box of {name!r}", "error"))
                continue
            start, end = centre[k], centre[k] + hole.length
            spans = sorted((b.origin[k], b.origin[k] + b.size[k]) for b in hosts)
            if not _covered(start, end, spans):
                shown = ", ".join(f"{lo * 1e3:g}..{hi * 1e3:g}" for lo, hi in spans)
                runs = f"runs {start * 1e3:g}..{end * 1e3:g} mm along {hole.axis}"
                if all(end <= lo + DEPTH_TOL or start >= hi - DEPTH_TOL for lo, hi in spans):
                    why = f"{runs}, outside its box ({shown} mm): a hole lies in the box it is cut from"
                elif hole.length > max(hi for _, hi in spans) - min(lo for lo, _ in spans) + DEPTH_TOL:
                    why = f"{runs}, beyond its box ({shown} mm): the hole is longer than its box"
                else:
                    why = f"{runs}, beyond its box ({shown} mm): the hole reaches out of its box's end (move it in)"
                findings.append(Finding(path, why, "error"))
                continue
            if not any(all(b.origin[m] - DEPTH_TOL <= centre[m] - r and centre[m] + r <= b.origin[m] + b.size[m]
                           + DEPTH_TOL for m in (u, v)) for b in hosts):
                findings.append(Finding(path, f"its {hole.outer_diameter * 1e3:g} mm disc reaches out of the side of "
                                        f"its box: a hole lies inside its box", "error"))
    return findings


def _covered(start: float, end: float, spans: list[tuple[float, float]]) -> bool:
    """True when [start, end] lies within the union of the sorted intervals ``spans``."""
    reach = start
    for lo, hi in spans:
        if lo > reach + DEPTH_TOL:
            break
        reach = max(reach, hi)
    return reach >= end - DEPTH_TOL


def selections(system: FeedSystem) -> list[Finding]:
    """A surface's ``boxes`` and ``cylinders`` indices name primitives its part has."""
    findings = []
    for name, surface in system.surfaces.items():
        part = system.parts[surface.part]
        for kind, indices, count in (("boxes", surface.boxes, len(part.boxes)),
                                     ("cylinders", surface.cylinders, len(part.cylinders))):
            bad = [i for i in indices or [] if not 0 <= i < count]
            if bad:
                findings.append(Finding(f"surfaces.{name}.{kind}", f"index {bad[0]} is out of range: part "
                                        f"{surface.part!r} has {count} {kind} (indices 0..{count - 1})" if count else
                                        f"index {bad[0]} is out of range: part {surface.part!r} has no {kind}",
                                        "error"))
            elif indices is not None and len(set(indices)) != len(indices):
                findings.append(Finding(f"surfaces.{name}.{kind}", f"an index is listed twice ({indices}): its faces "
                                        "would be counted twice", "error"))
    return findings


def _face_keys(system: FeedSystem, surface) -> list[tuple[str, str]]:
    """(primitive, face) of every face a surface selects, once per time it is selected."""
    part = system.parts[surface.part]
    boxes = range(len(part.boxes)) if surface.boxes is None else surface.boxes
    cylinders = range(len(part.cylinders)) if surface.cylinders is None else surface.cylinders
    keys = []
    for face in surface.faces:
        for i in boxes:
            if face in BOX_FACES or face == "bore":
                keys.append((f"boxes[{i}]", face))
        for i in cylinders:
            axis = part.cylinders[i].axis
            ends = (f"-{axis}", f"+{axis}")
            if face == "ends":
                keys.extend((f"cylinders[{i}]", end) for end in ends)
            elif face in ("lateral", "bore") or face in ends:
                keys.append((f"cylinders[{i}]", face))
    return keys


def faces_once(system: FeedSystem) -> list[Finding]:
    """Each face of each primitive belongs to one surface, once (or it would be cooled twice)."""
    findings, owner = [], {}
    for name, surface in system.surfaces.items():
        keys = _face_keys(system, surface)
        seen = set()
        for primitive, face in keys:
            key = (surface.part, primitive, face)
            if key in seen:
                findings.append(Finding(f"surfaces.{name}.faces", f"face {face} of {surface.part!r} {primitive} is "
                                        "selected twice in this surface (its area would count twice)", "error"))
                break
            seen.add(key)
        for key in dict.fromkeys(keys):
            full = (surface.part, *key)
            if full in owner and owner[full] != name:
                findings.append(Finding(f"surfaces.{name}.faces", f"face {key[1]} of {surface.part!r} {key[0]} is "
                                        f"also surfaces.{owner[full]}'s: a face is one surface (it would be cooled "
                                        "twice)", "error"))
                break
            owner.setdefault(full, name)
    return findings


def errors(system: FeedSystem, with_overlaps: bool = True) -> list[Finding]:
    """Every error of this module: selections and holes first (the overlaps read them); the overlaps
    only ``with_overlaps`` (not along a stroke that is an error itself)."""
    found = [*selections(system), *holes(system)]
    return found or [*faces_once(system), *(overlaps(system) if with_overlaps else [])]


def unjoined(system: FeedSystem) -> list[Finding]:
    """A part no joint touches (other than the drive's screw and nut, which the thread joins)."""
    joined = {p for j in system.joints for p in j.between}
    drive = {system.kinematics.screw, system.kinematics.nut} if system.kinematics is not None else set()
    return [Finding(f"parts.{name}", "is joined to nothing: it exchanges heat with the ambient only, and no other "
                    "part's heat reaches it; if it touches another part, declare their joint")
            for name in system.parts if name not in joined and name not in drive and len(system.parts) > 1]


def area_overrides(system: FeedSystem) -> list[Finding]:
    """A stated area far from the faces' own: a mistyped unit or the wrong faces."""
    findings = []
    for name, surface in system.surfaces.items():
        if surface.area is None:
            continue
        try:
            drawn = surface_area(surface.model_copy(update={"area": None}), system.parts[surface.part])
        except (ValueError, IndexError):
            continue
        if drawn <= 0.0:
            continue
        ratio = surface.area / drawn
        if ratio > AREA_RATIO or ratio < 1.0 / AREA_RATIO:
            findings.append(Finding(f"surfaces.{name}.area", f"{surface.area * 1e6:.4g} mm^2 is {ratio:.3g} times "
                                    f"the area of its faces as drawn ({drawn * 1e6:.4g} mm^2): a unit or the faces "
                                    "may be wrong"))
    return findings


def warnings(system: FeedSystem) -> list[Finding]:
    """Every warning of this module."""
    return [*unjoined(system), *area_overrides(system)]
