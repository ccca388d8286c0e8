"""The FE meshes of the verification session go to a cache of their own."""

import pytest


@pytest.fixture(scope="session", autouse=True)
def fem_cache(tmp_path_factory):
    """The FE meshes of this session in a cache of their own, not the user's."""
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("FEEDTHERM_CACHE", str(tmp_path_factory.mktemp("feedtherm-cache")))
        yield
