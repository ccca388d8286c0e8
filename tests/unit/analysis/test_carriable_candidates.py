"""Candidates a machine can carry (issue 56): no contact sensor on a turning part, no pyrometer on a
moving one, no spot that a part passes over as the table travels; a study chooses among the rest."""

import pytest

from feedtherm.analysis.candidates import candidate_sensors, carriable, covering_part, mount_problem
from feedtherm.system.load import load_system


@pytest.fixture(scope="module", params=["paper", "ballscrew_example"])
def bench(request):
    return load_system(request.param).system


def test_no_carriable_candidate_is_on_a_turning_part_by_wire_or_a_moving_part_by_pyrometer(bench):
    from feedtherm.system.checks import turning_parts

    turning = turning_parts(bench)
    candidates = candidate_sensors(bench)
    for name in carriable(candidates):
        c = candidates[name]
        if c.where == "ambient":
            continue
        assert not (c.kind == "contact" and c.part in turning), name
        assert not (c.kind == "infrared" and bench.parts[c.part].moving), name
        assert covering_part(bench, c.part, c.position) is None, name


def test_the_screw_under_the_nuts_travel_is_covered_and_beyond_it_is_not():
    system = load_system("ballscrew_example").system
    # the nut housing spans 260..340 mm at mid-stroke and travels +-200 mm: 60..540 mm of the screw;
    # the nut in its bore is what passes over the screw (a point in the housing's bore is not in the housing)
    assert covering_part(system, "screw", (0.150, 0.0, 0.0115)) == "nut"
    assert covering_part(system, "screw", (0.530, 0.0, 0.0115)) is not None
    assert covering_part(system, "screw", (0.560, 0.0, 0.0115)) is None
    # the declared infrared T4 at x = 150 mm is read where the nut passes: not carriable by default
    assert "path of" in candidate_sensors(system)["T4"].problem
    # a rail's side runs under the carriages' flanks; the bed's far end does not
    assert covering_part(system, "rails", (0.300, 0.1205, 0.026)) == "carriages"
    assert covering_part(system, "base", (0.600, -0.150, -0.071)) is None


def test_the_reasons_name_the_rule():
    system = load_system("paper").system
    assert "wires could not follow" in mount_problem(system, "screw", (0.2, 0.0, 0.0), "contact")
    moving = next(name for name, part in system.parts.items() if part.moving)
    assert "spot would travel" in mount_problem(system, moving, (0.0, 0.0, 0.0), "infrared")
    assert mount_problem(system, "", (0.0, 0.0, 0.0), "contact") == ""  # the air


def test_declared_and_default_requests(bench):
    from feedtherm.analysis.compensation.study import parse_sensors

    candidates = candidate_sensors(bench)
    own = tuple(n for n in bench.sensors)
    assert parse_sensors("declared", candidates) == own
    pool = carriable(candidates)
    assert parse_sensors(str(len(pool)), candidates) == len(pool)
    with pytest.raises(Exception, match="candidate positions a machine can carry"):
        parse_sensors(str(len(pool) + 1), candidates)
