"""The command line's reference, from the parser ``feedtherm`` reads its arguments with: a
section per command, an ``option`` entry per argument with its help, default and choices."""

from __future__ import annotations

import argparse
import textwrap
from dataclasses import dataclass
from typing import Any

from .rst import heading, indent, literal, rst_text


@dataclass(frozen=True)
class Option:
    """One argument of a command, as ``feedtherm COMMAND -h`` lists it."""

    invocation: str  # "--model MODEL", "system"
    help: str
    default: Any = None  # None: none worth stating
    choices: tuple[str, ...] = ()
    required: bool = False
    exclusive_with: tuple[str, ...] = ()  # the other options of its mutually exclusive group


@dataclass(frozen=True)
class Command:
    """A command of ``feedtherm`` (the program itself has the name ``""``)."""

    name: str
    help: str
    usage: str
    options: tuple[Option, ...]

    @property
    def program(self) -> str:
        return f"feedtherm {self.name}".strip()


def _subcommands(parser: argparse.ArgumentParser) -> dict[str, argparse.ArgumentParser]:
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            return dict(action.choices)
    return {}


def _command_help(parser: argparse.ArgumentParser) -> dict[str, str]:
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            return {choice.dest: choice.help or "" for choice in action._choices_actions}
    return {}


def _options(parser: argparse.ArgumentParser) -> tuple[Option, ...]:
    formatter = parser._get_formatter()
    exclusive = {}
    for group in parser._mutually_exclusive_groups:
        names = [a.option_strings[-1] if a.option_strings else a.dest for a in group._group_actions]
        for action, name in zip(group._group_actions, names):
            exclusive[id(action)] = tuple(n for n in names if n != name)
    options = []
    for action in parser._actions:
        if isinstance(action, (argparse._HelpAction, argparse._SubParsersAction)) or action.help == argparse.SUPPRESS:
            continue
        default = action.default
        if default in (None, argparse.SUPPRESS) or isinstance(action, (argparse._StoreTrueAction,
                                                                       argparse._VersionAction)):
            default = None
        options.append(Option(
            invocation=formatter._format_action_invocation(action),
            help=formatter._expand_help(action) if action.help else "",
            default=default,
            choices=tuple(str(c) for c in action.choices) if action.choices else (),
            required=bool(action.required) and bool(action.option_strings),
            exclusive_with=exclusive.get(id(action), ()),
        ))
    return tuple(options)


def cli_commands(parser: argparse.ArgumentParser | None = None) -> list[Command]:
    """The program and each of its commands, in the parser's order, with every option."""
    if parser is None:
        from feedtherm.cli import build_parser

        parser = build_parser()
    helps = _command_help(parser)
    commands = [Command("", parser.description or "", parser.format_usage().strip(), _options(parser))]
    for name, sub in _subcommands(parser).items():
        commands.append(Command(name, helps.get(name, ""), sub.format_usage().strip(), _options(sub)))
    return commands


def _usage(text: str) -> str:
    return " ".join(text.removeprefix("usage:").split())


def cli_rst(commands: list[Command] | None = None) -> str:
    """The command-line reference: a section per command, an ``option`` entry per argument."""
    commands = cli_commands() if commands is None else commands
    lines: list[str] = []
    for command in commands:
        title = command.program
        lines += [f".. _cli-{command.name or 'feedtherm'}:", "", *heading(f"``{title}``", "-")]
        if command.help:
            lines += [rst_text(_sentence(command.help)), ""]
        lines += ["::", "", *indent(_wrap_usage(_usage(command.usage))), ""]
        if not command.name:
            lines += ["Every command also takes ``-h``/``--help``: its usage and options, as below.", ""]
        if not command.options:
            lines += ["The command takes no options.", ""]
            continue
        lines += [f".. program:: {title}", ""]
        for option in command.options:
            lines += [f".. option:: {option.invocation}", ""]
            lines += indent(_option_body(option)) + [""]
    return "\n".join(lines)


def _sentence(text: str) -> str:
    """``text`` ending as a sentence (its first word may be a value, ``physics (default): …``, so
    its case stays)."""
    text = text.strip()
    return text + ("" if text.endswith((".", ")")) else ".")


def _wrap_usage(usage: str) -> str:
    return "\n".join(textwrap.wrap(usage, 96, subsequent_indent="    ", break_on_hyphens=False, break_long_words=False))


def _option_body(option: Option) -> str:
    parts = [rst_text(_sentence(option.help)) if option.help else ""]
    facts = []
    if option.required:
        facts.append("Required.")
    if option.choices:
        facts.append("Choices: " + ", ".join(literal(c) for c in option.choices) + ".")
    if option.default is not None and "default" not in option.help.lower():
        facts.append(f"Default: {literal(str(option.default))}.")
    if option.exclusive_with:
        facts.append("Not with " + ", ".join(literal(n) for n in option.exclusive_with) + ".")
    if facts:
        parts.append(" ".join(facts))
    return "\n\n".join(p for p in parts if p)
