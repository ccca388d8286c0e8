"""A source's heat_factor scales its heat alone, in both modes, and leaves the bench's hash alone."""

import pytest

from feedtherm.plan import boundary_of, with_mode
from feedtherm.system.load import load_system
from feedtherm.system.variants import with_values


@pytest.fixture(scope="module")
def paper():
    return load_system("paper")


@pytest.mark.parametrize("mode", ["physics", "paper"])
def test_heat_factor_scales_that_source_only(paper, mode):
    loaded = with_mode(paper, mode)
    base = boundary_of(loaded, "II")
    variant = with_values(loaded, {"sources.front_bearing.heat_factor": 1.2})
    scaled = boundary_of(variant, "II")
    assert scaled.heats["front_bearing"].power == pytest.approx(1.2 * base.heats["front_bearing"].power, rel=1e-12)
    for name, heat in base.heats.items():
        if name != "front_bearing":  # the motors' loads (torques) do not follow the factor
            assert scaled.heats[name].power == pytest.approx(heat.power, rel=1e-12)


def test_heat_factor_at_one_is_left_out_of_the_hash(paper):
    assert "heat_factor" not in paper.system.model_dump(mode="json")["sources"]["front_bearing"]
    assert with_values(paper, {"sources.front_bearing.heat_factor": 1.2}).sha256 != paper.sha256
