"""A compensation study's exported laws read 0 for a machine at the reference temperature, on sensors a
machine can carry (issue 56), checked on the files `compensate` writes: ballscrew_example's here, the
paper bench's on the study of tests/integration/test_cli_compensate.py (the same checks, imported)."""

import json
from pathlib import Path

import numpy as np
import pytest

from feedtherm.analysis.compensation.evaluator import CompensationLaw
from feedtherm.analysis.compensation.kalman import KalmanLaw
from feedtherm.cli import main
from feedtherm.system.load import load_system
from feedtherm.system.runs import visited_targets


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    out = tmp_path_factory.mktemp("ballscrew") / "compensation"
    assert main(["compensate", "ballscrew_example", "--cycles", "1", "--duration", "3600", "--sensors", "2",
                 "--out", str(out)]) == 0
    return "ballscrew_example", out


def test_the_default_choice_is_of_carriable_sensors(study):
    check_carriable(study[1])


def test_every_exported_law_reads_zero_at_the_reference(study):
    check_zero_at_reference(*study)


def check_carriable(out: Path) -> None:
    """Every sensor of every law of a study's folder is one a machine can carry."""
    summary = json.loads((out / "compensation.json").read_text())
    for kind, entry in [*summary["chosen"].items(), *((k, c) for k, curve in summary["curves"].items() for c in curve)]:
        for name in entry["sensors"]:
            assert "not_carriable" not in summary["candidates"][name], (kind, name, summary["candidates"][name])


def check_zero_at_reference(bench: str, out: Path) -> None:
    """Every law of a study's folder reads 0 (within 1e-6 m) with every input at the reference temperature."""
    system = load_system(bench).system
    reference = float(system.temperatures.reference)
    targets = sorted({x for test in system.tests for x in visited_targets(system, test)})
    for path in sorted(out.glob("law*.json")):
        document = json.loads(path.read_text())
        if document["kind"] == "kalman":
            estimator = KalmanLaw.from_document(document).estimator()
            readings = {s: reference for s in estimator.sensors} | {estimator.model.ambient: reference}
            for t in (0.0, 600.0, 3600.0):
                d, _ = estimator.update(t, readings, 0.0, 0.0)
                assert abs(d) <= 1e-6, (path.name, t, d)
            continue
        law = CompensationLaw(document)
        readings = {name: reference for name in law.inputs}
        if document["version"] == 2:  # a stroke law: E at every target (else across the stroke)
            xs = targets or list(np.linspace(law.x_min, law.x_max, 5))
            law.update(0.0, readings, xs[0])
            values = [law.at(x) for x in xs]
        else:
            values = [law.update(0.0, readings)]
        assert max(abs(v) for v in values) <= 1e-6, (path.name, values)
        assert document["reference"]["temperature_K"] == reference
