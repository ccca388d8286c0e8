"""The paper's printed values are the paper bench's overlay (system/overlay.py), applied by plan."""

import ast
from pathlib import Path

import pytest

from feedtherm.benches import bench
from feedtherm.errors import DescriptionError, FeedthermError
from feedtherm.plan import boundary_of, plan_run, with_mode
from feedtherm.system.load import load_system, parse_toml, read_text, validate_description
from feedtherm.system.overlay import OVERLAY, available_overlay, mode_of, read_overlay

SRC = Path(__file__).parents[3] / "src" / "feedtherm"


def test_the_paper_bench_supplies_its_tables_as_an_overlay(paper):
    overlay = available_overlay(paper)
    assert (overlay.name, overlay.reference_condition) == ("paper", "I")
    assert overlay.printed_heats()["front_bearing"] == pytest.approx(4.95)
    assert overlay.printed_chtcs()["worktable_bottom"] == pytest.approx(16.23)
    assert paper.overlay is None and mode_of(paper) == "physics"  # loaded, not applied


def test_with_mode_applies_it_once_and_every_run_takes_it(paper):
    in_paper_mode = with_mode(paper, "paper")
    assert mode_of(in_paper_mode) == "paper"
    plan = plan_run(in_paper_mode, condition="I", duration=60.0)
    assert plan.mode == "paper" and plan.segments[0].bc.overlay == "paper"
    assert plan.segments[0].bc.heats["front_bearing"].power == pytest.approx(4.95, rel=1e-12)
    assert boundary_of(paper, "I").heats["front_bearing"].power != pytest.approx(4.95, rel=1e-3)
    assert with_mode(in_paper_mode, "physics").overlay is None


def test_a_bench_without_an_overlay_refuses_it_in_one_line(ballscrew):
    with pytest.raises(FeedthermError, match=r"^--mode paper: bundled:ballscrew_example has no overlay"):
        with_mode(ballscrew, "paper")
    with pytest.raises(FeedthermError, match=r"^--mode: must be physics or paper .* got 'tables'$"):
        with_mode(load_system("paper"), "tables")


def test_a_description_file_names_its_overlay_in_meta(tmp_path, paper):
    text, origin = read_text("paper")
    data = parse_toml(text, origin)
    (tmp_path / "printed.toml").write_text(bench("paper").folder.joinpath(OVERLAY).read_text())
    data["meta"]["overlay"] = "printed.toml"  # beside the description
    path = tmp_path / "mine.toml"
    loaded = validate_description(data, str(path))
    assert available_overlay(loaded) == available_overlay(paper)
    data["meta"]["overlay"] = "bundled:paper"
    assert available_overlay(validate_description(data, str(path))) == available_overlay(paper)
    data["meta"]["overlay"] = ""
    assert available_overlay(validate_description(data, str(path))) is None  # a file is no bench


@pytest.mark.parametrize("edit, message", [
    (lambda t: t.replace('reference_condition = "I"', 'reference_condition = "VI"'),
     "reference_condition: no condition named 'VI'"),
    (lambda t: t.replace('source = "guideways"', 'source = "guideway"', 1),
     "heat[0].source: no heat source named 'guideway'; did you mean 'guideways'?"),
    (lambda t: t.replace('surfaces = ["screw_shaft"]', 'surfaces = ["screw"]'),
     "chtc[1].surfaces: no surface named 'screw'"),
    (lambda t: t.replace('value = "0.39 W"', 'value = "0.39 m"'), "heat[0].value"),
    (lambda t: t + "\n[[heat]]\nsource = 1\n", "heat[6].source"),
    (lambda t: t.replace("[[heat]]", "[[heats]]", 1), "heats"),
])
def test_a_bad_overlay_is_one_line_naming_the_file_and_field(tmp_path, paper, edit, message):
    path = tmp_path / OVERLAY
    path.write_text(edit(bench("paper").folder.joinpath(OVERLAY).read_text()))
    with pytest.raises(DescriptionError) as caught:
        read_overlay(path, paper.system)
    text = str(caught.value)
    assert "\n" not in text and text.startswith(str(path)) and message in text, text


def test_the_mode_argument_lives_in_plan_and_the_cli_only():
    """The mode becomes an overlay once, in plan.with_mode; everything else reads the LoadedSystem.

    The CLI's ``--mode`` and the Python API's ``ft.load(..., mode=)`` pass it there."""
    found = set()
    for path in SRC.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                arguments = node.args.posonlyargs + node.args.args + node.args.kwonlyargs
                if any(a.arg == "mode" for a in arguments):
                    found.add(path.relative_to(SRC).as_posix())
            if isinstance(node, ast.Call):  # mode=... passed on to anything but pydantic's dumps
                for keyword in node.keywords:
                    if keyword.arg == "mode" and not (isinstance(keyword.value, ast.Constant)
                                                      and keyword.value.value in ("json", "python", "wrap",
                                                                                  "after", "before", "plain")):
                        found.add(path.relative_to(SRC).as_posix())
    assert found <= {"plan/__init__.py", "cli.py", "api.py"}, found
