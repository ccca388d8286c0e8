"""The public API at the top: ``import feedtherm as ft``; ft.load, ft.simulate, ft.calibrate,
ft.compensate, the types they return, their errors, and Solution.to_dataframe.

The code blocks of docs/python-api.md are run here as a reader would run them.  One short run of
condition I (10 min of the fast model) serves every table test; calibrate and compensate are
checked on the arguments they refuse before any run, which is where the wrappers do their work.
"""

import pickle
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import feedtherm as ft
from feedtherm.constants import KELVIN_OFFSET
from feedtherm.errors import cli_message

DOC = Path(__file__).resolve().parents[2] / "docs" / "python-api.md"
DURATION = 600.0  # [s] long enough for a few cycles of condition I, short enough for a unit test


@pytest.fixture(scope="module")
def run(paper):
    return ft.simulate(paper, condition="I", duration=DURATION)


def code_blocks(text: str) -> list[str]:
    return re.findall(r"```python\n(.*?)```", text, flags=re.S)


def test_the_page_s_examples_run(capsys):
    blocks = code_blocks(DOC.read_text(encoding="utf-8"))
    assert len(blocks) == 2
    for block in blocks:
        exec(compile(block, str(DOC), "exec"), {"__name__": "__doc_example__"})
    out = capsys.readouterr().out
    assert "T1 [degC]" in out and "D [um]" in out and "positioning error [um]" in out
    assert "energy balance:" in out
    assert "condition: no condition or test 'nope' in bundled:paper; conditions: I, II, III, IV, V" in out


def test_import_feedtherm_stays_cheap():
    """The API is imported on first use: ``import feedtherm`` reads no numerical package."""
    script = ("import sys, feedtherm\n"
              "heavy = sorted(m for m in ('numpy', 'scipy', 'pandas', 'pydantic', 'feedtherm.api', "
              "'feedtherm.simulate') if m in sys.modules)\n"
              "assert not heavy, heavy\n"
              "assert callable(feedtherm.simulate) and callable(feedtherm.load)\n"
              "assert 'pandas' not in sys.modules\n")
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr[-2000:]


def test_every_public_name_resolves_and_is_documented():
    assert {"load", "simulate", "calibrate", "compensate", "Solution", "LoadedSystem", "CalibrationResult",
            "StudyResult", "FeedthermError", "ArgumentError"} <= set(ft.__all__)
    for name in ft.__all__:
        value = getattr(ft, name)
        assert value is not None and name in dir(ft)
    for verb in (ft.load, ft.calibrate, ft.compensate):
        for section in ("Parameters", "Returns", "Raises"):
            assert f"{section}\n    ----" in verb.__doc__, (verb.__name__, section)
    simulate_doc = ft.simulate.simulate.__doc__
    for section in ("Parameters", "Returns", "Raises", "Examples"):
        assert f"{section}\n    ----" in simulate_doc, section
    with pytest.raises(AttributeError, match="no attribute 'nothing'"):
        ft.nothing  # noqa: B018


def test_ft_simulate_is_the_run_wherever_feedtherm_simulate_was_imported_first(paper):
    """The package's attribute is the submodule once imported (the import system sets it), so the
    verb is that module, callable; the module's own names stay where they were."""
    import feedtherm.simulate
    from feedtherm.simulate import execute, simulate

    assert ft.simulate is feedtherm.simulate and callable(ft.simulate)
    assert ft.simulate.simulate is simulate and ft.simulate.execute is execute
    with pytest.raises(ft.ArgumentError, match=r"^model: no model 'nope'"):
        ft.simulate(paper, condition="I", model="nope")


def test_a_bench_name_is_loaded_by_the_verb():
    assert isinstance(ft.load("paper"), ft.LoadedSystem)
    with pytest.raises(ft.ArgumentError, match=r"^system: a description from feedtherm.load\(\), a bench name"):
        ft.simulate(42, condition="I")
    with pytest.raises(ft.DescriptionError, match="nope"):
        ft.load("nope")


def test_to_dataframe_sensors_wide_and_long(run):
    wide = run.to_dataframe()
    names = [n for n in run.sensors if n != run.ambient_sensor] + [run.ambient_sensor]
    assert list(wide.columns) == ["time [s]", *(f"{n} [degC]" for n in names), "D [um]"]
    assert len(wide) == run.times.size and run.times[-1] == DURATION
    np.testing.assert_array_equal(wide["time [s]"], run.times)
    np.testing.assert_allclose(wide["T1 [degC]"], run.sensors["T1"] - KELVIN_OFFSET)
    np.testing.assert_allclose(wide["D [um]"], run.elongation * 1e6)
    pd.testing.assert_frame_equal(wide, run.to_dataframe("sensors", form="wide"))
    long = run.to_dataframe("sensors", form="long")
    assert list(long.columns) == ["time [s]", "sensor", "value", "unit"]
    assert len(long) == run.times.size * (len(names) + 1)
    back = long.pivot(index="time [s]", columns="sensor", values="value")
    np.testing.assert_allclose(back["T3"], wide["T3 [degC]"])
    assert set(long.loc[long["sensor"] == "D", "unit"]) == {"um"}
    assert set(long.loc[long["sensor"] == "T3", "unit"]) == {"degC"}


@pytest.mark.parametrize("kind, symbol, quantity, x, field, scale", [
    ("screw_temperature", "T", "temperature [degC]", "screw_x", "screw_temperature", None),
    ("screw_displacement", "u", "displacement [um]", "screw_x", "screw_displacement", 1e6),
    ("positioning_error", "E", "positioning error [um]", "table_x", "positioning_error", 1e6),
])
def test_to_dataframe_fields_along_x(run, kind, symbol, quantity, x, field, scale):
    positions, values = getattr(run, x), getattr(run, field)
    expected = values - KELVIN_OFFSET if scale is None else values * scale
    wide = run.to_dataframe(kind, form="wide")
    assert wide.columns[0] == "time [s]" and len(wide.columns) == positions.size + 1
    unit = quantity.split("[")[1].rstrip("]")
    assert wide.columns[1] == f"{symbol}(x={positions[0] * 1e3:.6g} mm) [{unit}]"
    np.testing.assert_allclose(wide.iloc[:, 1:].to_numpy(), expected)
    long = run.to_dataframe(kind, form="long")
    assert list(long.columns) == ["time [s]", "x [mm]", quantity]
    last = long[long["time [s]"] == run.times[-1]]
    np.testing.assert_allclose(last["x [mm]"], positions * 1e3)
    np.testing.assert_allclose(last[quantity], expected[-1])


def test_to_dataframe_parts(run):
    wide = run.to_dataframe("parts")
    assert list(wide.columns) == ["time [s]", *(f"{p} [degC]" for p in run.part_temperatures)]
    long = run.to_dataframe("parts", form="long")
    screw = long[long["part"] == "screw"]["temperature [degC]"].to_numpy()
    np.testing.assert_allclose(screw, run.part_temperatures["screw"] - KELVIN_OFFSET)


def test_to_dataframe_refuses_an_unknown_table_or_layout_by_name(run):
    with pytest.raises(ft.ArgumentError, match=r"^kind: no table 'screw'; tables: sensors, parts"):
        run.to_dataframe("screw")
    with pytest.raises(ValueError, match=r"^form: must be long or wide, got 'tall'"):
        run.to_dataframe("sensors", form="tall")


def test_the_unit_named_fields_are_the_si_fields_in_their_unit(run):
    assert run.time_s is run.times and run.sensors_K is run.sensors and run.elongation_m is run.elongation
    assert run.screw_x_m is run.screw_x and run.table_x_m is run.table_x and run.nut_offset_m is run.nut_offset
    assert run.screw_temperature_K is run.screw_temperature and run.part_temperatures_K is run.part_temperatures
    assert run.screw_displacement_m is run.screw_displacement and run.positioning_error_m is run.positioning_error
    assert run.equilibrium_time_s == run.equilibrium_time
    np.testing.assert_allclose(run.sensors_degC["T1"], run.sensors["T1"] - 273.15)
    np.testing.assert_allclose(run.screw_temperature_degC, run.screw_temperature - 273.15)
    np.testing.assert_allclose(run.screw_displacement_um, run.screw_displacement * 1e6)
    np.testing.assert_allclose(run.positioning_error_um, run.positioning_error * 1e6)
    np.testing.assert_allclose(run.part_temperatures_degC["base"], run.part_temperatures["base"] - 273.15)
    for name in ("time_s", "sensors_degC", "positioning_error_um", "equilibrium_time_s"):
        assert name in ft.Solution.__doc__, name


@pytest.mark.parametrize("kwargs, message", [
    ({"condition": "nope"}, "condition: no condition or test 'nope' in bundled:paper; conditions: I, II"),
    ({"test": "nope"}, "test: no condition or test 'nope' in bundled:paper"),
    ({"condition": "I", "test": "I"}, "test: condition and test name the same thing"),
    ({}, "condition: give exactly one of condition (a test or a condition), test and cycle"),
    ({"cycle": "nope.csv"}, "cycle: 'nope.csv' is neither a duty cycle of bundled:paper"),
    ({"condition": "I", "duration": -1.0}, "duration: must be positive, got -1.0 s"),
    ({"condition": "I", "duration": 1e-9}, "duration: 1e-09 s is shorter than one time step"),
    ({"condition": "I", "sample_interval": 0.0}, "sample_interval: must be positive, got 0.0 s"),
    ({"condition": "I", "motion": "fast"}, "motion: must be resolved, exact or averaged, got 'fast'"),
    ({"condition": "I", "model": "fsat"}, "model: no model 'fsat'; models: fast"),
])
def test_simulate_errors_name_the_argument_and_the_cli_names_the_option(paper, kwargs, message):
    with pytest.raises(ft.ArgumentError) as caught:
        ft.simulate(paper, **kwargs)
    error = caught.value
    assert isinstance(error, ValueError) and isinstance(error, ft.FeedthermError)
    assert str(error).startswith(message), str(error)
    assert error.argument == message.split(":")[0]
    option = "--" + error.argument.replace("_", "-")
    assert cli_message(error) == f"{option}: {error.detail}"
    again = pickle.loads(pickle.dumps(error))  # a batch's worker process sends it back whole
    assert str(again) == str(error) and again.argument == error.argument


def test_the_cli_keeps_its_one_line_form(capsys):
    from feedtherm.cli import main

    assert main(["run", "paper", "--condition", "nope"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("feedtherm: error: --condition: no condition or test 'nope'"), err


@pytest.mark.parametrize("kwargs, message", [
    ({"fit": ["I"], "params": ["screw_nut_frction"]},
     "params: unknown parameter 'screw_nut_frction'; did you mean 'screw_nut_friction'"),
    ({"fit": "I", "params": "sources.screw_nut.preload"}, "params: 'sources.screw_nut.preload' has no declared bounds"),
    ({"fit": "I,VI", "params": "screw_nut_preload"}, "fit: no measurements for VI"),
    ({"fit": ["I"], "params": []}, "params: name at least one parameter"),
    ({"fit": ["I"], "params": ["screw_nut_preload"], "model": "fsat"}, "model: no model 'fsat'"),
])
def test_calibrate_refuses_by_argument_before_any_run(paper, kwargs, message):
    with pytest.raises(ft.ArgumentError) as caught:
        ft.calibrate(paper, **kwargs)
    assert str(caught.value).startswith(message), str(caught.value)


@pytest.mark.parametrize("kwargs, message", [
    ({"sensors": "T9"}, "sensors: no candidate sensor 'T9'"),
    ({"sensors": ["T1", "T1"]}, "sensors: a sensor is listed twice in 'T1,T1'"),
    ({"sensors": 0}, "sensors: K must be at least 1, got 0"),
    ({"sensors": True}, "sensors: a count, 'declared' or sensor names, got True"),
    ({"cycles": 0}, "cycles: 0 is not a positive integer"),
    ({"seed": 1.5}, "seed: 1.5 is not an integer"),
    ({"duration": 0.0}, "duration: must be positive, got 0.0 s"),
    ({"model": "fsat"}, "model: no model 'fsat'"),
])
def test_compensate_refuses_by_argument_before_any_run(paper, kwargs, message):
    with pytest.raises(ft.ArgumentError) as caught:
        ft.compensate(paper, **kwargs)
    assert str(caught.value).startswith(message), str(caught.value)
