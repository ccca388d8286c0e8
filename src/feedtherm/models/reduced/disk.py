"""The reduced model's disk caches (bases, projected models): atomic ``.npz`` files kept within a budget.

Both caches hold what a run can rebuild, under a digest of everything it was built from, so a
file is either the right one or absent: it is written atomically (a reader sees the whole file
or none), a file that cannot be read is treated as absent (and rebuilt by the caller), and each
directory keeps the most recently used files within :data:`CACHE_BYTES`.
"""

from __future__ import annotations

import os
import time
import zipfile
from pathlib import Path
from typing import Callable, TypeVar

import numpy as np

#: Each cache directory keeps its most recently used files within this many bytes, the least
#: recently used dropped first (a fine-mesh basis is about 0.4 GB; the file just written is kept).
CACHE_BYTES = 2_000_000_000
#: [s] a partial file older than this is a killed writer's, not one being written.
STALE_PARTIAL = 3600.0

T = TypeVar("T")


def read_npz(path: Path, parse: Callable[[np.lib.npyio.NpzFile], T]) -> T | None:
    """``parse`` of the arrays in ``path``, or None when the file is missing or damaged; a file read
    back is marked recently used (the last to be pruned)."""
    try:
        with np.load(path, allow_pickle=False) as data:
            value = parse(data)
        os.utime(path)
        return value
    # a truncated or overwritten file fails as any of these, depending on where it breaks
    except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile):
        return None


def write_npz(path: Path, arrays: dict[str, np.ndarray]) -> None:
    """Save ``arrays`` atomically, then prune the directory; an unwritable cache only costs the next run time."""
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        partial = path.with_name(f".{path.stem}.{os.getpid()}.partial.npz")
        np.savez(partial, **arrays)
        os.replace(partial, path)
        prune(path.parent, keep=path)
    except OSError:
        pass


def prune(directory: Path, keep: Path, budget: int = CACHE_BYTES) -> None:
    """Drop the least recently used files beyond ``budget`` bytes, and partial files a killed writer left."""
    now = time.time()
    for partial in directory.glob(".*.partial.npz"):
        if now - partial.stat().st_mtime > STALE_PARTIAL:
            partial.unlink(missing_ok=True)
    files = sorted((p for p in directory.glob("*.npz") if p != keep), key=lambda p: p.stat().st_mtime, reverse=True)
    used = keep.stat().st_size
    for path in files:
        used += path.stat().st_size
        if used > budget:
            path.unlink(missing_ok=True)
