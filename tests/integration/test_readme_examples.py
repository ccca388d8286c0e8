"""Every `$ feedtherm ...` line in the README's console blocks runs and exits 0."""

import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

README = Path(__file__).resolve().parents[2] / "README.md"


def readme_commands() -> list[str]:
    blocks = re.findall(r"```console\n(.*?)```", README.read_text(), flags=re.S)
    return [line[2:] for block in blocks for line in block.splitlines() if line.startswith("$ feedtherm")]


def test_readme_has_examples():
    assert len(readme_commands()) >= 3


@pytest.mark.parametrize("command", readme_commands())
def test_readme_example_runs(command):
    args = shlex.split(command)[1:]
    result = subprocess.run([sys.executable, "-m", "feedtherm", *args], capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr


def test_the_readme_is_a_landing_page_without_dates():
    """At most 900 words (as `wc -w` counts them) and no date: dated figures live in benchmarks/README.md."""
    text = README.read_text(encoding="utf-8")
    assert len(text.split()) <= 900
    assert not re.search(r"\b(19|20)\d\d-\d\d-\d\d\b", text)
