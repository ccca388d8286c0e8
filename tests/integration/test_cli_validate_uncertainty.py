"""`feedtherm validate --uncertainty DIR`: a folder of `feedtherm uncertainty` becomes the report's section;
a bad folder is one line, exit 2, before any run."""

from __future__ import annotations

import subprocess
import sys

import pytest

from feedtherm.benches import bench
from feedtherm.outputs.uncertainty_files import write_uncertainty

# The synthetic study lives in tests/ (pytest puts the directory of tests/conftest.py on sys.path).
from uncertainty_study import make_study


def validate(tmp_path, *args):
    return subprocess.run([sys.executable, "-m", "feedtherm", "validate", *args], capture_output=True, text=True,
                          timeout=600, cwd=tmp_path)


def test_the_study_becomes_the_reports_last_section(tmp_path):
    write_uncertainty(make_study(), tmp_path / "unc")
    # Condition I alone keeps the run short; the section shows the study's own 30 values.
    lines = bench("paper").measurements.read_text(encoding="utf-8").splitlines()
    (tmp_path / "I.csv").write_text("\n".join([lines[0]] + [line for line in lines if line.startswith("I,")]) + "\n")
    result = validate(tmp_path, "--measured", "I.csv", "--uncertainty", "unc", "--out", "report")
    assert result.returncode == 0, result.stderr
    assert "measured values inside the 5–95 % band: prior 15 of 30, calibrated 5 of 30" in result.stdout
    html = (tmp_path / "report" / "report.html").read_text(encoding="utf-8")
    assert html.index('id="uncertainty"') > html.index('id="assumptions"')
    section = html[html.index('id="uncertainty"'):]
    assert "15 of 30 measured values lie inside the prior 5–95 % band" in section
    assert "recalled &lt;screw_nut_preload&gt; from a catalogue" in section
    assert section.count("data:image/png;base64") == 3


@pytest.mark.parametrize("content, fragment", [
    (None, "uncertainty.json not found (give the output folder of `feedtherm uncertainty`)"),
    ("{not json", "is not readable JSON"),
    ('{"settings": {}, "parameters": [], "sets": 3}', "sets is not a list of sets; is it an uncertainty.json?"),
])
def test_a_bad_folder_is_one_line_and_nothing_is_written(tmp_path, content, fragment):
    folder = tmp_path / "unc"
    folder.mkdir()
    if content is not None:
        (folder / "uncertainty.json").write_text(content)
    result = validate(tmp_path, "--uncertainty", "unc", "--out", "report")
    assert result.returncode == 2 and result.stdout == ""
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("feedtherm: error: --uncertainty: ") and fragment in lines[0], \
        result.stderr
    assert not (tmp_path / "report").exists()
