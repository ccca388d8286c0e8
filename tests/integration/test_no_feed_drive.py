"""A system without a feed drive: a description that leaves ``[kinematics]`` out.

A heated steel block on a cast-iron plate: nothing moves or turns.  ``check``, ``heat`` and
``run`` (fast and FE) take it; the files of a run leave out what only a screw has (its map, its
displacement, the positioning error); what a feed drive needs is refused in one line naming it
(a moving part, a turning source, a speed, a positioning reference; ``compensate`` and
``sweep``, which vary motor speeds).
"""

import json

import pytest

from feedtherm.cli import main
from feedtherm.system.load import load_system

BLOCK = """\
joints = [{ between = ["plate", "block"], tcr = "1e-4 m^2*K/W" }]

[meta]
name = "heated_block"
title = "A heated block on a plate, no feed drive"

[materials.steel]
density = "7850 kg/m^3"
conductivity = "45 W/(m*K)"
specific_heat = "460 J/(kg*K)"
expansion = "1.2e-5 1/K"
youngs_modulus = "200 GPa"
poisson_ratio = 0.3

[parts.plate]
material = "steel"
boxes = [{ origin = ["0 mm", "0 mm", "0 mm"], size = ["200 mm", "100 mm", "20 mm"] }]

[parts.block]
material = "steel"
boxes = [{ origin = ["50 mm", "20 mm", "20 mm"], size = ["100 mm", "60 mm", "40 mm"] }]

[sources.heater]
model = "fixed"
power = "20 W"
into = { block = 1.0 }

[surfaces.block_top]
part = "block"
faces = ["+z"]
convection = { kind = "natural", orientation = "horizontal_plate_up", length = "80 mm" }
emissivity = 0.3

[surfaces.plate_bottom]
part = "plate"
faces = ["-z"]
convection = { kind = "fixed", coefficient = "10 W/(m^2*K)" }
emissivity = 0

[sensors.block]
part = "block"
position = ["100 mm", "50 mm", "60 mm"]

[sensors.plate]
part = "plate"
position = ["10 mm", "50 mm", "20 mm"]

[[mechanics.supports]]
part = "plate"
point = ["0 mm", "0 mm", "0 mm"]
fix = ["x", "y", "z"]

[[mechanics.supports]]
part = "plate"
point = ["200 mm", "0 mm", "0 mm"]
fix = ["y", "z"]

[[mechanics.supports]]
part = "plate"
point = ["0 mm", "100 mm", "0 mm"]
fix = ["z"]

[mechanics.elongation]
target = { part = "plate", point = ["200 mm", "50 mm", "10 mm"] }
mount = "ground"
direction = [1, 0, 0]
description = "the plate's far end along x"

[temperatures]
reference = "20 degC"
convection_delta_t = "5 K"

[conditions.on]
ambient = "20 degC"
duration = "1800 s"

[[provenance]]
paths = ["meta", "materials", "parts", "joints", "sources", "surfaces", "sensors", "mechanics", "temperatures",
         "conditions"]
origin = "assumption"
source = "test case"
reason = "A made-up block on a plate, handbook steel values: what a system without a feed drive is."
"""

NO_DRIVE = "the system has no feed drive ([kinematics] is left out)"


@pytest.fixture
def block(tmp_path):
    path = tmp_path / "block.toml"
    path.write_text(BLOCK, encoding="utf-8")
    return path


def refusal(capsys, *args) -> str:
    """The one line ``main`` prints on standard error when it refuses ``args`` (exit 2)."""
    assert main([str(a) for a in args]) == 2
    captured = capsys.readouterr()
    assert captured.err.count("\n") == 1 and "Traceback" not in captured.err
    return captured.err


def test_the_description_loads_and_writes_back_without_kinematics(block):
    system = load_system(str(block)).system
    assert system.kinematics is None and system.mechanics.positioning is None
    assert all(c.screw_speed == 0.0 and c.nut_speed == 0.0 for c in system.conditions.values())
    dumped = system.model_dump(mode="json")
    assert "kinematics" not in dumped and "positioning" not in dumped["mechanics"]  # TOML has no null


def test_check_and_heat_take_it(block, capsys):
    assert main(["check", str(block)]) == 0
    assert "no inconsistencies found" in capsys.readouterr().out
    assert main(["heat", str(block), "--condition", "on"]) == 0
    assert "heater" in capsys.readouterr().out


@pytest.mark.parametrize("model", ["fast", "fem", "reduced"])
def test_a_run_writes_the_sensors_and_d_and_no_screw_files(block, tmp_path, model):
    out = tmp_path / model
    args = ["run", str(block), "--condition", "on", "--model", model, "--out", str(out)]
    assert main(args + (["--mesh", "coarse"] if model != "fast" else [])) == 0
    written = {p.name for p in out.iterdir()}
    assert {"sensors.csv", "summary.json", "sensors.png", "elongation.png"} <= written
    assert not written & {"screw.csv", "screw_displacement.csv", "positioning_error.csv", "screw_heatmap.png",
                          "positioning_error.png", "screw_deformation.png"}
    summary = json.loads((out / "summary.json").read_text())
    assert summary["declared_drive"] is None and summary["single_drive"] is False
    assert summary["positioning_error"]["max_abs_um"] is None
    assert abs(summary["energy_balance_error"]) < 1e-6
    # 20 W into the block: it is the warmest, and the plate grows along x
    assert summary["final"]["block"] > summary["final"]["plate"] > 20.0
    assert summary["final"]["D_um"] > 0.0


@pytest.mark.parametrize("edit, field", [
    (('[parts.block]\nmaterial = "steel"', '[parts.block]\nmaterial = "steel"\nmoving = true'), "parts.block.moving"),
    (('[conditions.on]\n', '[conditions.on]\nscrew_speed = "100 rpm"\n'), "conditions.on.screw_speed"),
    (('model = "fixed"\npower = "20 W"', 'model = "torque"\nshaft = "screw"\ntorque = "0.1 N*m"'),
     "sources.heater.model"),
    (('kind = "fixed", coefficient = "10 W/(m^2*K)"', 'kind = "rotating", shaft = "screw", diameter = "20 mm"'),
     "surfaces.plate_bottom.convection.kind"),
    (('[temperatures]', '[mechanics.positioning]\nreference = { part = "plate", point = ["0 mm", "0 mm", "0 mm"] }\n\n'
                        '[temperatures]'), "mechanics.positioning"),
])
def test_what_needs_a_feed_drive_is_refused_in_one_line(block, capsys, edit, field):
    old, new = edit
    text = block.read_text(encoding="utf-8")
    assert old in text
    block.write_text(text.replace(old, new, 1), encoding="utf-8")
    err = refusal(capsys, "check", block)
    assert field in err and "no feed drive" in err


def test_a_feed_drive_needs_its_positioning_reference(tmp_path, capsys):
    from feedtherm.benches import bench

    text = bench("ballscrew_example").description.read_text(encoding="utf-8")
    start = text.index("[mechanics.positioning]")
    end = text.index("\n[", start + 1)
    path = tmp_path / "description.toml"
    path.write_text(text[:start] + text[end + 1:], encoding="utf-8")
    err = refusal(capsys, "check", path)
    assert "mechanics.positioning: a feed drive needs the positioning error's reference point" in err


def test_with_a_feed_drive_a_forgotten_screw_speed_is_not_a_standstill(tmp_path, capsys):
    from feedtherm.benches import bench

    text = bench("ballscrew_example").description.read_text(encoding="utf-8")
    start = text.index("[conditions.v10]")
    line = text.index("screw_speed", start)
    path = tmp_path / "description.toml"
    path.write_text(text[:line] + text[text.index("\n", line) + 1:], encoding="utf-8")
    err = refusal(capsys, "check", path)
    assert "conditions.v10.screw_speed: missing (required with a feed drive" in err


@pytest.mark.parametrize("command", [["compensate", "--sensors", "block"],
                                     ["sweep", "--screw-rpm", "0", "--nut-rpm", "0", "--ambient", "20"]])
def test_commands_that_vary_motor_speeds_say_they_need_a_feed_drive(block, tmp_path, capsys, command):
    out = tmp_path / "out"
    err = refusal(capsys, command[0], block, *command[1:], "--out", out)
    assert f"feedtherm {command[0]} needs a feed drive" in err and "'heated_block' has none" in err
    assert not out.exists()
