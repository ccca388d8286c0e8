"""Variants of a loaded description: some values replaced, everything else shared.

Used by sweeps (an extra condition), sensitivity studies (one value scaled) and calibration
(fitted values).  Values are set in SI units on the validated objects; the result carries a
new SHA-256 so its provenance differs from the original's.
"""

from __future__ import annotations

import hashlib
import json
from dataclasses import replace
from typing import Any

from pydantic import BaseModel, ValidationError

from ..errors import DescriptionError
from .areas import with_joint_areas
from .load import LoadedSystem
from .paths import get_path, split_path
from .schema import Condition, FeedSystem
from .validation_errors import describe_error


def _set(obj: Any, keys: list, value: Any) -> Any:
    if not keys:
        return value
    key, rest = keys[0], keys[1:]
    if isinstance(obj, BaseModel):
        if not isinstance(key, str) or key not in type(obj).model_fields:
            raise DescriptionError(f"no field {key!r} in {type(obj).__name__}")
        return obj.model_copy(update={key: _set(getattr(obj, key), rest, value)})
    if isinstance(obj, dict):
        copy = dict(obj)
        copy[key] = _set(obj.get(key), rest, value) if rest else value
        return copy
    if isinstance(obj, (list, tuple)):
        items = list(obj)
        items[key] = _set(items[key], rest, value)
        return type(obj)(items) if isinstance(obj, tuple) else items
    raise DescriptionError(f"cannot set {key!r} inside a {type(obj).__name__}")


def with_values(loaded: LoadedSystem, changes: dict[str, Any], origin_suffix: str = "variant") -> LoadedSystem:
    """A copy of ``loaded`` with each dotted path in ``changes`` set to its value (SI units)."""
    system: FeedSystem = loaded.system
    for path, value in changes.items():
        try:
            get_path(system, path)
        except (KeyError, IndexError, AttributeError, TypeError):
            raise DescriptionError(f"{path}: no such value in {loaded.origin}") from None
        system = _set(system, split_path(path), value)
    # A joint area the geometry gave follows a change of the geometry; one set here is stated.
    derived = tuple(i for i in loaded.derived_joint_areas
                    if not any(path in ("joints", f"joints[{i}]", f"joints[{i}].area") for path in changes))
    if derived and any(path == "parts" or path.startswith(("parts.", "parts[")) for path in changes):
        joints = [j.model_copy(update={"area": None}) if i in derived else j for i, j in enumerate(system.joints)]
        try:
            system, _ = with_joint_areas(system.model_copy(update={"joints": joints}))
        except ValueError as exc:
            raise DescriptionError(f"{loaded.origin} ({origin_suffix}): {exc}") from None
    canonical = json.dumps(system.model_dump(mode="json"), sort_keys=True, separators=(",", ":"))
    return replace(loaded, system=system, origin=f"{loaded.origin} ({origin_suffix})",
                   sha256=hashlib.sha256(canonical.encode()).hexdigest(), derived_joint_areas=derived)


def with_condition(loaded: LoadedSystem, name: str, screw_rpm: float, nut_rpm: float, ambient_c: float,
                   duration_s: float | None = None) -> LoadedSystem:
    """A copy of ``loaded`` with one more (or a replaced) constant condition."""
    data = {"screw_speed": f"{screw_rpm} rpm", "nut_speed": f"{nut_rpm} rpm", "ambient": f"{ambient_c} degC"}
    if duration_s is not None:
        data["duration"] = f"{duration_s} s"
    try:
        condition = Condition.model_validate(data)
    except ValidationError as exc:
        raise DescriptionError(f"condition {name} ({screw_rpm:g} rpm, {nut_rpm:g} rpm, {ambient_c:g} degC): "
                               f"{describe_error(exc)}") from None
    conditions = {**loaded.system.conditions, name: condition}
    return with_values(loaded, {"conditions": conditions}, origin_suffix=f"condition {name}")
