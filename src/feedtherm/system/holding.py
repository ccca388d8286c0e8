"""Is the structure held?  The rigid-body motions the supports and the joints leave free.

Each part is taken as a rigid body with six motions (three translations, three rotations
about its centre).  A support holds its point along its axes; a joint ties its two parts
along the axes it does not release, at the corners of the region where their bounding boxes
meet; the drive holds the nut to the screw along x at the nut's centre.  The motions the structure may still make without deforming are the null space of
those constraints: empty when every part is held.  A displacement computed on a structure
with a free motion is undefined (its stiffness matrix is singular), so a description with one
is an error, named by the part and the motion.
"""

from __future__ import annotations

import itertools

import numpy as np

from .geometry import bounds, drive_point
from .mechanics import joint_holds

#: A null-space vector's largest share below this is round-off (of unit-length vectors).
_NULL_TOLERANCE = 1e-9
_MOTIONS = ("translate along x", "translate along y", "translate along z",
            "rotate about x", "rotate about y", "rotate about z")


def _mode_rows(point: np.ndarray, centre: np.ndarray) -> np.ndarray:
    """(3, 6): the displacement at ``point`` along x, y, z per unit of each rigid motion."""
    r = point - centre
    rows = np.zeros((3, 6))
    rows[:, :3] = np.eye(3)
    for j in range(3):  # rotation about axis j: e_j × r
        e = np.zeros(3)
        e[j] = 1.0
        rows[:, 3 + j] = np.cross(e, r)
    return rows


def _contact_corners(lo_a, hi_a, lo_b, hi_b) -> np.ndarray:
    """Corners of the region where two boxes meet (its midpoint along an axis where they are apart)."""
    lo = np.maximum(lo_a, lo_b)
    hi = np.minimum(hi_a, hi_b)
    mid = 0.5 * (lo + hi)
    lo, hi = np.where(lo <= hi, lo, mid), np.where(lo <= hi, hi, mid)
    return np.array(list(itertools.product(*zip(lo, hi))))


def free_motions(system) -> list[str]:
    """The parts and motions the supports and joints leave free (``"part: rotate about x"``), worst first."""
    names = list(system.parts)
    index = {name: i for i, name in enumerate(names)}
    box = {name: tuple(np.asarray(b) for b in bounds(part)) for name, part in system.parts.items()}
    scale = max(float(np.max(hi - lo)) for lo, hi in box.values())
    centre = {name: 0.5 * (lo + hi) for name, (lo, hi) in box.items()}
    rows = []

    def block(name: str, point: np.ndarray) -> np.ndarray:
        out = np.zeros((3, 6 * len(names)))
        i = index[name]
        modes = _mode_rows(point, centre[name])
        modes[:, 3:] *= scale  # rotations in units of the structure's size: a well-scaled matrix
        out[:, 6 * i:6 * i + 6] = modes
        return out

    for support in system.mechanics.supports:
        point = np.asarray(support.point, dtype=float)
        full = block(support.part, point)
        rows.extend(full["xyz".index(axis)] for axis in support.fix)
    for joint in system.joints:
        a, b = joint.between
        held = joint_holds(joint.release)
        if not held:
            continue
        for point in _contact_corners(*box[a], *box[b]):
            relative = block(a, point) - block(b, point)
            rows.extend(relative[k] for k in held)
    kin = system.kinematics  # the thread holds the nut to the screw along the axis (the drive)
    if (point := drive_point(system)) is not None:
        point = np.asarray(point, dtype=float)
        rows.append((block(kin.nut, point) - block(kin.screw, point))[0])
    if not rows:
        return ["the whole structure: every motion"]
    matrix = np.array(rows)
    _, s, vt = np.linalg.svd(matrix, full_matrices=True)
    rank = int(np.sum(s > s[0] * 1e-10)) if s.size else 0
    null = vt[rank:]
    if null.size == 0:
        return []
    out = []
    # motions of the whole structure as one body first: a missing support, not a loose part
    whole = np.array(_whole_structure_modes(names, centre, scale)).T  # (6n, 6)
    basis, _ = np.linalg.qr(whole)
    u, sv, _ = np.linalg.svd(null @ basis, full_matrices=False)
    inside = sv > 1.0 - 1e-6  # directions of the null space that move the structure as one body
    if inside.any():
        free = (u[:, inside].T @ null)  # (f, 6n), orthonormal rows
        for vector in free:
            c = np.linalg.lstsq(whole, vector, rcond=None)[0]
            text = f"the whole structure: {_MOTIONS[int(np.argmax(np.abs(c)))]}"
            if text not in out:
                out.append(text)
        null = null - (null @ free.T) @ free
        _, sv2, vt2 = np.linalg.svd(null, full_matrices=False)
        null = vt2[sv2 > 1e-6]
    for vector in null:
        share = np.abs(vector).reshape(len(names), 6)
        part, motion = np.unravel_index(np.argmax(share), share.shape)
        if share[part, motion] > _NULL_TOLERANCE:
            text = f"{names[part]}: {_MOTIONS[motion]}"
            if text not in out:
                out.append(text)
    return out


def _whole_structure_modes(names, centre, scale) -> list[np.ndarray]:
    """The six motions of every part as one rigid body, unit vectors in the constraints' variables."""
    c0 = np.mean([centre[name] for name in names], axis=0)
    modes = []
    for m in range(6):
        vector = np.zeros(6 * len(names))
        for i, name in enumerate(names):
            if m < 3:
                vector[6 * i + m] = 1.0
            else:
                e = np.zeros(3)
                e[m - 3] = 1.0
                vector[6 * i:6 * i + 3] = np.cross(e, centre[name] - c0)
                vector[6 * i + m] = 1.0 / scale  # the variables hold rotations times the size
        modes.append(vector / np.linalg.norm(vector))
    return modes

__all__ = ["free_motions"]
