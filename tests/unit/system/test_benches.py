"""Benches are folders found through one registry; other packages add theirs by entry point."""

from importlib import metadata

import pytest

from feedtherm import benches
from feedtherm.system.measurements import measurement_spec
from feedtherm.analysis.validation import measurements_of
from feedtherm.benches import GROUP, Bench, bench, bench_names
from feedtherm.cli import main
from feedtherm.errors import DescriptionError
from feedtherm.system.load import load_system

def _without_tests(text: str) -> str:
    """The description without its [tests], whose measurements are a file of the bench's own."""
    import tomlkit

    document = tomlkit.parse(text)
    del document["tests"]
    return tomlkit.dumps(document)


EXAMPLE = _without_tests(bench("ballscrew_example").description.read_text(encoding="utf-8"))
# Measured values made up for the test bench below: one per ballscrew_example sensor, and D.
MEASURED = "condition,quantity,unit,measured\nv10,T1,C,24.5\nv10,T3,C,31.0\nv10,D_um,um,18.0\n"


def one_line_error(call, *args) -> str:
    with pytest.raises(DescriptionError) as info:
        call(*args)
    message = str(info.value)
    assert "\n" not in message, message
    return message


def axis_folder(tmp_path, name="my_axis", measurements: str | None = MEASURED, meta_line: str = ""):
    """A bench folder of another package: the ball-screw example renamed, with its own data."""
    folder = tmp_path / name
    folder.mkdir()
    text = EXAMPLE.replace('name = "ballscrew_example"', f'name = "{name}"{meta_line}', 1)
    (folder / "description.toml").write_text(text, encoding="utf-8")
    if measurements is not None:
        (folder / "measurements.csv").write_text(measurements, encoding="utf-8")
    return folder


@pytest.fixture
def register(tmp_path, monkeypatch):
    """Install entry points of group feedtherm.benches; each names a real, importable object."""
    monkeypatch.syspath_prepend(str(tmp_path))
    real = metadata.entry_points
    added: list[metadata.EntryPoint] = []

    def entry_points(**params):
        if params.get("group") == GROUP:
            return metadata.EntryPoints(added)
        return real(**params)

    monkeypatch.setattr(metadata, "entry_points", entry_points)

    def add(name: str, value: str, module_source: str | None = None):
        if module_source is not None:
            module = value.split(":")[0]
            (tmp_path / f"{module}.py").write_text(module_source, encoding="utf-8")
        added.append(metadata.EntryPoint(name=name, value=value, group=GROUP))

    return add


def test_both_shipped_benches_are_listed_with_their_files():
    assert {"paper", "ballscrew_example"} <= set(bench_names())
    paper = bench("paper")
    assert paper.folder.name == "paper" and paper.provider == "feedtherm"
    assert paper.description == paper.folder / "description.toml"
    assert paper.measurements == paper.folder / "measurements.csv"
    assert paper.title == load_system("paper").system.meta.title
    example = bench("ballscrew_example")
    assert example.measurements == example.folder / "measurements.csv" and example.equilibrium_times is None
    assert [b.name for b in benches.benches()] == bench_names()


def test_paper_tables_are_read_from_the_bench_folder():
    # Table 5 as printed: condition I runs the screw at 396 rpm and the nut at 360 rpm
    row = bench("paper").table(5)[0]
    assert row["condition"] == "I" and float(row["screw_speed_rpm"]) == 396.0 and float(row["nut_speed_rpm"]) == 360.0
    assert "table 6" in one_line_error(bench("ballscrew_example").table, 6)


def test_a_mistyped_name_is_answered_with_the_closest_bench():
    message = one_line_error(load_system, "ballscrew")
    assert "no such file or bench" in message and "did you mean 'ballscrew_example'" in message
    assert "did you mean 'paper'" in one_line_error(bench, "papr")


def test_an_entry_point_adds_a_bench_that_loads_by_name(tmp_path, register):
    folder = axis_folder(tmp_path)
    register("my_axis", "my_axis_plugin:FOLDER", f"FOLDER = {str(folder)!r}\n")
    assert "my_axis" in bench_names()
    loaded = load_system("my_axis")
    assert loaded.origin == "bundled:my_axis" and loaded.system.meta.name == "my_axis"
    assert bench("my_axis").provider.startswith("entry point my_axis = my_axis_plugin:FOLDER")
    assert load_system("paper").origin == "bundled:paper"  # the shipped ones are still there


def test_an_entry_point_may_name_a_function_returning_a_bench(tmp_path, register):
    folder = axis_folder(tmp_path)
    register("my_axis", "my_axis_record:make", (
        "from feedtherm.benches import Bench\n"
        f"def make():\n    return Bench.from_folder('my_axis', {str(folder)!r}, provider='my package')\n"))
    assert bench("my_axis").provider == "my package"
    assert load_system("my_axis").system.meta.name == "my_axis"


def test_measurements_default_to_the_benchs_own_file(tmp_path, register):
    register("my_axis", "my_axis_data:FOLDER", f"FOLDER = {str(axis_folder(tmp_path))!r}\n")
    loaded = load_system("my_axis")
    assert loaded.system.meta.measurements == ""
    data = measurements_of(loaded, None)
    assert data.source == "bundled:my_axis"
    assert {(r.condition, r.quantity): r.measured for r in data.rows} == {
        ("v10", "T1"): 24.5, ("v10", "T3"): 31.0, ("v10", "D_um"): 18.0}


def test_a_relative_meta_measurements_is_read_in_the_bench_folder(tmp_path, register):
    folder = axis_folder(tmp_path, measurements=None, meta_line='\nmeasurements = "data/runs.csv"')
    (folder / "data").mkdir()
    (folder / "data" / "runs.csv").write_text(MEASURED, encoding="utf-8")
    register("my_axis", "my_axis_relative:FOLDER", f"FOLDER = {str(folder)!r}\n")
    assert measurements_of(load_system("my_axis"), None).source == str(folder / "data" / "runs.csv")


def test_measured_on_the_command_line_is_relative_to_the_working_directory(tmp_path, monkeypatch):
    (tmp_path / "descriptions").mkdir()
    description = tmp_path / "descriptions" / "axis.toml"
    description.write_text(EXAMPLE, encoding="utf-8")
    (tmp_path / "runs.csv").write_text(MEASURED, encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    data = measurements_of(load_system(str(description)), "runs.csv")
    assert data.source == "runs.csv" and len(data.rows) == 3


def test_a_bench_without_measurements_says_so_in_one_line(tmp_path, register, capsys):
    folder = axis_folder(tmp_path, measurements=None)
    register("my_axis", "my_bare_axis_plugin:FOLDER", f"FOLDER = {str(folder)!r}\n")  # a module of its own
    message = one_line_error(measurement_spec, None, "", "bundled:my_axis")
    assert "bench 'my_axis' has no measurements" in message and "--measured FILE" in message
    assert main(["validate", "my_axis"]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "has no measurements" in err


def test_an_entry_point_that_fails_to_load_is_named_in_one_line(register, capsys):
    register("broken_axis", "no_such_module_for_feedtherm:FOLDER")
    message = one_line_error(bench, "broken_axis")
    assert "entry point broken_axis = no_such_module_for_feedtherm:FOLDER" in message
    assert "ModuleNotFoundError" in message
    assert load_system("ballscrew_example").system.meta.name == "ballscrew_example"  # others still load
    assert main(["check", "broken_axis"]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err and "broken_axis" in err


@pytest.mark.parametrize(
    "name, value, source, fragment",
    [
        ("my_axis", "raises_inside:make", "def make():\n    raise RuntimeError('no licence\\nfor this bench')\n",
         "RuntimeError: no licence for this bench"),
        ("my_axis", "returns_number:make", "def make():\n    return 42\n", "returned an object of type int; expected a folder path"),
        ("my_axis", "empty_folder:FOLDER", "FOLDER = '/nonexistent/feedtherm/bench'\n", "no such file; a bench folder needs description.toml"),
        ("paper", "shadows_paper:FOLDER", "FOLDER = '/nonexistent'\n", "bench 'paper' is registered 2 times"),
    ],
)
def test_bad_entry_points_give_one_line_naming_them(register, name, value, source, fragment):
    register(name, value, source)
    message = one_line_error(bench, name)
    assert fragment in message, message
    assert name in message


def test_a_bench_record_must_carry_the_entry_points_name(tmp_path, register):
    folder = axis_folder(tmp_path)
    register("my_axis", "misnamed:make", (
        "from feedtherm.benches import Bench\n"
        f"def make():\n    return Bench.from_folder('other_axis', {str(folder)!r})\n"))
    assert "returned a bench named 'other_axis'" in one_line_error(bench, "my_axis")
    assert isinstance(bench("paper"), Bench)
