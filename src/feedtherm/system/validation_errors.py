"""One line for a pydantic ValidationError: ``path: reason``, as the description reads.

The path is the field's, dotted (``joints[3].tcr``); an unknown key is answered with the closest
valid name of the model at its place, found by walking :class:`~feedtherm.system.schema.FeedSystem`;
a value that no member of a union took, with the member it was meant for.
"""

from __future__ import annotations

import difflib
import re
from typing import get_args

from pydantic import BaseModel, ValidationError

from .schema import FeedSystem

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
