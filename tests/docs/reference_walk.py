"""What the site's reference must hold, enumerated apart from the generator
(docs/_ext/feedtherm_reference/): every key of a description, by a short walk of the pydantic
schema, and every argument of every command, from the argparse parser.  The reference's tests
(test_docs_reference.py) and the built site's (test_docs_site.py) compare the pages with these.
"""

from __future__ import annotations

import argparse
import types
import typing

from pydantic import BaseModel

from feedtherm.cli import build_parser
from feedtherm.system.quantities import SIUnit


def schema_keys(model: type[BaseModel], prefix: str = "") -> dict[str, typing.Any]:
    """Every key's dotted path (``<name>``: any name, ``[]``: any item), with its annotation."""
    keys = {}
    for name, info in model.model_fields.items():
        path = f"{prefix}.{name}" if prefix else name
        keys[path] = typing.Annotated[(info.annotation, *info.metadata)] if info.metadata else info.annotation
        for table_path, table in tables_in(info.annotation, path):
            keys.update(schema_keys(table, table_path))
    return keys


def tables_in(annotation, path: str) -> list[tuple[str, type[BaseModel]]]:
    origin, args = typing.get_origin(annotation), typing.get_args(annotation)
    if origin is typing.Annotated:
        return tables_in(args[0], path)
    if origin in (typing.Union, types.UnionType):
        return [found for arg in args for found in tables_in(arg, path)]
    if origin is dict:
        return tables_in(args[1], f"{path}.<name>")
    if origin is list:
        return tables_in(args[0], f"{path}[]")
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return [(path, annotation)]
    return []


def si_unit(annotation) -> SIUnit | None:
    """The SI unit a quantity (or a tuple, list or union of quantities) is stored in."""
    for item in (*getattr(annotation, "__metadata__", ()), *typing.get_args(annotation)):
        found = item if isinstance(item, SIUnit) else si_unit(item) if item is not Ellipsis else None
        if found is not None:
            return found
    return None


def parser_options() -> dict[str, set[str]]:
    """Program -> the names of its arguments: each option string, a positional by its metavar or dest."""
    parser = build_parser()
    programs = {"feedtherm": parser}
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            programs.update({f"feedtherm {name}": sub for name, sub in action.choices.items()})
    options = {}
    for program, sub in programs.items():
        options[program] = {name for action in sub._actions
                            if not isinstance(action, (argparse._HelpAction, argparse._SubParsersAction))
                            for name in (action.option_strings or [action.metavar or action.dest])}
    return options
