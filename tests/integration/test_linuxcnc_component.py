"""`feedtherm export --to linuxcnc` (issue 58): the HAL component built with halcompile, loaded in
halrun on a simulated thread, fed a logged series through its pins, gives what `feedtherm correct`
gives; its fault pin holds the output on a failed sensor; the HAL file wires it into LinuxCNC's
motion module.

LinuxCNC comes from Debian's `linuxcnc-uspace` and `linuxcnc-uspace-dev` (`make setup-test`
installs them); where they cannot be had the module is skipped, and the C's own tests
(test_law_export_c.py) still run.  Every HAL session runs in this one module, one at a time: HAL's
shared memory is one per machine.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from controller_harness import halrun, install_component, linuxcnc_available, random_day_log, replay
from feedtherm.analysis.compensation.apply import correct, read_law
from feedtherm.analysis.compensation.pairs import union_times, values_at
from feedtherm.cli import main
from feedtherm.constants import KELVIN_OFFSET
from feedtherm.system.measurements import read_measurements
from law_documents import POSITIONS, every_document

pytestmark = pytest.mark.skipif(not linuxcnc_available(),
                                reason="LinuxCNC (Debian linuxcnc-uspace, linuxcnc-uspace-dev) is not installed, or "
                                       "its module folder is not writable (halcompile --install needs it)")

DOCUMENTS = every_document()
BENCH_LOG = Path(__file__).resolve().parents[2] / "src" / "feedtherm" / "benches" / "ballscrew_example" / "drift_tests.csv"
AGREEMENT_UM = 1e-6
KINDS = ("law", "law_static", "law_adapted", "law_stroke")


@pytest.fixture(scope="module")
def components(tmp_path_factory):
    """Each kind exported and installed once (a module name unique to this run), removed afterwards."""
    folder = tmp_path_factory.mktemp("hal")
    built, installed = {}, []
    for kind in KINDS:
        law = folder / f"{kind}.json"
        law.write_text(json.dumps(DOCUMENTS[kind]))
        name = f"ft_test_{kind}_{abs(hash(str(folder))) % 10**6}"
        out = folder / kind
        assert main(["export", str(law), "--to", "linuxcnc", "--name", name, "--out", str(out),
                     "--valid-range", "0 degC,60 degC"]) == 0
        installed.append(install_component(out, name))
        built[kind] = (law, out, name)
    yield built
    for module in installed:
        module.unlink(missing_ok=True)


def _log_in_celsius(law, condition: str):
    """The law's inputs on the union of their sample times in °C, as correct reads them before it adds 273.15."""
    data = read_measurements(str(BENCH_LOG))
    rows = {r.quantity: r for r in data.for_condition(condition)}
    times = union_times([rows[n] for n in law.inputs])
    return times, np.column_stack([values_at(rows[n], times) for n in law.inputs])


@pytest.mark.parametrize("kind", KINDS)
def test_the_component_gives_what_correct_gives_on_the_bench_log(components, kind):
    law_file, out, name = components[kind]
    law = read_law(law_file)
    x = float(POSITIONS[1])
    expected = {c.condition: c for c in correct(law, str(BENCH_LOG), (x,) if law.stroke else ())}
    times, celsius = _log_in_celsius(law, "drift")
    c = expected["drift"]
    np.testing.assert_array_equal(times, c.times)
    np.testing.assert_array_equal(celsius + KELVIN_OFFSET, np.column_stack([c.readings[n] for n in law.inputs]))
    pins = ["law-um", "output-um", "fault:bit"] + (["sd-um"] if kind == "law_adapted" else [])
    # machine position 0 is the law's x_min: the position pin in mm puts the table at x
    position = (x - law.x_min) * 1e3 if law.stroke else None
    rows = replay(out, name, times, celsius, pins, position=position)
    np.testing.assert_allclose(rows[:, 0], c.predicted[:, 0] * 1e6, rtol=0, atol=AGREEMENT_UM)
    if kind == "law_adapted":
        np.testing.assert_allclose(rows[:, 3], c.sd * 1e6, rtol=0, atol=AGREEMENT_UM)
    assert not rows[:, 2].any()


@pytest.mark.parametrize("kind", KINDS)
def test_the_component_gives_what_correct_gives_on_a_random_day(components, tmp_path, kind):
    law_file, out, name = components[kind]
    law = read_law(law_file)
    log = random_day_log(tmp_path / "day.csv")
    x = float(POSITIONS[3])
    (c,) = correct(law, str(log), (x,) if law.stroke else ())
    assert len(c.times) > 1000
    celsius = np.column_stack([c.readings[n] for n in law.inputs]) - KELVIN_OFFSET
    # the log's °C values, read back: (T - 273.15) + 273.15 is the reading correct used, to the bit here
    assert np.array_equal(celsius + KELVIN_OFFSET, np.column_stack([c.readings[n] for n in law.inputs]))
    position = (x - law.x_min) * 1e3 if law.stroke else None
    rows = replay(out, name, c.times, celsius, ["law-um"] + (["sd-um"] if kind == "law_adapted" else []),
                  position=position)
    np.testing.assert_allclose(rows[:, 0], c.predicted[:, 0] * 1e6, rtol=0, atol=AGREEMENT_UM)
    if kind == "law_adapted":
        np.testing.assert_allclose(rows[:, 1], c.sd * 1e6, rtol=0, atol=AGREEMENT_UM)


def test_a_failed_sensor_raises_the_fault_pin_and_holds_the_offset(components):
    law_file, out, name = components["law"]
    law = read_law(law_file)
    times, celsius = _log_in_celsius(law, "drift")
    celsius = celsius.copy()
    celsius[20:30, 1] = np.nan
    rows = replay(out, name, times, celsius, ["output-um", "offset", "fault:bit", "bad-input:s32", "counts:s32"])
    output, offset, fault, bad, counts = rows.T
    assert list(fault[20:30]) == [1] * 10 and not fault[:20].any() and not fault[30:].any()
    assert list(bad[20:30]) == [1] * 10
    np.testing.assert_array_equal(output[20:30], output[19])
    np.testing.assert_allclose(offset, -output * 1e-3, rtol=0, atol=1e-12)      # mm, minus the output
    np.testing.assert_array_equal(counts, np.floor(offset / 1e-6 + 0.5))        # counts of 1 nm


@pytest.mark.parametrize("kind", ["law", "law_stroke"])
def test_the_hal_file_wires_into_linuxcncs_motion_module(components, tmp_path, kind):
    """The generated .hal loads beside LinuxCNC's motion module: its pins and the axis's external-offset
    pins exist and their types match."""
    _, out, name = components[kind]
    hal = name.replace("_", "-")
    script = "\n".join(["loadrt trivkins coordinates=xyz", "loadrt tpmod", "loadrt homemod",
                        "loadrt motmod servo_period_nsec=1000000 num_joints=3",
                        f"source {out / f'{name}.hal'}", "show sig", ""])
    done = halrun(script, tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    assert f"{hal}.0.counts" in done.stdout and "axis.x.eoffset-counts" in done.stdout
    if kind == "law_stroke":
        assert "axis.x.pos-cmd" in done.stdout


def test_a_reversed_axis_maps_the_position_the_other_way_and_turns_the_offset(components):
    """With `reversed`, machine position p is x = x-at-zero-m - p / 1000 and the offset is +E in mm."""
    law_file, out, name = components["law_stroke"]
    law = read_law(law_file)
    x = float(POSITIONS[1])
    (c,) = [c for c in correct(law, str(BENCH_LOG), (x,)) if c.condition == "drift"]
    times, celsius = _log_in_celsius(law, "drift")
    hal = name.replace("_", "-")
    extra = f"setp {hal}.0.reversed 1\nsetp {hal}.0.x-at-zero-m {law.x_max!r}"
    rows = replay(out, name, times, celsius, ["law-um", "output-um", "offset"], position=(law.x_max - x) * 1e3,
                  extra=extra)
    np.testing.assert_allclose(rows[:, 0], c.predicted[:, 0] * 1e6, rtol=0, atol=AGREEMENT_UM)
    np.testing.assert_allclose(rows[:, 2], rows[:, 1] * 1e-3, rtol=0, atol=1e-12)
    assert np.abs(rows[:, 2]).max() > 1e-4
