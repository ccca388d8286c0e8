"""A new bench folder from the template beside this file (``feedtherm new``).

The template (``_template/``: a commented single-drive ball-screw description, a README saying
what to replace, a SOURCES.md) is copied with the bench's name filled in. The folder is written
whole or not at all: into a temporary sibling first, renamed into place when complete.
"""

from __future__ import annotations

import re
import shutil
import uuid
from pathlib import Path

from ..errors import FeedthermError

TEMPLATE = Path(__file__).parent / "_template"
#: Replaced by the bench's name in every file of the template.
PLACEHOLDER = "__BENCH_NAME__"
_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")  # the description's names (system/schema.py)
_FILES = ("description.toml", "README.md", "SOURCES.md")


def new_bench(name: str, parent: str | Path = ".") -> Path:
    """Write the folder ``parent/name`` from the template and return it.

    Raises FeedthermError (one line) for a name that is not a valid bench name or a target
    that exists and is not an empty folder.
    """
    if not _NAME.match(name):
        raise FeedthermError(f"NAME: {name!r} is not a valid bench name (a letter, then letters, digits "
                             "or underscores, as a Python identifier without a leading underscore)")
    target = Path(parent) / name
    if target.exists() and (not target.is_dir() or any(target.iterdir())):
        what = "a folder that is not empty" if target.is_dir() else "a file"
        raise FeedthermError(f"{target}: exists and is {what}; choose another NAME or --out")
    parent_dir = target.parent
    parent_dir.mkdir(parents=True, exist_ok=True)
    staging = parent_dir / f".{name}-{uuid.uuid4().hex[:8]}.partial"
    staging.mkdir()  # as any folder the user makes (mkdtemp's would be private to the user)
    try:
        for file in _FILES:
            text = (TEMPLATE / file).read_text(encoding="utf-8")
            (staging / file).write_text(text.replace(PLACEHOLDER, name), encoding="utf-8")
        if target.exists():
            target.rmdir()  # empty, checked above
        staging.rename(target)
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise
    return target
