"""Fixtures shared by the test layers."""

import pytest

from feedtherm.system.load import LoadedSystem, load_system, parse_toml, read_text, validate_data

#: The paper bench's loss models before the catalogue ones replaced them (issue 12): the paper's
#: Eq. 14 (an efficiency) for the motors, Palmgren (Eqs. 15-22, corrected) for the bearings on a
#: fixed 100 mm²/s oil, a 500 N thread preload, coefficients frozen (the paper's assumption 3).
PAPER_EQUATION_MODELS = {
    "screw_motor": {"efficiency": 0.85},
    "nut_motor": {"efficiency": 0.85},
    "front_bearing": {"mean_diameter": "43.5 mm", "f0": 4.0, "lubricant_viscosity": "100 mm^2/s"},
    "rear_bearing": {"mean_diameter": "38.5 mm", "f0": 1.5, "lubricant_viscosity": "100 mm^2/s"},
    "nut_bearing": {"mean_diameter": "65 mm", "f0": 4.0, "lubricant_viscosity": "100 mm^2/s"},
    "screw_nut": {"preload": "500 N"},
}
# The paper's equations load the motors by a 500 N thread preload (1.75 N m at I, docs/paper-audit.md
# §5), more than the declared servos' continuous torque: the variant's motors are the paper's unnamed ones.
_REPLACED = ("losses", "friction_model", "bore_diameter", "outer_diameter", "series", "bearings_in_set", "lubricant",
             "continuous_torque")


def paper_with_equation_models() -> LoadedSystem:
    """The paper bench with :data:`PAPER_EQUATION_MODELS`: what hand calculations written for the
    paper's own equations are checked against."""
    text, origin = read_text("paper")
    data = parse_toml(text, origin)
    for name, values in PAPER_EQUATION_MODELS.items():
        source = data["sources"][name]
        for key in _REPLACED:
            source.pop(key, None)
        if source["model"] == "bearing":
            source.pop("friction_coefficient", None)  # a constant-friction bearing's; the thread keeps its own
        source.update(values)
    data["temperatures"]["coupling"] = "frozen"
    data["calibration"]["parameters"].pop("motor_copper")
    data["calibration"]["parameters"].pop("motor_no_load")
    data.get("uncertainty", {}).get("parameters", {}).pop("motor_copper", None)  # on the datasheet losses
    data["calibration"]["parameters"]["motor_efficiency"] = {
        "kind": "value", "paths": ["sources.screw_motor.efficiency", "sources.nut_motor.efficiency"],
        "bounds": [0.5, 0.98], "description": "efficiency of both servo motors at their operating point"}
    return validate_data(data, "bundled:paper (the paper's equation loss models)")


@pytest.fixture(scope="session")
def paper():
    """The paper's bench, loaded once for the whole session (descriptions are frozen)."""
    return load_system("paper")


@pytest.fixture(scope="session")
def paper_equations():
    """The paper's bench with the paper's own loss models (:func:`paper_with_equation_models`)."""
    return paper_with_equation_models()


@pytest.fixture(scope="session")
def ballscrew():
    """The bundled single-drive ball-screw axis."""
    return load_system("ballscrew_example")
