"""The description's reference, from the pydantic schema that validates every description: a
section per table (a model at a dotted path; a union of models by its tag, ``model = "motor"``),
an entry per key with its type, the SI unit it is stored in, its range (the quantity's rules,
the field's constraints), its default and what the schema says of it (a field's description, or
the comments beside it in the source)."""

from __future__ import annotations

import ast
import inspect
import json
import re
import textwrap
import types
import typing
from dataclasses import dataclass, field
from typing import Any

import annotated_types
from pydantic import BaseModel
from pydantic.fields import FieldInfo
from pydantic_core import PydanticUndefined

from .rst import escape, heading, indent, literal, rst_text


@dataclass(frozen=True)
class Key:
    """One key of a description, at its dotted path (``<name>``: any name; ``[]``: any item)."""

    path: str
    type: str
    unit: str  # the SI unit the value is stored in, "" where it has none
    range: str
    default: str
    description: str


@dataclass
class Section:
    """The keys of one table of a description (a pydantic model at a path)."""

    path: str  # "" for the top level
    title: str
    doc: str
    model: type[BaseModel]
    keys: list[Key] = field(default_factory=list)


def _plain(annotation) -> tuple[Any, list]:
    """``annotation`` without ``Annotated`` (its metadata returned beside it) and without ``None``."""
    metadata: list = []
    while typing.get_origin(annotation) is typing.Annotated:
        metadata += list(annotation.__metadata__)
        annotation = annotation.__origin__
    if _is_union(annotation):
        args = [a for a in typing.get_args(annotation) if a is not type(None)]
        if len(args) == 1:
            inner, more = _plain(args[0])
            return inner, metadata + more
    return annotation, metadata


def _is_union(annotation) -> bool:
    return typing.get_origin(annotation) in (typing.Union, types.UnionType)


def _is_model(annotation) -> bool:
    return isinstance(annotation, type) and issubclass(annotation, BaseModel)


def _alternatives(annotation) -> list:
    """The members of a union (``None`` left out), each without its ``Annotated``."""
    annotation, _ = _plain(annotation)
    if _is_union(annotation):
        return [_plain(a)[0] if typing.get_origin(a) is typing.Annotated else a
                for a in typing.get_args(annotation) if a is not type(None)]
    return [annotation]


def _si_unit(metadata: list):
    from feedtherm.system.quantities import SIUnit

    return next((m for m in metadata if isinstance(m, SIUnit)), None)


def _constraints(metadata: list) -> list:
    found = []
    for item in metadata:
        if isinstance(item, FieldInfo):
            found += _constraints(item.metadata)
        else:
            found.append(item)
    return found


def _type_text(annotation) -> str:
    """A value's type in words: ``quantity``, ``"dual" or "single"``, ``array of 3 quantities`` …"""
    annotation, metadata = _plain(annotation)
    if _si_unit(metadata) is not None:
        return "quantity" if _si_unit(metadata).unit else "number"
    origin = typing.get_origin(annotation)
    if origin is typing.Literal:
        return " or ".join(json.dumps(v) for v in typing.get_args(annotation))
    if _is_union(annotation):
        texts = [_type_text(a) for a in typing.get_args(annotation) if a is not type(None)]
        return " or ".join(dict.fromkeys(texts))  # the members of a union of tables: "table"
    if origin is tuple:
        args = typing.get_args(annotation)
        if len(args) == 2 and args[1] is Ellipsis:
            return f"array of {_plural(args[0])}"
        if len({repr(a) for a in args}) == 1:
            return f"array of {len(args)} {_plural(args[0])}"
        return "array of " + ", ".join(_type_text(a) for a in args)
    if origin is list:
        return f"array of {_plural(typing.get_args(annotation)[0])}"
    if origin is dict:
        return f"table of {_plural(typing.get_args(annotation)[1])} by name"
    if _is_model(annotation):
        return "table"
    return {bool: "boolean", int: "integer", float: "number", str: "string"}.get(annotation, str(annotation))


def _plural(annotation) -> str:
    text = _type_text(annotation)
    if " or " in text or text.startswith('"'):
        return f"({text})"
    return {"quantity": "quantities", "boolean": "booleans", "integer": "integers", "number": "numbers",
            "string": "strings", "table": "tables"}.get(text, text)


def _unit_of(annotation) -> str:
    """The SI unit of a quantity, of a tuple's or a list's quantities, or of a union's."""
    annotation, metadata = _plain(annotation)
    unit = _si_unit(metadata)
    if unit is not None:
        return unit.unit
    for arg in typing.get_args(annotation):
        if arg is not Ellipsis and (found := _unit_of(arg)):
            return found
    return ""


def _range_text(annotation, metadata: list) -> str:
    """What a value must satisfy, from the field's constraints and its quantity's rules."""
    inner, more = _plain(annotation)
    metadata = [*metadata, *more]
    rules = []
    unit = _si_unit(metadata)
    if unit is None and (typing.get_origin(inner) in (tuple, list, dict) or _is_union(inner)):
        unit = next((u for a in typing.get_args(inner) if a is not Ellipsis
                     for u in [_si_unit(_plain(a)[1])] if u is not None), None)
    if unit is not None:
        rules.append(_quantity_range(unit))
    for item in _constraints(metadata):
        for attribute, symbol in (("gt", ">"), ("ge", "≥"), ("lt", "<"), ("le", "≤")):
            if isinstance(item, getattr(annotated_types, attribute.capitalize())):
                rules.append(f"{symbol} {getattr(item, attribute):g}")
        if isinstance(item, annotated_types.MinLen) and item.min_length:
            if inner is str:
                rules.append("not empty")
            else:
                rules.append(f"at least {item.min_length} item{'s' if item.min_length > 1 else ''}")
        if isinstance(item, annotated_types.MaxLen):
            rules.append(f"at most {item.max_length} items")
        if getattr(item, "pattern", None):
            rules.append(f"matches ``{item.pattern}``")
    return "; ".join(rules)


def _quantity_range(unit) -> str:
    """A quantity's rules in words: its sign, its smallest size, its :class:`Limit` in the unit the
    limit is shown in, with the limit's reason."""
    from feedtherm.system.quantities import registry

    limit = unit.limit
    sign = {"positive": "above 0", "nonnegative": "0 or more"}.get(unit.sign, "")
    size = f"nonzero sizes at least {unit.minimum * 1e6:g} µm" if unit.minimum is not None else ""
    if limit is None:
        return ", ".join(part for part in (sign, size) if part)
    low, high = (float(registry().Quantity(x, limit.si).to(limit.unit).magnitude) for x in (limit.low, limit.high))
    shown = f" {limit.unit}" if limit.unit else ""
    if limit.magnitude:
        span = f"|value| ≤ {high:g}{shown}"
    elif limit.low == 0.0 and sign:
        span = f"{sign}, up to {high:g}{shown}"
        sign = ""
    else:
        span = f"{low:g} to {high:g}{shown}"
        sign = ""  # a lower limit above 0 says the sign (an absolute temperature's)
    return ", ".join(part for part in (sign, size, span) if part) + f" ({limit.reason})"


def _default_text(info: FieldInfo, unit: str) -> str:
    if info.default_factory is not None:
        value = info.default_factory()
    elif info.default is PydanticUndefined:
        return "required"
    else:
        value = info.default
    if value is None:
        return "none (left out)"
    if isinstance(value, BaseModel):
        return "its keys' defaults"
    if isinstance(value, bool):
        return json.dumps(value)
    if isinstance(value, float) and unit:
        return f"{value:g} {unit}"
    if isinstance(value, (int, float)):
        return f"{value:g}"
    return json.dumps(value, ensure_ascii=False)


def _defining_class(model: type[BaseModel], name: str) -> type:
    for cls in model.__mro__:
        if name in cls.__dict__.get("__annotations__", {}):
            return cls
    return model


_COMMENTS: dict[type, dict[str, str]] = {}


def field_comments(cls: type) -> dict[str, str]:
    """What the source says of each field of ``cls``: the ``#`` comment block right above it and
    the comment at its line's end (the schema documents its fields so)."""
    if cls in _COMMENTS:
        return _COMMENTS[cls]
    try:
        lines, _ = inspect.getsourcelines(cls)
    except (OSError, TypeError):
        return {}
    source = textwrap.dedent("".join(lines))
    body = source.splitlines()
    found: dict[str, str] = {}
    for node in ast.parse(source).body[0].body:
        if not (isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name)):
            continue
        above = []
        row = node.lineno - 2
        while row >= 0 and body[row].strip().startswith("#"):
            above.insert(0, body[row].strip().lstrip("#").removeprefix(":").strip())
            row -= 1
        trailing = _trailing_comment(body[node.end_lineno - 1])
        text = " — ".join(part for part in (" ".join(above), trailing) if part)
        if text:
            found[node.target.id] = text
    _COMMENTS[cls] = found
    return found


def _trailing_comment(line: str) -> str:
    """The comment at the end of a line of code (a ``#`` outside strings)."""
    import io
    import tokenize

    try:
        for token in tokenize.generate_tokens(io.StringIO(line.strip() + "\n").readline):
            if token.type == tokenize.COMMENT:
                return token.string.lstrip("#").strip()
    except (tokenize.TokenError, IndentationError, SyntaxError):
        return ""
    return ""


def _description(model: type[BaseModel], name: str, info: FieldInfo) -> str:
    if info.description:
        return info.description
    return field_comments(_defining_class(model, name)).get(name, "")


def _doc(model: type) -> str:
    doc = model.__dict__.get("__doc__")
    return inspect.cleandoc(doc) if doc else ""


def _child_path(prefix: str, name: str) -> str:
    return f"{prefix}.{name}" if prefix else name


def description_sections(root: type[BaseModel] | None = None) -> list[Section]:
    """Every table of a description, depth first, each with every key it takes."""
    if root is None:
        from feedtherm.system.schema import FeedSystem

        root = FeedSystem
    sections: list[Section] = []
    _walk(root, "", "The top level", sections)
    return sections


def _walk(model: type[BaseModel], path: str, title: str, sections: list[Section],
          fields: list[str] | None = None) -> None:
    section = Section(path, title, _doc(model), model)
    sections.append(section)
    later: list[tuple] = []
    for name, info in model.model_fields.items():
        if fields is not None and name not in fields:
            continue
        key_path = _child_path(path, name)
        annotation = info.annotation
        if info.metadata:
            annotation = typing.Annotated[(annotation, *info.metadata)]
        unit = _unit_of(annotation)
        section.keys.append(Key(key_path, _type_text(annotation), unit, _range_text(annotation, []),
                                _default_text(info, unit), _description(model, name, info)))
        later += _nested(annotation, key_path)
    for child, child_path, child_title in later:
        _walk_union_or_model(child, child_path, child_title, sections)


def _nested(annotation, path: str) -> list[tuple]:
    """The tables a key holds: a model, a table of models by name, an array of models."""
    inner, _ = _plain(annotation)
    origin = typing.get_origin(inner)
    if origin is dict:
        return _nested(typing.get_args(inner)[1], f"{path}.<name>")
    if origin is list:
        return _nested(typing.get_args(inner)[0], f"{path}[]")
    models = [a for a in _alternatives(inner) if _is_model(a)]
    if len(models) == 1:
        return [(models[0], path, path)]
    if models:
        return [(inner, path, path)]
    return []


def _discriminator(members: list[type[BaseModel]]) -> str | None:
    for name in members[0].model_fields:
        if all(typing.get_origin(m.model_fields.get(name, FieldInfo()).annotation) is typing.Literal
               for m in members):
            return name
    return None


def _walk_union_or_model(annotation, path: str, title: str, sections: list[Section]) -> None:
    if _is_model(annotation):
        _walk(annotation, path, title, sections)
        return
    members = [a for a in _alternatives(annotation) if _is_model(a)]
    tag = _discriminator(members)
    # the keys every member takes from one base class are listed once, before the members' own
    common = [name for name in members[0].model_fields
              if name != tag and all(name in m.model_fields for m in members)
              and len({_defining_class(m, name) for m in members}) == 1]
    if common:
        base = _defining_class(members[0], common[0])
        _walk(members[0], path, f"{path} (every {tag})", sections, fields=common)
        sections[-1].doc = _doc(base)
    for member in members:
        value = typing.get_args(member.model_fields[tag].annotation)[0] if tag else member.__name__
        own = [name for name in member.model_fields if name not in common]
        _walk(member, path, f"{path} ({tag} = {json.dumps(value)})" if tag else path, sections, fields=own)


def description_rst(sections: list[Section] | None = None) -> str:
    """The description's reference: a section per table, an entry per key; a key that holds tables
    links to their sections."""
    sections = description_sections() if sections is None else sections
    labels = [_label(section) for section in sections]
    lines: list[str] = []
    for section, label in zip(sections, labels):
        lines += [f".. _{label}:", "", *heading(f"``{section.title}``" if section.path else section.title, "-")]
        if section.doc:
            lines += [section.doc, ""]
        for key in section.keys:
            tables = [f":ref:`{escape(_link_text(other))} <{other_label}>`"
                      for other, other_label in zip(sections, labels)
                      if other.path in (key.path, f"{key.path}.<name>", f"{key.path}[]")]
            body = _key_body(key) + ("\n\nIts keys: " + ", ".join(tables) + "." if tables else "")
            lines += [f"``{key.path}``", *indent(body), ""]
    return "\n".join(lines)


def _link_text(section: Section) -> str:
    """A section's title, or only what tells a kind of table from the others (``model = "motor"``)."""
    return section.title[len(section.path) + 2:-1] if section.title.endswith(")") else section.title


def _label(section: Section) -> str:
    return "desc-" + (re.sub(r"[^a-z0-9]+", "-", section.title.lower()).strip("-") or "top")


#: Defaults that are words, not values.
_NO_VALUE = ("required", "none (left out)", "its keys' defaults")


def _key_body(key: Key) -> str:
    # the values a key takes (its choices, its default) as literals: typography leaves them alone
    facts = ["".join(literal(part) if part.startswith('"') else escape(part)
                     for part in re.split(r'("[^"]*")', key.type) if part)]
    if key.unit:
        facts.append(f"in {literal(key.unit)}")
    if key.range:
        facts.append(rst_text(key.range))
    facts.append(f"default: *{key.default}*" if key.default in _NO_VALUE else f"default: {literal(key.default)}")
    body = " · ".join(facts)
    if key.description:
        body += "\n\n" + rst_text(key.description)
    return body
