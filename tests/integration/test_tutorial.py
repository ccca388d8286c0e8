"""The tutorial *Your machine in an afternoon* (docs/tutorials/plot_02_your_machine.py), run as the
documentation site runs it: block by block (its ``# %%`` cells), each from the script's own folder,
every ``feedtherm`` command in this process; then the figures its text states, checked on what the
commands wrote, and the script's folder as it was."""

import csv
import json
import os
import re
import shutil
from pathlib import Path

import numpy as np
import pytest

import feedtherm.cli

ROOT = Path(__file__).parents[2]
SCRIPT = ROOT / "docs" / "tutorials" / "plot_02_your_machine.py"


@pytest.fixture(scope="module")
def tutorial():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    done = []
    main = feedtherm.cli.main

    def recorded(argv):
        status = main(argv)
        done.append((argv, status))
        return status

    here = os.getcwd()
    before = sorted(p.name for p in SCRIPT.parent.iterdir())
    namespace = {"__name__": "__main__"}
    try:
        with pytest.MonkeyPatch.context() as patch:
            patch.setattr(feedtherm.cli, "main", recorded)
            for block in cells(SCRIPT.read_text(encoding="utf-8")):
                # sphinx-gallery runs every cell from the script's folder, whatever the one before did
                os.chdir(SCRIPT.parent)
                exec(compile(block, str(SCRIPT), "exec"), namespace)
    finally:
        os.chdir(here)
        plt.close("all")
    folder = namespace["work"]
    yield folder, done, before
    shutil.rmtree(folder, ignore_errors=True)


def cells(text: str) -> list[str]:
    """The script's ``# %%`` cells, each padded with blank lines to keep its line numbers."""
    lines = text.splitlines(keepends=True)
    starts = [0] + [i for i, line in enumerate(lines) if re.match(r"# %%", line)]
    ends = starts[1:] + [len(lines)]
    return ["\n" * start + "".join(lines[start:end]) for start, end in zip(starts, ends)]


def test_every_step_ran(tutorial):
    _, done, _ = tutorial
    assert [argv[0] for argv, _ in done] == ["new", "check", "check", "run", "validate", "calibrate", "compensate",
                                             "correct"]
    assert all(status == 0 for _, status in done)


def test_nothing_is_written_beside_the_script(tutorial):
    folder, _, before = tutorial
    assert not folder.is_relative_to(ROOT)
    assert sorted(p.name for p in SCRIPT.parent.iterdir()) == before
    assert (folder / "my_axis" / "description.toml").is_file() and (folder / "out").is_dir()


def test_the_test_is_run_as_declared(tutorial):
    folder, _, _ = tutorial
    summary = json.loads((folder / "out" / "my_axis_drift" / "summary.json").read_text())
    assert summary["steady"] is None and summary["profile"]["D_um"]["max"] > 0


def test_the_uncalibrated_model_falls_short_at_the_far_target(tutorial):
    folder, _, _ = tutorial
    with open(folder / "out" / "my_axis_validation" / "iso230_3.csv", newline="") as handle:
        rows = {(r["test"], r["quantity"]): r for r in csv.DictReader(handle) if r["figure"] == "largest drift"}
    far = rows[("drift", "E at 490 mm")]
    assert float(far["measured_um"]) - float(far["simulated_um"]) > 5.0  # 76 against 65 µm in the text


def test_the_held_out_drift_is_within_3_um_rms_at_every_target(tutorial):
    folder, _, _ = tutorial
    document = json.loads((folder / "out" / "my_axis_calibration" / "calibration.json").read_text())
    held = [s for s in document["series"]["held_out"] if s["condition"] == "drift" and s["quantity"].startswith("E@")]
    assert len(held) == 5
    assert max(s["rms_deviation"] for s in held) <= 3.0  # 2.2 µm in the text


def test_the_laws_read_zero_at_the_reference_and_are_judged_on_the_drift_tests(tutorial):
    from feedtherm.analysis.compensation.evaluator import CompensationLaw

    folder, _, _ = tutorial
    out = folder / "out" / "my_axis_compensation"
    for name in ("law.json", "law_static.json"):
        document = json.loads((out / name).read_text())
        law = CompensationLaw(document)
        assert abs(law.update(0.0, {n: document["reference"]["temperature_K"] for n in law.inputs})) <= 1e-6
        assert set(document["envelope"]["inputs"]) == set(law.inputs)
    summary = json.loads((out / "compensation.json").read_text())
    tests = {t["test"]: t for t in summary["drift_tests"]}
    assert set(tests) == {"drift", "drift_fast"}
    for test in tests.values():
        left = max(abs(v["largest_um"]) for v in test["residual"]["regression_lags"].values())
        before = max(abs(v["largest_um"]) for v in test["uncompensated"].values())
        assert left < 0.2 * before  # 8 µm against 77 and 99 µm in the text


def test_correct_flags_the_samples_outside_the_envelope(tutorial):
    folder, _, _ = tutorial
    with open(folder / "out" / "my_axis_correction" / "correction.csv", newline="") as handle:
        rows = list(csv.DictReader(handle))
    assert "outside_envelope" in rows[0]
    residual = np.array([float(r["residual_um"]) for r in rows if r["condition"] == "drift" and r["residual_um"]])
    assert np.sqrt(np.mean(residual ** 2)) < 10.0  # 5.8 µm in the text
