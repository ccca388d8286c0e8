"""`feedtherm new NAME` writes a bench folder that checks and runs as written, and refuses to
overwrite anything or to take a name a description could not carry."""

import json

import pytest

from feedtherm.benches import bench_names
from feedtherm.cli import main


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    parent = tmp_path_factory.mktemp("benches")
    assert main(["new", "my_mill", "--out", str(parent)]) == 0
    return parent / "my_mill"


def test_the_folder_holds_a_description_a_readme_and_sources(folder):
    assert sorted(p.name for p in folder.iterdir()) == ["README.md", "SOURCES.md", "description.toml"]
    text = (folder / "description.toml").read_text(encoding="utf-8")
    assert 'name = "my_mill"' in text and "__BENCH_NAME__" not in text
    assert "my_mill" in (folder / "README.md").read_text(encoding="utf-8")


def test_check_passes_without_a_warning_and_states_areas_and_costs(folder, capsys):
    assert main(["check", str(folder / "description.toml")]) == 0
    out = capsys.readouterr().out
    assert "no inconsistencies found" in out and "warning" not in out
    assert "joints[10] front_housing – base: 0.0055 m² of contact" in out  # 50 x 110 mm, derived
    assert "surfaces.table_bottom: 0.1005 m² exposed of 0.12 m² of faces" in out
    # v10: 1000 rpm x 10 mm = 10 m/min over a 400 mm stroke, a cycle of 2 x 0.4 m / (1/6 m/s) = 4.8 s,
    # far under 30 s: the averaged motion is advised
    assert "run cost of conditions.v10 (3.0 h simulated):" in out
    assert "--motion averaged: 1,080 steps" in out  # 10,800 s in 10 s steps
    assert "the reciprocation cycle (4.8 s) is under 30 s" in out
    assert "estimated times:" in out


def test_run_works_with_the_fast_model(folder, tmp_path, capsys):
    out = tmp_path / "run"
    assert main(["run", str(folder / "description.toml"), "--condition", "v10", "--duration", "900",
                 "--no-plots", "--out", str(out)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["single_drive"] is True and summary["declared_drive"] == "single"
    assert abs(summary["energy_balance_error"]) < 1e-6
    assert all(summary["final"][name] > 20.0 for name in ("T1", "T2", "T3", "T4", "T5"))


def one_line_refusal(capsys, *args) -> str:
    assert main(list(args)) == 2
    captured = capsys.readouterr()
    assert captured.out == "" and captured.err.count("\n") == 1 and "Traceback" not in captured.err
    return captured.err


def test_a_folder_that_is_not_empty_is_refused_and_left_alone(folder, capsys):
    before = {p.name: p.read_bytes() for p in folder.iterdir()}
    err = one_line_refusal(capsys, "new", "my_mill", "--out", str(folder.parent))
    assert "exists and is a folder that is not empty" in err
    assert {p.name: p.read_bytes() for p in folder.iterdir()} == before
    assert not [p for p in folder.parent.iterdir() if p.name.startswith(".")]  # no staging left behind


def test_a_file_in_the_way_is_refused(tmp_path, capsys):
    (tmp_path / "axis").write_text("mine")
    assert "exists and is a file" in one_line_refusal(capsys, "new", "axis", "--out", str(tmp_path))
    assert (tmp_path / "axis").read_text() == "mine"


@pytest.mark.parametrize("name", ["1axis", "my-mill", "my mill", "_hidden", "../up", ""])
def test_a_name_that_is_no_bench_name_is_refused(tmp_path, capsys, name):
    assert "is not a valid bench name" in one_line_refusal(capsys, "new", name, "--out", str(tmp_path))
    assert list(tmp_path.iterdir()) == []


def test_an_empty_folder_is_filled(tmp_path, capsys):
    (tmp_path / "axis").mkdir()
    assert main(["new", "axis", "--out", str(tmp_path)]) == 0
    assert (tmp_path / "axis" / "description.toml").is_file()


def test_the_template_is_not_a_bench():
    assert "_template" not in bench_names()


def test_heat_reports_the_derived_and_exposed_areas(folder, capsys):
    import math

    assert main(["heat", str(folder / "description.toml"), "--condition", "v10", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    # the table's underside less the nut housing and the four carriages (mm^2), not its whole face
    assert data["surface_area_m2"]["table_bottom"] == pytest.approx((400 * 300 - 80 * 100 - 4 * 60 * 48) * 1e-6)
    joints = {tuple(j["between"]): j for j in data["joints"]}
    ring = joints[("front_bearing", "front_housing")]  # pi 47 mm x 30 mm, the ring in its seat
    assert ring["area_m2"] == pytest.approx(math.pi * 47 * 30 * 1e-6, rel=1e-9)
    assert ring["conductance_W_per_K"] == pytest.approx(ring["area_m2"] / 1.25e-3)


def uncommented_calibration(text: str) -> str:
    """The description with its commented ``[calibration]`` block (up to the next section rule) uncommented."""
    start = text.index("# [calibration]\n")
    end = text.index("\n# ----", start)
    block = "\n".join(line[2:] if line.startswith("# ") else line.lstrip("#") for line in text[start:end].splitlines())
    return text[:start] + block + text[end:]


def test_the_commented_calibration_block_declares_parameters_that_resolve(folder, tmp_path, capsys):
    from feedtherm.analysis.calibration import resolve_parameters
    from feedtherm.system.load import load_system

    description = tmp_path / "description.toml"
    description.write_text(uncommented_calibration((folder / "description.toml").read_text(encoding="utf-8")))
    assert main(["check", str(description)]) == 0
    out = capsys.readouterr().out
    assert "no inconsistencies found" in out and "warning" not in out  # its provenance entry comes with it
    loaded = load_system(str(description))
    parameters = {p.name: p for p in resolve_parameters(loaded, list(loaded.system.calibration.parameters))}
    assert set(parameters) == {"nut_torque", "bearing_preload", "chtc_screw"}
    # each bound pair holds the template's own value (a value's, or a scale's factor 1): a fit can
    # start where the description is
    for p in parameters.values():
        starts = p.originals if p.kind == "value" else [1.0]
        assert all(p.lower <= start <= p.upper for start in starts), p
    assert parameters["chtc_screw"].originals == [1.0]  # the factor is declared 1 when not written
