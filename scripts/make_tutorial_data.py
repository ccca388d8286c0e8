"""Write the tutorial's SYNTHETIC drift-test log, docs/tutorials/my_axis_drift.csv (run once; committed).

The tutorial docs/tutorials/plot_02_your_machine.py starts a bench with ``feedtherm new my_axis``
and declares two drift tests on it; the log it then reads stands in for a real machine's.  It is
made here, as scripts/make_ballscrew_drift_tests.py makes the ballscrew bench's:

1. the machine: the template bench (``feedtherm new``) with the tutorial's declarations (its
   ``DECLARATIONS`` text, read from the script itself, so the two cannot drift apart), and two values
   changed (:data:`TRUTH`): the ball nut's drag torque +24 %, the support pair's preload +30 %;
2. the model: the FE model (coarse mesh, cycle-averaged motion), not the fast model the tutorial
   calibrates;
3. the starts, which the tutorial's tests declare as ``"measured"``: ``drift`` from a machine at
   the room's air, ``drift_fast`` 10 min after 40 min at 10 m/min;
4. the room's air, its noise, the sensors' noise, the interferometer's and a geometric error per
   target: as the ballscrew bench's (``make_ballscrew_drift_tests``).

Usage (from the repository root; a few minutes)::

    python scripts/make_tutorial_data.py
"""

from __future__ import annotations

import ast
import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))
import make_ballscrew_drift_tests as drift  # noqa: E402  (the log's layout, noise and geometric errors)

ROOT = Path(__file__).parents[1]
TUTORIAL = ROOT / "docs" / "tutorials" / "plot_02_your_machine.py"
TARGET = ROOT / "docs" / "tutorials" / "my_axis_drift.csv"
TRUTH = {"sources.ball_nut.torque": 0.36, "sources.front_bearing.axial_load": 2800.0}
TESTS = ("drift", "drift_fast")
SEED = 20261130
APPEND = "DECLARATIONS"


def appended_toml(script: str) -> str:
    """The text the tutorial appends to the description: its module-level string ``DECLARATIONS``."""
    for node in ast.parse(script).body:
        if (isinstance(node, ast.Assign) and [getattr(t, "id", None) for t in node.targets] == [APPEND]
                and isinstance(node.value, ast.Constant) and isinstance(node.value.value, str)):
            return node.value.value
    raise SystemExit(f"{TUTORIAL}: no module-level string {APPEND} = \"\"\"...\"\"\"")


def room_air(test: str, times: np.ndarray) -> np.ndarray:
    """The room's true air [°C]: a slow drift and a swing."""
    hours = times / 3600.0
    if test == "drift":
        return 19.8 + 0.3 * hours + 0.25 * np.sin(2 * np.pi * hours / 1.7)
    return 20.9 - 0.2 * hours + 0.2 * np.sin(2 * np.pi * (hours + 0.3) / 2.2)


def truth(folder: Path):
    """The tutorial's machine: the template with the tutorial's block, :data:`TRUTH` and the truth's starts."""
    from feedtherm.benches.template import new_bench
    from feedtherm.system.load import load_system
    from feedtherm.system.thermal_tests import Soak
    from feedtherm.system.variants import with_values

    bench = new_bench("my_axis", folder)
    description = bench / "description.toml"
    description.write_text(description.read_text() + "\n" + appended_toml(TUTORIAL.read_text()))
    machine = with_values(load_system(str(description)), TRUTH, origin_suffix="synthetic truth")
    system = machine.system
    warm = system.tests["drift"].model_copy(update={"cycle": None, "condition": "v10", "duration": 2400.0,
                                                   "start": "ambient", "room": "declared"})
    standing = system.duty_cycles["iso_duty"].model_copy(update={"repeat": 1, "measuring": None, "duration": 600.0,
                                                                "segments": [system.duty_cycles["iso_duty_fast"].segments[1]
                                                                             .model_copy(update={"start": 0.0})]})
    tests = dict(system.tests)
    tests["truth_warm"] = warm
    tests["truth_standing"] = tests["drift"].model_copy(update={"cycle": "truth_standing", "start": Soak(soaked="truth_warm"),
                                                                "room": "declared", "measurements": ""})
    tests["drift"] = tests["drift"].model_copy(update={"start": "ambient"})
    tests["drift_fast"] = tests["drift_fast"].model_copy(update={"start": Soak(soaked="truth_standing")})
    return with_values(machine, {"duty_cycles": {**system.duty_cycles, "truth_standing": standing}, "tests": tests},
                       origin_suffix="synthetic starts")


def log(model: str = "fem", mesh: str = "coarse") -> str:
    with tempfile.TemporaryDirectory() as folder:
        loaded = truth(Path(folder))
        header = ("# SYNTHETIC drift-test log of the tutorial's axis (docs/tutorials/plot_02_your_machine.py), not a measured "
                  "machine: written by\n# scripts/make_tutorial_data.py from the template bench with the tutorial's "
                  "tests and " + ", ".join(f"{k} = {v:g}" for k, v in TRUTH.items())
                  + f",\n# run with the {model} model ({mesh} mesh, cycle-averaged motion), a geometric error per "
                  f"target and seeded noise (seed {SEED}).\n")
        return header + drift.drift_test_log(loaded, TESTS, room_air, model, mesh, SEED)


def main(argv: list[str]) -> int:
    TARGET.parent.mkdir(parents=True, exist_ok=True)
    TARGET.write_text(log(argv[0] if argv else "fem"), encoding="utf-8")
    print(f"wrote {TARGET}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
