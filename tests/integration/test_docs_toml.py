"""Every ```toml block of the docs and the README is valid TOML (a reader copies them)."""

import re
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PAGES = sorted((ROOT / "docs").glob("*.md")) + [ROOT / "README.md"]


def toml_blocks() -> list[tuple[str, str]]:
    blocks = []
    for page in PAGES:
        for index, block in enumerate(re.findall(r"```toml\n(.*?)```", page.read_text(encoding="utf-8"), flags=re.S)):
            blocks.append((f"{page.name}#{index}", block))
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
