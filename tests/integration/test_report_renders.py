"""The validation report of real runs, rendered by headless Chromium.

The Validation is built here from short runs of the fast model (30 min, cycle-averaged
motion) and the paper's Tables 6–7, with a few made-up sensitivities, so that the report is
tested without `feedtherm.analysis.validation`.  Chromium is the Debian package `chromium`,
which `make test` installs (target `setup-test`).
"""

from __future__ import annotations

import base64
import io
import re
import struct
import subprocess
from pathlib import Path

import pytest

from feedtherm.analysis.validation import operating_points, report_notes, sensor_locations
from feedtherm.analysis.validation_types import Comparison, Sensitivity, Validation
from feedtherm.benches import bench
from feedtherm.boundary import boundary_conditions
from feedtherm.outputs.report import write_report
from feedtherm.simulate import simulate
from feedtherm.system.load import load_system

CHROMIUM = "/usr/bin/chromium"
CONDITIONS = ("I", "II", "III", "IV", "V")
# The Validation below holds no inferred heats and no consistency check: a section appears only with its
# content, so neither of theirs (`feedtherm validate` computes both: its report has them between the heat
# budget and the sensitivity ranking).
SECTION_IDS = ["headline", "deviations", "displacement", "sensor-curves", "screw-field", "equilibrium", "trends",
               "dual-single", "heat-budget", "sensitivity", "inconsistencies", "calibrated", "assumptions"]
# the positioning error, 5 sensor-curve figures, the screw field, trends, dual/single, heat budget,
# sensitivity ranking.
EXPECTED_IMAGES = len(CONDITIONS) + 6
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync"]


@pytest.fixture(scope="module")
def validation() -> Validation:
    loaded = load_system("paper")
    runs = {c: simulate(loaded, condition=c, duration=1800.0, motion="averaged") for c in CONDITIONS}
    single = {c: simulate(loaded, condition=c, duration=1800.0, motion="averaged", single_drive=True)
              for c in CONDITIONS}
    comparisons = [Comparison(r["condition"], r["point"], "C", runs[r["condition"]].summary_values()[r["point"]],
                              float(r["measured_C"]), float(r["paper_simulated_C"])) for r in bench("paper").table(6)]
    comparisons += [Comparison(r["condition"], "D_um", "um", runs[r["condition"]].summary_values()["D_um"],
                               float(r["measured_um"]), float(r["paper_simulated_um"])) for r in bench("paper").table(7)]
    budget = {c: {name: h.power for name, h in boundary_conditions(loaded.system, c).heats.items()}
              for c in CONDITIONS}
    sensitivities = [Sensitivity(f"sources.front_bearing.preload_{i}", "bearing catalogues", 1.0 + 0.1 * (i % 3),
                                 {"T1": 0.3 * i, "T2": -0.1 * i, "T3": 0.05, "T4": 0.02 * i, "T5": 0.01, "D_um": 0.4 * i})
                     for i in range(18)]
    provenance = dict(runs["I"].info["provenance"])
    assumptions = provenance.pop("assumptions")
    return Validation(
        system_name="paper_bench", model="fast", comparisons=comparisons, solutions=runs,
        single_drive=single, heat_budget=budget,
        measured_equilibrium_min={"I": 120.0, "II": 100.0, "III": 90.0, "IV": 70.0, "V": 110.0},
        sensitivities=sensitivities, sensitivity_condition="I",
        inconsistencies=["Table 1: total heat 18.58 W < what the measured T3 needs", "Table 5 row I: lead 5 mm"],
        assumptions=assumptions, provenance=provenance, measurement_source="the paper's Tables 6 and 7",
        wall_time_s=1.5, operating_points=operating_points(loaded), sensor_locations=sensor_locations(loaded),
        notes=report_notes(loaded),
    )


@pytest.fixture(scope="module")
def report(validation, tmp_path_factory) -> Path:
    return write_report(validation, tmp_path_factory.mktemp("report"))


def chromium(url: str, profile: Path, *extra: str) -> subprocess.CompletedProcess:
    if not Path(CHROMIUM).exists():
        pytest.fail(f"{CHROMIUM} is missing: the report test needs headless Chromium; `make test` installs it "
                    "(target setup-test: apt-get install chromium)")
    return subprocess.run([CHROMIUM, *FLAGS, f"--user-data-dir={profile}", *extra, url],
                          capture_output=True, text=True, timeout=180)


def console_problems(stderr: str) -> list[str]:
    """Lines in which the page wrote to the console or threw: a page without scripts has none."""
    return [line for line in stderr.splitlines() if "Uncaught" in line or ":CONSOLE" in line]


#: Sections whose tables hold no model's values: the measurements' own check, the description's values.
NO_MODEL_SECTIONS = {"consistency", "inconsistencies", "calibrated", "assumptions"}
#: The paper bench's report (3 h runs of five conditions, every section) measures 0.63 MB; a megabyte is the bound.
MAX_REPORT_BYTES = 1_000_000


def unlabelled_tables(html: str) -> list[tuple[str, str]]:
    """(section, table tag) of every table of model values that does not say which model it shows."""
    found = []
    for anchor, body in re.findall(r'<section id="([^"]+)">(.*?)</section>', html, re.S):
        if anchor in NO_MODEL_SECTIONS:
            continue
        for tag, caption in re.findall(r'(<table\b[^>]*>)(<caption>.*?</caption>)?', body, re.S):
            model = re.search(r'data-model="([^"]+)"', tag)
            if model is None or f'<span class="model">{model.group(1)}</span>' not in caption:
                found.append((anchor, tag))
    return found


def test_the_report_is_one_self_contained_file(report):
    text = report.read_text(encoding="utf-8")
    assert report.name == "report.html"
    assert not re.search(r"(src|href)\s*=\s*[\"']?(https?:|//|file:)", text), "external resource"
    assert "<script" not in text and "<link" not in text
    assert text.count('src="data:image/png;base64,') == EXPECTED_IMAGES


def test_the_report_is_under_a_megabyte_with_every_figure_a_palette_png(report):
    from PIL import Image

    assert report.stat().st_size < MAX_REPORT_BYTES
    for data in re.findall(r'src="data:image/png;base64,([^"]+)"', report.read_text(encoding="utf-8")):
        with Image.open(io.BytesIO(base64.b64decode(data))) as image:
            assert image.mode == "P" and image.size[0] == 1080  # 256 colours, full width


def test_every_table_says_which_model_it_shows(report):
    html = report.read_text(encoding="utf-8")
    assert unlabelled_tables(html) == []
    assert html.count('data-model="uncalibrated model"') >= 2 * len(CONDITIONS) + 5  # no calibration given
    assert 'data-model="calibrated model"' not in html


def test_chromium_renders_the_tables_and_every_image(report, tmp_path):
    run = chromium(report.as_uri(), tmp_path / "profile", "--enable-logging=stderr", "--v=0", "--dump-dom")
    assert run.returncode == 0, run.stderr[-2000:]
    dom = run.stdout
    images = re.findall(r"<img\b[^>]*>", dom)
    assert len(images) == EXPECTED_IMAGES
    assert all('src="data:image/png;base64,' in tag for tag in images)
    ids = re.findall(r'<section id="([^"]+)"', dom)
    assert ids == SECTION_IDS
    nav = dom[dom.index('<nav class="contents"'):dom.index("</nav>")]
    assert re.findall(r'<a href="#([^"]+)"', nav) == SECTION_IDS  # the contents: the sections present
    for condition in CONDITIONS:
        assert f'<caption>Condition {condition} <span class="model">uncalibrated model</span></caption>' in dom
    assert dom.count("<table") >= 2 * len(CONDITIONS) + 5  # deviations, dual/single, and the rest
    assert "T1 [°C]" in dom and "D [µm]" in dom and 'class="dev-' in dom
    assert "not reached in the run" in dom  # 30-min runs are too short for equilibrium
    assert console_problems(run.stderr) == []


@pytest.mark.parametrize("width", [1400, 800])  # the sidebar, and the bar above the page on a narrow window
def test_the_contents_stay_in_view_when_the_page_scrolls(report, tmp_path, width):
    """A copy of the report with a probe script: scrolled halfway down, the contents are still at the top edge."""
    probe = ('<script>window.scrollTo(0, document.documentElement.scrollHeight / 2); '
             'const box = document.querySelector("nav.contents")'
             '.getBoundingClientRect(); document.body.dataset.probe = `${window.scrollY} ${box.top} ${box.height}`;'
             '</script></body>')
    page = tmp_path / "probe.html"
    page.write_text(report.read_text(encoding="utf-8").replace("</body>", probe), encoding="utf-8")
    run = chromium(page.as_uri(), tmp_path / "profile", f"--window-size={width},1000", "--dump-dom")
    assert run.returncode == 0, run.stderr[-2000:]
    scrolled, top, height = (float(v) for v in re.search(r'data-probe="([^"]+)"', run.stdout).group(1).split())
    assert scrolled > 5000 and abs(top) < 1.0 and height > 100  # at the edge, to within a sub-pixel


def test_the_console_check_sees_a_script_error(tmp_path):
    """The check above is not vacuous: a page that throws shows up in the log."""
    page = tmp_path / "broken.html"
    page.write_text("<!DOCTYPE html><p>x</p><script>throw new Error('broken on purpose')</script>", encoding="utf-8")
    run = chromium(page.as_uri(), tmp_path / "profile", "--enable-logging=stderr", "--v=0", "--dump-dom")
    assert any("broken on purpose" in line for line in console_problems(run.stderr))


def test_chromium_screenshot_of_the_report(report, tmp_path):
    shot = tmp_path / "shot.png"
    run = chromium(report.as_uri(), tmp_path / "profile", f"--screenshot={shot}", "--window-size=1200,4000")
    assert run.returncode == 0, run.stderr[-2000:]
    assert shot.exists(), run.stderr[-2000:]
    data = shot.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    assert struct.unpack(">II", data[16:24]) == (1200, 4000)
    assert len(data) > 150_000  # text, tables and figures, not a blank page

    from PIL import Image

    with Image.open(shot) as image:
        colours = image.convert("RGB").resize((300, 1000)).getcolors(maxcolors=1_000_000)
    assert len(colours) > 500  # a blank or error page has a handful


def test_the_trend_prose_states_the_runs_own_slopes(validation, report):
    """The D-against-ambient sentence is the least-squares slope of these runs' final D over IV, II, V."""
    import numpy as np

    series = ["IV", "II", "V"]
    ambients = [validation.operating_points[c].ambient_c for c in series]
    slope = float(np.polyfit(ambients, [validation.solutions[c].summary_values()["D_um"] for c in series], 1)[0])
    html = report.read_text(encoding="utf-8")
    word = "rises" if slope > 0 else "falls"
    assert f"the model&#x27;s D {word} by {abs(slope):.2f} µm per kelvin" in html
    assert "α·L" not in html
