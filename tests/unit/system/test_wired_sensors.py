"""A contact sensor cannot ride on a part that turns: `check` says so (system/checks.py)."""

from feedtherm.system.checks import check_system, turning_parts
from feedtherm.system.load import parse_toml, read_text, validate_data


def _paper_with(edit):
    text, origin = read_text("paper")
    data = parse_toml(text, origin)
    edit(data)
    return validate_data(data, "bundled:paper (edited)").system


def _wired(system):
    return [f for f in check_system(system) if f.path.endswith(".method")]


def test_paper_bench_turns_its_screw_nut_and_belt_and_reads_none_by_wire(paper):
    assert turning_parts(paper.system) == {"screw", "nut", "belt"}
    assert _wired(paper.system) == []


def test_a_pt100_on_the_turning_nut_is_named_with_the_remedy():
    def on_nut(data):
        data["sensors"]["T3"].update(part="nut", position=["251 mm", "0 mm", "40 mm"])

    findings = _wired(_paper_with(on_nut))
    assert len(findings) == 1
    finding = findings[0]
    assert finding.path == "sensors.T3.method" and finding.severity == "warning"
    assert "'nut'" in finding.message and 'method = "infrared"' in finding.message


def test_an_infrared_reading_of_the_turning_nut_passes():
    def infrared_on_nut(data):
        data["sensors"]["T3"].update(part="nut", position=["251 mm", "0 mm", "40 mm"], method="infrared")

    assert _wired(_paper_with(infrared_on_nut)) == []


def test_a_nut_that_never_turns_may_carry_a_pt100():
    """A single drive's nut, or a dual drive whose nut speed is 0 in every run, does not turn."""
    def still_nut(data):
        data["sensors"]["T3"].update(part="nut", position=["251 mm", "0 mm", "40 mm"])
        for condition in data["conditions"].values():
            condition["nut_speed"] = "0 rpm"
        for cycle in data["duty_cycles"].values():
            for segment in cycle["segments"]:
                segment["nut_speed"] = "0 rpm"
        for condition in data["conditions"].values():
            condition.pop("feed_speed", None)

    system = _paper_with(still_nut)
    assert turning_parts(system) == {"screw"}  # the belt turns with the nut only
    assert _wired(system) == []
