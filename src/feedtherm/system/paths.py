"""Dotted paths into a description: ``joints[6].tcr``, ``sources.motor.heat_factor``.

Calibration, sensitivity and uncertainty parameters, provenance entries and variants name the
values of a description by such paths; ``[*]`` stands for every index of a list.  Here they are
split, read, expanded, and asked for the SI unit of their value and whether it would accept
another (the rules its own value passed).
"""

from __future__ import annotations

import difflib
import functools
import re
import types
import typing
from typing import Annotated, Any

from pydantic import BaseModel, TypeAdapter, ValidationError

from .quantities import SIUnit
from .schema import FeedSystem

_STEP = re.compile(r"([A-Za-z0-9_]+)|\[(\d+)\]")


def split_path(path: str) -> list[str | int]:
    """``"joints[6].tcr"`` -> ``["joints", 6, "tcr"]``."""
    keys: list[str | int] = []
    for part in path.split("."):
        for name, index in _STEP.findall(part):
            keys.append(int(index) if index else name)
    return keys


def get_path(obj: Any, path: str) -> Any:
    return _walk(obj, split_path(path))


def expand_path(obj: Any, path: str) -> list[str]:
    """Concrete paths for a path with ``[*]`` wildcards (every index of the list there)."""
    if "[*]" not in path:
        return [path]
    head, tail = path.split("[*]", 1)
    items = get_path(obj, head)
    return [p for i in range(len(items)) for p in expand_path(obj, f"{head}[{i}]{tail}")]


def unresolved(system: FeedSystem, path: str) -> str | None:
    """Why ``path`` (``[*]`` allowed) names no number of ``system``, with the closest path that
    does; ``None`` when it names one or more numbers."""
    try:
        values = [get_path(system, p) for p in expand_path(system, path)]
    except (KeyError, IndexError, AttributeError, TypeError):
        leaves = leaf_paths(system.model_dump())
        if "[*]" in path:
            leaves = list(dict.fromkeys(re.sub(r"\[\d+\]", "[*]", leaf) for leaf in leaves))
        match = difflib.get_close_matches(path, leaves, n=1, cutoff=0.6)
        hint = f"; did you mean {match[0]!r}?" if match else ""
        return f"{path!r} does not name a value of the description{hint}"
    if not values or any(isinstance(v, bool) or not isinstance(v, (int, float)) for v in values):
        return f"{path!r} does not name a number"
    return None


def _walk(obj: Any, keys: list[str | int]) -> Any:
    for key in keys:
        obj = obj[key] if isinstance(obj, (dict, list, tuple)) else getattr(obj, key)
    return obj


def si_unit_at(system: FeedSystem, path: str) -> str | None:
    """The SI unit the value at ``path`` is stored in (``None``: not a quantity field).

    Raises ``KeyError``/``IndexError``/``AttributeError`` where the path names no value.
    """
    keys = split_path(path)
    if len(keys) >= 2 and isinstance(keys[-1], int) and isinstance(_walk(system, keys[:-1]), tuple):
        # an element of a fixed-length tuple field (a point's coordinate, a box's size)
        owner, name = _walk(system, keys[:-2]), keys[-2]
        if not isinstance(owner, BaseModel) or name not in type(owner).model_fields:
            raise KeyError(path)
        elements = typing.get_args(type(owner).model_fields[name].annotation)
        if keys[-1] >= len(elements):
            raise IndexError(path)
        return _si_unit_in([elements[keys[-1]]])
    parent = _walk(system, keys[:-1])
    if not isinstance(parent, BaseModel) or keys[-1] not in type(parent).model_fields:
        raise KeyError(path)
    field = type(parent).model_fields[keys[-1]]
    return _si_unit_in([*field.metadata, field.annotation])


def _si_unit_in(items) -> str | None:
    for item in items:
        if isinstance(item, SIUnit):
            return item.unit
        found = _si_unit_in([*getattr(item, "__metadata__", ()), *typing.get_args(item)])
        if found is not None:
            return found
    return None


def refusal_at(system: FeedSystem, path: str, si_value: float) -> str | None:
    """Why the field at ``path`` would refuse ``si_value`` (in its SI unit) had the description
    stated it: the same validation (sign, :class:`~feedtherm.system.quantities.Limit`, bounds) its
    own value passed.  ``None`` where it accepts it, or where ``path`` names no field of a model
    (a share in a dict: its rules are the dict's, checked with the whole description).
    """
    keys = split_path(path)
    try:
        if len(keys) >= 2 and isinstance(keys[-1], int) and isinstance(_walk(system, keys[:-1]), tuple):
            owner, name, index = _walk(system, keys[:-2]), keys[-2], keys[-1]
        else:
            owner, name, index = _walk(system, keys[:-1]), keys[-1], None
    except (KeyError, IndexError, AttributeError, TypeError):
        return None
    if not isinstance(owner, BaseModel) or name not in type(owner).model_fields:
        return None
    adapter, unit = _field_adapter(type(owner), name, index)
    try:
        adapter.validate_python(f"{si_value!r} {unit}" if unit else si_value)
    except ValidationError as exc:
        reason = str(exc.errors()[0]["msg"]).removeprefix("Value error, ")
        return reason.split("; did you mean")[0]  # a typo's hint: the value is no typed text here
    return None


@functools.lru_cache(maxsize=None)
def _field_adapter(owner: type[BaseModel], name: str, index: int | None) -> tuple[TypeAdapter, str | None]:
    """A validator of one field of ``owner`` (of element ``index`` of a tuple field), with the
    field's constraints, and its SI unit; ``None`` left out of an optional field's type."""
    field = owner.model_fields[name]
    if index is not None:
        annotation = typing.get_args(field.annotation)[index]
    else:
        args = typing.get_args(field.annotation)
        annotation = field.annotation
        if type(None) in args and typing.get_origin(field.annotation) in (typing.Union, types.UnionType):
            annotation = typing.Union[tuple(a for a in args if a is not type(None))]
        if field.metadata:
            annotation = Annotated[(annotation, *field.metadata)]
    return TypeAdapter(annotation), _si_unit_in([annotation])


def leaf_paths(data, prefix: str = "") -> list[str]:
    """Dotted paths of every value in nested dicts/lists (lists of scalars are leaves)."""
    if isinstance(data, dict):
        paths = []
        for key, value in data.items():
            paths.extend(leaf_paths(value, f"{prefix}.{key}" if prefix else str(key)))
        return paths
    if isinstance(data, list) and any(isinstance(v, (dict, list)) for v in data):
        paths = []
        for i, value in enumerate(data):
            paths.extend(leaf_paths(value, f"{prefix}[{i}]"))
        return paths
    return [prefix]
