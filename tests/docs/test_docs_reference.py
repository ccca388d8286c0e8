"""The site's generated reference (docs/_ext/feedtherm_reference/) holds every key of a
description and every option of every command.

What the reference must hold is enumerated here on its own, by a short walk of the pydantic
schema and of the argparse parser, not by the generator's functions; and the check that compares
the two is shown to catch a key or an option left out.
"""

from __future__ import annotations

import re
import sys
import typing
from pathlib import Path

import pytest
from reference_walk import parser_options, schema_keys, si_unit

from feedtherm.system.schema import FeedSystem

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "docs" / "_ext"))
import feedtherm_reference as reference  # noqa: E402


# --------------------------------------------------------------------------- the description's keys


def key_entries(rst: str) -> dict[str, str]:
    """The reference's entries: ``path`` as a definition term, and the text under it."""
    entries: dict[str, str] = {}
    # a term's next line is indented (a heading's is its underline)
    for match in re.finditer(r"^``([^`]+)``\n(   .*\n(?:   .*\n|\n)*)", rst, flags=re.M):
        entries[match.group(1)] = entries.get(match.group(1), "") + match.group(2)
    return entries


def missing_keys(expected, rst: str) -> list[str]:
    entries = key_entries(rst)
    return sorted(key for key in expected if key not in entries)


@pytest.fixture(scope="module")
def keys() -> dict[str, typing.Any]:
    return schema_keys(FeedSystem)


@pytest.fixture(scope="module")
def description_rst() -> str:
    return reference.description_rst()


def test_every_description_key_has_an_entry(keys, description_rst):
    assert len(keys) > 200  # the walk reaches the nested tables, the sources' and convections' kinds
    assert "sources.<name>.losses.torque_constant" in keys and "joints[].tcr" in keys
    assert missing_keys(keys, description_rst) == []


def test_the_reference_invents_no_key(keys, description_rst):
    assert sorted(set(key_entries(description_rst)) - set(keys)) == []


def test_a_key_left_out_is_caught(keys, description_rst):
    entry = "``joints[].tcr``\n"
    assert entry in description_rst
    assert missing_keys(keys, description_rst.replace(entry, "", 1)) == ["joints[].tcr"]


def test_every_quantity_states_its_unit_and_its_range(keys, description_rst):
    entries = key_entries(description_rst)
    quantities = {path: unit for path, annotation in keys.items() if (unit := si_unit(annotation)) is not None}
    assert len(quantities) > 80
    for path, unit in quantities.items():
        if unit.unit:
            assert f"``{unit.unit}``" in entries[path], path
        if unit.limit is not None:
            assert unit.limit.reason in " ".join(entries[path].split()), path


def test_every_key_states_its_default_or_that_it_is_required(keys, description_rst):
    entries = key_entries(description_rst)
    for path in keys:
        assert "default: " in entries[path], path
    assert "default: *required*" in entries["kinematics.lead"]
    assert "default: \\ ``10800 s``\\ " in entries["conditions.<name>.duration"]
    assert "default: \\ ``1``\\ " in entries["parts.<name>.mesh_refinement"]


def test_field_constraints_and_comments_reach_the_reference(description_rst):
    entries = {path: " ".join(text.split()) for path, text in key_entries(description_rst).items()}
    assert "≥ 0.25; ≤ 8" in entries["parts.<name>.mesh_refinement"]  # Field(ge=0.25, le=8.0)
    assert "> 1; ≤ 1e+06" in entries["mechanics.tie_penalty"]
    # the comments the schema documents its fields with: a block above, one at the line's end
    assert "The FE mesh puts this many times more elements across the part" in entries["parts.<name>.mesh_refinement"]
    assert "the contact travels with the table" in entries["joints[].sliding"]


# --------------------------------------------------------------------------- the command line


def documented_options(rst: str) -> dict[str, set[str]]:
    """Program -> the names its ``.. option::`` entries document."""
    documented: dict[str, set[str]] = {}
    program = None
    for line in rst.splitlines():
        if line.startswith(".. program:: "):
            program = line.removeprefix(".. program:: ").strip()
            documented.setdefault(program, set())
        elif line.startswith(".. option:: "):
            for invocation in line.removeprefix(".. option:: ").split(", "):
                documented[program].add(invocation.split()[0])
    return documented


def missing_options(expected: dict[str, set[str]], rst: str) -> list[str]:
    documented = documented_options(rst)
    return sorted(f"{program} {name}" for program, names in expected.items()
                  for name in names if name not in documented.get(program, set()))


@pytest.fixture(scope="module")
def cli_rst() -> str:
    return reference.cli_rst()


def test_every_command_and_option_has_an_entry(cli_rst):
    expected = parser_options()
    assert len(expected) == 17 and sum(map(len, expected.values())) > 100
    assert "--factor-memory" in expected["feedtherm run"] and "LAW.json" in expected["feedtherm export"]
    assert missing_options(expected, cli_rst) == []
    commands = [p for p, names in expected.items() if names]
    assert sorted(documented_options(cli_rst)) == sorted(commands)
    for program in expected:  # a section per command, those without options too
        assert f"``{program}``\n" in cli_rst


def test_an_option_left_out_is_caught(cli_rst):
    entry = ".. option:: --factor-memory GB\n"
    assert entry in cli_rst
    assert missing_options(parser_options(), cli_rst.replace(entry, "", 1)) == ["feedtherm run --factor-memory"]


def test_options_state_their_help_default_and_choices(cli_rst):
    body = cli_rst.split(".. option:: --mesh {coarse,medium,fine}", 1)[1].split(".. option::", 1)[0]
    assert "FE mesh density (with \\ ``--model``\\  fem)" in body
    assert "Choices: \\ ``coarse``\\ , \\ ``medium``\\ , \\ ``fine``\\ ." in body
    assert "Default: \\ ``coarse``\\ ." in body
    body = cli_rst.split(".. option:: --workers N", 1)[1].split(".. option::", 1)[0]
    assert "Not with \\ ``--scheduler``\\ ." in body
    required = cli_rst.split(".. program:: feedtherm calibrate", 1)[1].split(".. option:: --fit", 1)[1]
    assert required.split(".. option::", 1)[0].count("Required.") == 1


# --------------------------------------------------------------------------- the Python API


def test_every_public_name_is_documented():
    import feedtherm

    text = reference.api_rst()
    names = [name for name in feedtherm.__all__ if name != "__version__"]
    for name in names:
        target = "feedtherm.simulate.simulate" if name == "simulate" else f"feedtherm.{name}"
        assert re.search(rf"^\.\. auto(function|class|exception):: {re.escape(target)}$", text, flags=re.M), name


# --------------------------------------------------------------------------- text written as reStructuredText


@pytest.mark.parametrize(("text", "rst"), [
    ("law*.json of `feedtherm compensate`", "law\\*.json of \\ ``feedtherm compensate``\\ "),
    ("with --model fem", "with \\ ``--model``\\  fem"),
    ("a non-negative |value|, time_s", "a non-negative \\|value\\|, time\\_s"),
    ("``[mechanics] positioning``", "\\ ``[mechanics] positioning``\\ "),
])
def test_plain_text_reads_the_same_in_rst(text, rst):
    assert reference.rst_text(text) == rst
