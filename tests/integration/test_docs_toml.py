"""Every ```toml block of the docs and the README is valid TOML (a reader copies them); a how-to
guide's blocks are parts of a description, each valid in the `feedtherm new` template."""

import re
import tomllib
from pathlib import Path

import pytest

from feedtherm.benches.template import PLACEHOLDER, TEMPLATE
from feedtherm.errors import DescriptionError
from feedtherm.system.load import validate_description

ROOT = Path(__file__).resolve().parents[2]
HOWTO = sorted((ROOT / "docs" / "howto").glob("*.md"))
PAGES = sorted((ROOT / "docs").glob("*.md")) + HOWTO + [ROOT / "README.md"]


def toml_blocks(pages: list[Path] = PAGES) -> list[tuple[str, str]]:
    blocks = []
    for page in pages:
        for index, block in enumerate(re.findall(r"```toml\n(.*?)```", page.read_text(encoding="utf-8"), flags=re.S)):
            blocks.append((f"{page.relative_to(ROOT)}#{index}", block))
    return blocks


def test_the_docs_have_toml_examples():
    assert len(toml_blocks()) >= 5


@pytest.mark.parametrize("where, block", toml_blocks(), ids=[where for where, _ in toml_blocks()])
def test_toml_block_parses(where, block):
    tomllib.loads(block)  # raises TOMLDecodeError, naming the line, on an invalid example


def test_a_multiline_inline_table_is_caught():
    # The test is not vacuous: the form the motor example once had is rejected.
    with pytest.raises(tomllib.TOMLDecodeError):
        tomllib.loads('losses = { model = "datasheet",\n  friction_torque = "11 mN*m" }\n')


def in_template(fragment: dict) -> dict:
    """The template's description with ``fragment`` pasted in: its arrays of tables (``[[provenance]]``)
    appended, its named entries (``[sources.front_bearing]``, ``[tests.drift]``) in place of the
    template's of the same name, a section the template lacks (``[calibration]``) added."""
    description = tomllib.loads((TEMPLATE / "description.toml").read_text(encoding="utf-8").replace(PLACEHOLDER, "my_axis"))
    for key, value in fragment.items():
        if isinstance(value, list) and isinstance(description.get(key), list):
            description[key] = description[key] + value
        elif isinstance(value, dict) and isinstance(description.get(key), dict):
            description[key] = {**description[key], **value}
        else:
            description[key] = value
    return description


def test_the_how_to_guides_have_description_snippets():
    assert len(HOWTO) >= 7 and len(toml_blocks(HOWTO)) >= 5


@pytest.mark.parametrize("where, block", toml_blocks(HOWTO), ids=[where for where, _ in toml_blocks(HOWTO)])
def test_a_how_to_snippet_is_valid_in_a_description(where, block):
    # the schema and the description's checks (names that exist, paths to numbers, values in range)
    validate_description(in_template(tomllib.loads(block)), where)


def test_a_snippet_that_names_nothing_is_caught():
    # The test is not vacuous: a calibration path with a typo is refused with the closest path.
    fragment = {"calibration": {"parameters": {"nut": {"kind": "value", "paths": ["sources.ball_nut.torqe"],
                                                       "bounds": ["0.1 N*m", "0.8 N*m"]}}}}
    with pytest.raises(DescriptionError, match="did you mean .sources.ball_nut.torque."):
        validate_description(in_template(fragment), "fragment")
