"""The mesh a model's full states live on, for field output (FE models)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True, eq=False)
class FieldMesh:
    """Vertices with every part at rest (the moving group mid-stroke) and linear tetrahedra.

    ``points`` (n, 3) [m]; ``tets`` (m, 4) vertex indices; ``part_id`` (m,) into
    ``part_names``; ``moving_part`` per part: does it move with the worktable?
    """

    points: np.ndarray
    tets: np.ndarray
    part_id: np.ndarray
    part_names: tuple[str, ...]
    moving_part: tuple[bool, ...]
