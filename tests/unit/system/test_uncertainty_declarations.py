"""Declared uncertainties ([uncertainty.parameters]): one line per mistake, and the paper
bench's declarations load with every declared value inside its range."""

import math

import pytest

from feedtherm.analysis.uncertainty.declared import resolve_uncertainties
from feedtherm.benches import bench
from feedtherm.errors import DescriptionError, FeedthermError
from feedtherm.system.load import load_system
from feedtherm.system.paths import get_path
from feedtherm.system.variants import with_values

BENCH = bench("paper").description.read_text(encoding="utf-8")
FRICTION = '''[uncertainty.parameters.screw_nut_friction]
kind = "value"
paths = ["sources.screw_nut.friction_coefficient"]
distribution = "uniform"
range = [0.08, 0.15]
'''


def load_error(tmp_path, old: str, new: str) -> str:
    assert old in BENCH, f"test fixture out of date: {old!r} not in the bench file"
    path = tmp_path / "variant.toml"
    path.write_text(BENCH.replace(old, new, 1))
    with pytest.raises(DescriptionError) as info:
        load_system(str(path))
    message = str(info.value)
    assert "\n" not in message
    assert message.startswith(f"{path}: ")
    return message


@pytest.mark.parametrize("new, fragments", [
    (FRICTION.replace("range = [0.08, 0.15]", "range = [0.12, 0.15]"),
     ["uncertainty.parameters.screw_nut_friction.range", "excludes the declared value 0.1", "contradicts"]),
    (FRICTION.replace("range = [0.08, 0.15]", "range = [0.15, 0.08]"),
     ["uncertainty.parameters.screw_nut_friction.range", "lower bound must be below the upper"]),
    (FRICTION.replace("range = [0.08, 0.15]\n", ""),
     ["uncertainty.parameters.screw_nut_friction", "uniform distribution needs range"]),
    (FRICTION.replace('"uniform"', '"normal"').replace("range = [0.08, 0.15]\n", "sigma = -0.02\n"),
     ["uncertainty.parameters.screw_nut_friction.sigma", "must be positive"]),
    (FRICTION.replace('"uniform"', '"lognormal"'),
     ["uncertainty.parameters.screw_nut_friction", "lognormal distribution needs sigma"]),
    (FRICTION.replace("range = [0.08, 0.15]", "range = [0.08, 0.15]\nsigma = 0.01"),
     ["uncertainty.parameters.screw_nut_friction", "uniform distribution has no sigma"]),
    (FRICTION.replace('"uniform"', '"gamma"'),
     ["uncertainty.parameters.screw_nut_friction.distribution", "'uniform'"]),
    (FRICTION.replace("friction_coefficient", "model"),
     ["uncertainty.parameters.screw_nut_friction.paths", "does not name a number"]),
    (FRICTION.replace('["sources.screw_nut.friction_coefficient"]', '["joints[*].tcr"]').replace("[0.08, 0.15]", '["1e-4 m^2*K/W", "1e-2 m^2*K/W"]'),
     ["uncertainty.parameters.screw_nut_friction.paths", "different values", 'kind = "scale"']),
    (FRICTION.replace('"value"', '"scale"'),
     ["uncertainty.parameters.screw_nut_friction.range", "excludes the declared factor 1"]),
    (FRICTION.replace('range = [0.08, 0.15]', 'range = ["0.08 N", "0.15 N"]'),
     ["uncertainty.parameters.screw_nut_friction.range", "'0.08 N' is not a plain number"]),
    (FRICTION.replace('range = [0.08, 0.15]', 'range = [0.08, "0.15 blorps"]'),
     ["uncertainty.parameters.screw_nut_friction.range", "cannot read the unit"]),
    (FRICTION.replace('distribution', 'distribtion'),
     ["unknown key 'distribtion'", "did you mean 'distribution'"]),
])
def test_bad_declarations_are_one_line_naming_the_field(tmp_path, new, fragments):
    message = load_error(tmp_path, FRICTION, new)
    for fragment in fragments:
        assert fragment in message, message


def test_a_path_that_names_no_value_is_an_error_with_the_closest_path(tmp_path):
    # a typo, or a loss model swapped in the description that left the path behind (issue 35)
    message = load_error(tmp_path, FRICTION, FRICTION.replace("friction_coefficient", "friction_coeff"))
    assert message.endswith("uncertainty.parameters.screw_nut_friction.paths: 'sources.screw_nut.friction_coeff' "
                            "does not name a value of the description; did you mean "
                            "'sources.screw_nut.friction_coefficient'?")


def test_a_missing_reason_is_an_error(tmp_path):
    start = BENCH.index('reason = "Steel screw in a bronze nut')
    end = BENCH.index("\n", start) + 1
    message = load_error(tmp_path, BENCH[start:end], "")
    assert message.endswith("uncertainty.parameters.screw_nut_friction.reason: missing (required)")
    message = load_error(tmp_path, 'reason = "Steel screw in a bronze nut', 'reaso = "Steel screw in a bronze nut')
    assert "unknown key 'reaso'" in message and "did you mean 'reason'" in message


def test_an_empty_reason_is_an_error(tmp_path):
    start = BENCH.index('reason = "Steel screw in a bronze nut')
    end = BENCH.index("\n", start)
    message = load_error(tmp_path, BENCH[start:end], 'reason = "  "')
    assert message.split(": ", 1)[1].startswith("uncertainty.parameters.screw_nut_friction.reason: ")
    assert "needs a reason" in message


def test_the_paper_bench_declares_its_values_inside_their_ranges(paper):
    parameters = resolve_uncertainties(paper)
    assert len(parameters) >= 8
    for p in parameters:
        assert p.reason.strip(), p.name
        # every value has its provenance, but for the room's still air, the schema's default (left out)
        assert p.provenance != "undeclared" or p.paths == ("room.air_speed",), p.name
        assert p.distribution in ("uniform", "triangular", "normal", "lognormal")
        if p.kind == "scale":
            assert p.declared == 1.0
        else:  # a value parameter's declared value is every path's value
            assert all(math.isclose(float(get_path(paper.system, path)), p.declared) for path in p.paths)
        if p.low is not None:
            assert p.low <= p.declared <= p.high, p.name
        if p.sigma is not None:
            assert p.sigma > 0
    by_name = {p.name: p for p in parameters}
    # a quantity in the range is read in SI: 50 N to 365 N, and the unit is the value's
    assert (by_name["screw_nut_preload"].low, by_name["screw_nut_preload"].high) == (50.0, 365.0)
    assert by_name["screw_nut_preload"].unit == "N"
    assert by_name["room_air_speed"].high == pytest.approx(0.3) and by_name["room_air_speed"].unit == "m/s"


def test_a_system_without_declarations_is_one_line(paper):
    bare = with_values(paper, {"uncertainty": None})
    with pytest.raises(FeedthermError, match=r"declares no uncertainties; add \[uncertainty.parameters"):
        resolve_uncertainties(bare)
