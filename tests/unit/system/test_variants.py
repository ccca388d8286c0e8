import pytest

from feedtherm.errors import DescriptionError
from feedtherm.system.load import load_system
from feedtherm.system.paths import get_path, split_path
from feedtherm.system.variants import with_condition, with_values


def test_split_path():
    assert split_path("joints[6].tcr") == ["joints", 6, "tcr"]
    assert split_path("sources.front_bearing.axial_load") == ["sources", "front_bearing", "axial_load"]


def test_with_values_changes_only_the_value_and_the_hash():
    paper = load_system("paper")
    variant = with_values(paper, {"sources.front_bearing.axial_load": 2000.0, "joints[6].tcr": 2e-4})
    assert get_path(variant.system, "sources.front_bearing.axial_load") == 2000.0
    assert variant.system.joints[6].tcr == 2e-4
    assert paper.system.sources["front_bearing"].axial_load == 3150.0  # the original is untouched
    assert variant.sha256 != paper.sha256
    assert variant.system.joints[5] is paper.system.joints[5]


def test_with_condition_adds_a_condition():
    variant = with_condition(load_system("paper"), "sweep", 1000.0, 900.0, 22.0)
    c = variant.system.conditions["sweep"]
    assert c.ambient == pytest.approx(295.15) and c.duration == 10800.0


def test_unknown_path_is_one_line():
    with pytest.raises(DescriptionError, match="sources.front_bearng.axial_load: no such value"):
        with_values(load_system("paper"), {"sources.front_bearng.axial_load": 1.0})
