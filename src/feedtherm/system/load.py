"""Load a feed-system description from a TOML file or a bench name (feedtherm.benches).

Every problem becomes one :class:`~feedtherm.errors.DescriptionError` whose message names
the file, the field (as a dotted path) and the reason; unknown keys are answered with the
closest valid name.
"""

from __future__ import annotations

import difflib
import hashlib
import json
import os
import re
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, get_args

from pydantic import BaseModel, ValidationError

from ..benches import ORIGIN_PREFIX, bench, bench_names, suggestion
from ..errors import ArgumentError, DescriptionError
from .areas import with_joint_areas
from .files import parse_bounded_toml, read_text_file
from .schema import FeedSystem

if TYPE_CHECKING:  # pragma: no cover
    from .overlay import Overlay


@dataclass(frozen=True)
class LoadedSystem:
    """A validated description with where it came from and the hash of its content."""

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
    from .checks import check_errors  # checks reads descriptions through variants, which imports this module

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


#: Sections that descriptions of earlier versions had, and what replaced them.
_REPLACED = {"elongation": "the elongation D is now what a declared displacement sensor reads; replace [elongation] "
                           "by a [mechanics] section (supports, elongation, positioning; docs/system-description.md)"}


def describe_error(exc: ValidationError) -> str:
    """One line for the first error of a pydantic ValidationError: ``path: reason``."""
    errors = exc.errors(include_url=False)
    # A misspelt key also makes the right key "missing": report the cause, not the symptom.
    error = next((e for e in errors if e["type"] == "extra_forbidden"), None)
    branches = [] if error is not None else _union_branches(errors)
    if branches:  # a value a union of types refused: the branch meant, not the first tried
        return _describe_union(branches, errors)
    error = error or errors[0]
    raw_loc = list(error["loc"])
    loc = [part for part in raw_loc if not _is_union_tag(part)]
    path = _dotted(loc)
    kind, message = error["type"], error["msg"]
    if kind == "finite_number":
        return f"{path}: {_message(error)}"
    if kind == "extra_forbidden":
        key = str(loc[-1])
        parent = _dotted(loc[:-1])
        if not parent and key in _REPLACED:
            return f"unknown key {key!r}: {_REPLACED[key]}"
        valid = _valid_keys(raw_loc[:-1])
        where = f" in {parent}" if parent else ""
        hint = difflib.get_close_matches(key, valid, n=1, cutoff=0.5)
        suggestion = f"; did you mean {hint[0]!r}?" if hint else (f"; valid keys: {', '.join(valid)}" if valid else "")
        return f"unknown key {key!r}{where}{suggestion}"
    if kind == "missing":
        return f"{path}: missing (required)"
    if kind == "bool_type":  # strict: "yes", "off" and 1 are not read as booleans
        return f"{path}: {error['input']!r} is not a boolean; write true or false"
    if kind == "literal_error":  # pydantic's "Input should be ..." does not say what was given
        return f"{path}: {error['input']!r} is not allowed; allowed values: {error['ctx']['expected']}"
    if kind == "union_tag_invalid":
        key = error["ctx"]["discriminator"].strip("'")
        return (f"{_dotted([*loc, key])}: {error['ctx']['tag']!r} is not allowed; "
                f"allowed values: {error['ctx']['expected_tags']}")
    if message.startswith("Value error, "):
        message = message[len("Value error, "):]
    if not path:  # cross-reference errors carry their own path
        return message
    return f"{path}: {message}"


#: How pydantic labels the members of a plain union in an error's location: ``literal['ambient']``,
#: ``function-before[<lambda>(), float]`` (a quantity), ``str``, ``float``.
_BRANCH_LABEL = re.compile(r"^(literal\[|function-(before|after|wrap|plain)\[|(str|float|int|bool)$)")
#: A string that is written as a number (a quantity), not as a word.
_NUMERIC = re.compile(r"^\s*[-+]?(\d|\.\d|inf|nan)", re.IGNORECASE)


def _union_branches(errors: list[dict]) -> list[dict]:
    """The errors of the first error's union members (one per member it tried), or [] where the first
    error is not one of a plain union (``Literal["ambient"] | Temperature``, ``str | float``)."""
    loc = errors[0]["loc"]
    if not loc or not isinstance(loc[-1], str):
        return []
    branches = [e for e in errors if len(e["loc"]) == len(loc) and e["loc"][:-1] == loc[:-1]
                and isinstance(e["loc"][-1], str)]
    labels = [e["loc"][-1] for e in branches]
    # a model's branch is labelled by its class name; field names and a description's own names never
    # come with a literal's, a quantity's or a plain type's label beside them
    if len(branches) < 2 or not any(_BRANCH_LABEL.match(label) for label in labels):
        return []
    return branches


def _describe_union(branches: list[dict], errors: list[dict]) -> str:
    """One line for a value no member of a union took: a word is answered with the words allowed, a
    number or quantity with what is wrong with it as one (out of range, not finite), a table with what
    is wrong inside it, and the other allowed values beside."""
    where = branches[0]["loc"][:-1]
    path = _dotted([part for part in where if not _is_union_tag(part)])
    value = branches[0]["input"]
    words = next((e for e in branches if e["type"] == "literal_error"), None)
    quantity = any(str(e["loc"][-1]).startswith("function-") for e in branches)
    inner = next((e for e in errors if len(e["loc"]) > len(where) + 1 and e["loc"][:len(where)] == where), None)
    if isinstance(value, dict) and inner is not None:  # a table: what its model member found inside it
        inside = _dotted([where_part for where_part in inner["loc"][len(where) + 1:]])
        return f"{path}.{inside}: {_message(inner)}"
    if words is not None and not (isinstance(value, str) and _NUMERIC.match(value)) \
            and not isinstance(value, (int, float)):
        more = ", or a quantity with its unit" if quantity else ""
        return f"{path}: {value!r} is not allowed; allowed values: {words['ctx']['expected']}{more}"
    # a type mismatch says only that the value is not of another member's type
    error = next((e for e in branches if e["type"] not in ("literal_error", "model_type", "dict_type")
                  and not e["type"].endswith("_type")), branches[0])
    message = _message(error)
    if words is None:
        return f"{path}: {message}"
    instead = f"llowed instead: {words['ctx']['expected']}"
    return f"{path}: {message} A{instead}" if message.endswith("?") else f"{path}: {message}; a{instead}"


def _message(error: dict) -> str:
    """An error's reason as one of ours reads: the validator's own words, or what pydantic says."""
    if error["type"] == "finite_number":  # pydantic's "Input should be ..." does not say what was given
        return f"must be a finite number, got {error['input']!r}"
    return error["msg"].removeprefix("Value error, ")


def _is_union_tag(part) -> bool:
    # pydantic inserts the discriminator value ("bearing", "natural", ...) into locations
    return isinstance(part, str) and part in _TAGS


_TAGS = {"bearing", "motor", "guideway", "sliding_screw", "ball_screw", "torque", "fixed", "natural", "rotating", "moving_plate", "moving_face",
         "datasheet", "rated"}


def _dotted(loc) -> str:
    text = ""
    for part in loc:
        text += f"[{part}]" if isinstance(part, int) else (f".{part}" if text else str(part))
    return text


def _valid_keys(loc) -> list[str]:
    """Field names of the model at ``loc`` (walking the schema), for 'did you mean'.

    ``loc`` is pydantic's raw location: field names, dict keys, list indices and, inside a
    discriminated union, the tag (``"bearing"``, ``"natural"``, ...) that picks the member.
    """
    candidates: list[type[BaseModel]] = [FeedSystem]
    for part in loc:
        if isinstance(part, int) or not candidates:
            continue
        tagged = [m for m in candidates if _tag_of(m) == part]
        if tagged:
            candidates = tagged
            continue
        field = candidates[0].model_fields.get(str(part))
        if field is None:  # a dict key such as a part's name
            continue
        candidates = _models_in(field.annotation)
    return sorted(candidates[0].model_fields) if len(candidates) == 1 else []


def _tag_of(model: type[BaseModel]) -> str | None:
    """The discriminator value of a union member (its ``model`` or ``kind`` literal)."""
    for key in ("model", "kind"):
        field = model.model_fields.get(key)
        if field is not None and get_args(field.annotation):
            return get_args(field.annotation)[0]
    return None


def _models_in(annotation) -> list[type[BaseModel]]:
    """The BaseModel classes inside an annotation such as ``dict[str, Part]`` or a union."""
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return [annotation]
    found: list[type[BaseModel]] = []
    for arg in get_args(annotation):
        found.extend(m for m in _models_in(arg) if m not in found)
    return found
