"""A small valid description to edit in the topology tests: a steel block on a plate, joined,
no feed drive (tests/integration/test_no_feed_drive.py's BLOCK, with a stated joint area so that
the block may be moved anywhere)."""

import tomllib

from feedtherm.system.load import validate_data

PLATE_BOX = '{ origin = ["0 mm", "0 mm", "0 mm"], size = ["200 mm", "100 mm", "20 mm"] }'
BLOCK_BOX = '{ origin = ["50 mm", "20 mm", "20 mm"], size = ["100 mm", "60 mm", "40 mm"] }'

BASE = """\
joints = [{ between = ["plate", "block"], tcr = "1e-4 m^2*K/W", area = "6000 mm^2" }]

[meta]
name = "block"
title = "A heated block on a plate"

[materials.steel]
density = "7850 kg/m^3"
conductivity = "45 W/(m*K)"
specific_heat = "460 J/(kg*K)"
expansion = "1.2e-5 1/K"
youngs_modulus = "200 GPa"
poisson_ratio = 0.3

[parts.plate]
material = "steel"
boxes = [PLATE_BOXES]

[parts.block]
material = "steel"
boxes = [BLOCK_BOXES]

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
reason = "made up"
"""


def text(plate: str = PLATE_BOX, block: str = BLOCK_BOX, *changes: tuple[str, str]) -> str:
    """The description with the plate's and the block's boxes (TOML inline tables, comma-separated)."""
    out = BASE.replace("PLATE_BOXES", plate).replace("BLOCK_BOXES", block)
    for old, new in changes:
        assert old in out, f"test fixture out of date: {old!r}"
        out = out.replace(old, new, 1)
    return out


def system(description: str):
    """The description validated against its schema (not yet checked)."""
    return validate_data(tomllib.loads(description), "test").system


def box(origin, size) -> str:
    """A box as a TOML inline table, from mm."""
    o = ", ".join(f'"{v:g} mm"' for v in origin)
    s = ", ".join(f'"{v:g} mm"' for v in size)
    return f"{{ origin = [{o}], size = [{s}] }}"
