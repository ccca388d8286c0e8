"""Fixtures shared by the test layers."""

import pytest

from feedtherm.system.load import load_system


@pytest.fixture(scope="session")
def paper():
    """The paper's bench, loaded once for the whole session (descriptions are frozen)."""
    return load_system("paper")


@pytest.fixture(scope="session")
def ballscrew():
    """The bundled single-drive ball-screw axis."""
    return load_system("ballscrew_example")
