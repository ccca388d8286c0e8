"""Load a feed-system description from a TOML file or a bench name (feedtherm.benches).

Every problem becomes one :class:`~feedtherm.errors.DescriptionError` whose message names
the file, the field (as a dotted path) and the reason; unknown keys are answered with the
closest valid name (system/validation_errors.py).
"""

from __future__ import annotations

import hashlib
import json
import os
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from pydantic import ValidationError

from ..benches import ORIGIN_PREFIX, bench, bench_names, suggestion
from ..errors import ArgumentError, DescriptionError
from .areas import with_joint_areas
from .checks import check_errors
from .files import parse_bounded_toml, read_text_file
from .schema import FeedSystem
from .validation_errors import describe_error

if TYPE_CHECKING:  # pragma: no cover
    from .overlay import Overlay


@dataclass(frozen=True)
class LoadedSystem:
    """A validated description with where it came from and the hash of its content.

    Attributes
    ----------
    system : FeedSystem
        The validated description (docs/system-description.md), every value in SI units.
    origin : str
        The file's path, or ``"bundled:<bench name>"``.
    sha256 : str
        The hash of the resolved description (canonical JSON of the validated data).
    derived_joint_areas : tuple of int
        The joints whose area the geometry gave (none was stated).
    overlay : Overlay or None
        The printed values its runs lay over the physics (the mode ``ft.load`` was given).
    """

    system: FeedSystem
    origin: str  # file path or "bundled:<bench name>"
    sha256: str  # of the resolved description (canonical JSON of the validated data)
    derived_joint_areas: tuple[int, ...] = ()  # joints whose area the geometry gave (none was stated)
    overlay: "Overlay | None" = None  # printed values its runs lay over the physics (system/overlay.py)


def read_text(spec: str) -> tuple[str, str]:
    """Return ``(text, origin)`` for a bench name or a file path (a bench name wins)."""
    if spec in bench_names():
        origin = f"{ORIGIN_PREFIX}{spec}"
        return _read(bench(spec).description, origin), origin
    if not spec:
        raise DescriptionError("an empty name: give a bench's name or a description's path")
    path = Path(spec)
    if not path.exists():
        hint = "" if spec.endswith(".toml") else f" or bench{suggestion(spec)}"
        raise DescriptionError(f"{spec}: no such file{hint}")
    if path.is_dir():
        raise DescriptionError(f"{spec}: is a directory, not a TOML file")
    return _read(path, spec), str(path)


def _read(path: Path, origin: str) -> str:
    """A regular file of at most MAX_DESCRIPTION_BYTES, UTF-8 with or without a BOM (system/files.py)."""
    return read_text_file(path, origin)


def parse_toml(text: str, origin: str) -> dict:
    if not text.strip():
        raise DescriptionError(f"{origin}: the file is empty; a description needs [meta], [parts], ... (see docs/system-description.md)")
    return parse_bounded_toml(text, origin)


def load_system(spec: str = "paper") -> LoadedSystem:
    """Load a description given as a TOML path or a bench name, and validate it (:func:`validate_description`)."""
    text, origin = read_text(spec)
    return validate_description(parse_toml(text, origin), origin)


def as_loaded(system: "LoadedSystem | str | os.PathLike", argument: str = "system") -> LoadedSystem:
    """``system`` as given if loaded, else loaded from a bench name or a description's path.

    Parameters
    ----------
    system : LoadedSystem, str or path-like
        A loaded description, a bench name or the path of a TOML description.
    argument : str
        The caller's name for ``system``, which the error for anything else names.

    Raises
    ------
    ArgumentError
        ``system`` is none of those.
    DescriptionError
        The bench or file cannot be loaded.
    """
    if isinstance(system, LoadedSystem):
        return system
    if isinstance(system, (str, os.PathLike)):
        return load_system(os.fspath(system))
    raise ArgumentError(argument, "a description from feedtherm.load(), a bench name or a path, "
                                  f"got {type(system).__name__}")


def validate_description(data: dict, origin: str) -> LoadedSystem:
    """Validate parsed description data: its schema, then :func:`~feedtherm.system.checks.check_errors`.

    The checks find what no model can run as meant (sensors off their parts, faces that do not
    exist, joints declared twice, ...); the first is raised as one line, so that no command
    starts on such a description.
    """
    loaded = validate_data(data, origin)
    errors = check_errors(loaded.system)
    if errors:
        more = f" (and {len(errors) - 1} more error{'s' if len(errors) > 2 else ''}: run feedtherm check)" \
            if len(errors) > 1 else ""
        raise DescriptionError(f"{origin}: {errors[0]}{more}")
    return loaded


def validate_data(data: dict, origin: str) -> LoadedSystem:
    """Validate already-parsed description data against the schema only (variants of a checked description)."""
    try:
        system = FeedSystem.model_validate(data)
    except ValidationError as exc:
        raise DescriptionError(f"{origin}: {describe_error(exc)}") from None
    try:
        system, derived = with_joint_areas(system)
    except ValueError as exc:
        raise DescriptionError(f"{origin}: {exc}") from None
    canonical = json.dumps(system.model_dump(mode="json"), sort_keys=True, separators=(",", ":"))
    return LoadedSystem(system, origin, hashlib.sha256(canonical.encode()).hexdigest(), tuple(derived))
