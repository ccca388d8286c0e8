"""`feedtherm compensate` as a user runs it: a small study, its files, and bad input (issue 16)."""

import json
import subprocess
import sys

import numpy as np
import pytest

from feedtherm.analysis.compensation.evaluator import CompensationLaw

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def run(cwd, *args):
    return subprocess.run([sys.executable, "-m", "feedtherm", "compensate", *args], capture_output=True, text=True,
                          timeout=300, cwd=cwd)


#: D [µm] of the made-up measurements the study is adapted to (one per condition).
ADAPT_D_UM = {"a": 12.0, "b": 25.0, "c": 31.0, "d": 47.0}


def adaptation_file(path):
    """Final values of every candidate (the sensors the study will choose are not known before it
    runs) and D, at four made-up conditions: a file in the format the measurement readers accept."""
    from feedtherm.analysis.candidates import candidate_sensors
    from feedtherm.system.load import load_system

    names = list(candidate_sensors(load_system("paper").system))
    rng = np.random.default_rng(11)
    lines = ["condition,quantity,unit,measured"]
    for i, (condition, d) in enumerate(ADAPT_D_UM.items()):
        lines += [f"{condition},{name},C,{20 + 4 * i + rng.uniform(0, 8):.2f}" for name in names]
        lines.append(f"{condition},D_um,um,{d}")
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    """One 1-hour cycle per set: the whole path, not the figures of docs/compensation.md; the laws
    adapted to a made-up measurement file (``--adapt``)."""
    cwd = tmp_path_factory.mktemp("compensate")
    adaptation_file(cwd / "measured.csv")
    return cwd, run(cwd, "--cycles", "1", "--duration", "3600", "--seed", "4", "--sensors", "2",
                    "--adapt", "measured.csv")


def test_two_workers_give_the_serial_study(study, tmp_path):
    """The cycles on a local Dask cluster: the same laws, to the byte."""
    cwd, serial = study
    assert serial.returncode == 0, serial.stderr
    parallel = run(tmp_path, "--cycles", "1", "--duration", "3600", "--seed", "4", "--sensors", "2", "--workers", "2")
    assert parallel.returncode == 0, parallel.stderr
    for name in ("law.json", "law_static.json", "compensation.csv"):
        assert (tmp_path / "out" / "paper_compensation_physics" / name).read_bytes() == \
            (cwd / "out" / "paper_compensation_physics" / name).read_bytes(), name
    assert not list((tmp_path / "out" / "paper_compensation_physics").glob("law_adapted*"))  # no --adapt, none


def test_a_study_writes_its_files_and_one_line(study):
    cwd, result = study
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    # the plan before any run (its runs, steps and an estimate), then the result
    assert len(lines) == 2 and lines[0].startswith("compensate: 7 runs (1 train, 1 validation, 1 test, 4 out-of-range), "), lines
    assert "min on 1 worker" in lines[0]
    assert lines[1].startswith("out/paper_compensation_physics: law on "), lines
    out = cwd / "out" / "paper_compensation_physics"
    assert sorted(p.name for p in out.iterdir()) == sorted(
        ["law.json", "law_static.json", "law_kalman.json", "law_adapted.json", "law_adapted_static.json",
         "law_stroke.json", "law_stroke_static.json", "compensation.json", "compensation.csv", "error_vs_k.png",
         "sensor_map.png", "test_cycle.png", "compensation.html"])
    for name in ("error_vs_k.png", "sensor_map.png", "test_cycle.png"):
        assert (out / name).read_bytes()[:8] == PNG_MAGIC
    summary = json.loads((out / "compensation.json").read_text())
    assert [len(e["sensors"]) for e in summary["curves"]["regression_lags"]] == [1, 2, 3, 4, 5, 6]
    assert summary["declared"]["regression"]["sensors"] == ["T1", "T2", "T3", "T4", "T5"]
    assert [m["condition"] for m in summary["measured"]["regression"]["conditions"]] == ["I", "II", "III", "IV", "V"]
    law = CompensationLaw.from_file(out / "law.json")
    assert len(law.inputs) == 2 and law.inputs == summary["chosen"]["regression_lags"]["sensors"]
    assert np.isfinite(law.update(0.0, {name: 300.0 for name in law.inputs}))
    html = (out / "compensation.html").read_text()
    assert 'id="compensation"' in html and "data:image/png;base64" in html
    # issue 34: the noise the readings carried, each candidate's kind, every law's conditioning
    assert summary["noise"]["kinds"]["contact"]["noise_K"] == 0.1
    assert summary["noise"]["kinds"]["infrared"]["offset_K"] == 0.5
    assert summary["candidates"]["T4"]["kind"] == "infrared" and summary["candidates"]["T1"]["kind"] == "contact"
    for name in ("law.json", "law_static.json", "law_kalman.json"):
        document = json.loads((out / name).read_text())
        conditioning = document["conditioning"]
        assert set(conditioning["offset_error_um"]) >= {i["name"] for i in document["inputs"]}, name
        assert conditioning["max_offset_error_um"] == max(conditioning["offset_error_um"].values())
    assert "ridge_K" in summary["chosen"]["regression"] and "conditioning" in summary["best"]
    # issue 34, item 3: the error along the stroke, the stroke law beside each law of D applied at every x
    stroke = summary["stroke"]
    assert stroke["positions"] == 9 and stroke["laws"]["kalman"]["stroke_law"] is None
    kalman = stroke["laws"]["kalman"]["state_along_stroke"]  # the filter's state read along the stroke
    assert 0 < kalman["test"]["rms_um"] <= kalman["test"]["max_um"]
    from feedtherm.analysis.compensation.kalman import KalmanLaw

    estimator = KalmanLaw.from_document(json.loads((out / "law_kalman.json").read_text())).estimator()
    estimator.update(0.0, {n: 300.0 for n in (*estimator.sensors, estimator.model.ambient)}, 1000.0, 1000.0)
    assert np.isfinite(estimator.stroke_error(float(estimator.model.stroke_x.mean())))
    for kind, name in (("regression_lags", "law_stroke.json"), ("regression", "law_stroke_static.json")):
        entry = stroke["laws"][kind]
        assert entry["sensors"] == summary["chosen"][kind]["sensors"] and entry["stroke_law"]["file"] == name
        assert entry["stroke_law"]["order"] in (0, 1, 2, 3) and entry["d_only"]["rms_um"] > 0
        document = json.loads((out / name).read_text())
        assert document["version"] == 2 and document["controller_cost"]["multiply_adds_per_sample"] == \
            entry["stroke_law"]["multiply_adds_per_sample"]
        law = CompensationLaw(document)
        x_min, x_max = document["position"]["x_min_m"], document["position"]["x_max_m"]
        assert np.isfinite(law.update(0.0, {n: 300.0 for n in law.inputs}, (x_min + x_max) / 2))
        with pytest.raises(ValueError, match="^x: .* outside the stroke"):
            law.at(x_max + 0.01)
    assert "along the stroke" in html and "along the stroke E(x) RMS" in lines[-1]
    # issue 34, item 2: the test machines draw every declared uncertainty; out-of-range cases apart
    machine = summary["sets"]["test"]["machines"][0]
    assert {"screw_expansion", "loop_expansion", "tcr_bolted", "front_bearing_preload"} <= set(machine["declared"])
    outside = summary["out_of_range"]
    assert list(outside["cases"]) == ["ambient_ramp", "ambient_step", "fast", "warm_start"]
    assert outside["cycles_per_case"] == 1
    for kind in ("regression", "regression_lags", "kalman"):
        entry = outside["laws"][kind]
        assert entry["sensors"] == summary["chosen"][kind]["sensors"]
        for what in ("d", "stroke"):
            assert list(entry[what]) == list(outside["cases"]), (kind, what)
            for figures in entry[what].values():
                assert 0 <= figures["rms_um"] <= figures["max_um"] and figures["uncompensated_rms_um"] > 0
    assert "out of the training" in html and "; out of range, worst " in lines[-1]


@pytest.mark.parametrize("args, message", [
    (["--sensors", "500"], "--sensors: K = 500 but there are "),
    (["--sensors", "0"], "--sensors: K must be at least 1"),
    (["--sensors", "T1,T9"], "--sensors: no candidate sensor 'T9'"),
    (["--sensors", "T1,T1"], "--sensors: a sensor is listed twice"),
    (["--seed", "1.5"], "argument --seed: must be a whole number, got '1.5'"),
    (["--seed", "one"], "argument --seed: must be a whole number, got 'one'"),
    (["--cycles", "0"], "argument --cycles: must be a positive whole number"),
    (["--mode", "paper", "ballscrew_example"], "--mode paper"),
])
def test_bad_input_is_one_line_exit_2_and_nothing_written(tmp_path, args, message):
    result = run(tmp_path, *args, "--out", "study")
    assert result.returncode == 2
    assert result.stdout == ""
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and message in lines[0], result.stderr
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("section, message", [
    ('[compensation.infrared]\nnoise = "-0.3 K"\nreason = "r"\n', "compensation.infrared.noise: must not be negative"),
    ('[compensation]\nkinds = ["laser"]\n', "compensation.kinds"),
    ('[compensation.contact]\noffset = "0.2 K"\n', "compensation.contact: reason: a declared noise or offset needs"),
])
def test_bad_noise_settings_are_one_line_exit_2_and_nothing_written(tmp_path, section, message):
    from feedtherm.benches import bench

    (tmp_path / "bench.toml").write_text(bench("paper").description.read_text() + "\n" + section)
    result = run(tmp_path, "bench.toml", "--out", "study")
    assert result.returncode == 2 and result.stdout == ""
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and message in lines[0], result.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bench.toml"]


def test_validate_refuses_a_folder_without_a_study_in_one_line(tmp_path):
    result = subprocess.run([sys.executable, "-m", "feedtherm", "validate", "--compensation", str(tmp_path / "none"),
                             "--out", "report"], capture_output=True, text=True, timeout=120, cwd=tmp_path)
    assert result.returncode == 2
    assert result.stderr.splitlines() == [f"feedtherm: error: --compensation: {tmp_path / 'none' / 'compensation.json'} "
                                          "not found (give the output folder of `feedtherm compensate`)"]
    assert list(tmp_path.iterdir()) == []


def test_the_study_reads_back_as_a_report_section(study):
    from feedtherm.outputs.compensation_files import read_compensation_summary
    from feedtherm.outputs.report.compensation import compensation_section

    cwd, _ = study
    read = read_compensation_summary(cwd / "out" / "paper_compensation_physics")
    assert sorted(read["figures"]) == ["error_vs_k.png", "sensor_map.png", "test_cycle.png"]
    html = compensation_section(read["summary"], read["figures"])
    assert html.count("data:image/png;base64") == 3 and "Kalman filter" in html


def test_the_adapted_laws_are_the_posterior_and_the_evaluator_gives_their_mean_and_sd(study):
    """law_adapted*.json: the posterior of law*.json on the file, recomputed here from the prior, the
    file's pairs and the stated scale and width; the evaluator's mean and sd are the posterior's."""
    from feedtherm.analysis.compensation.adapt import adapt_law
    from feedtherm.analysis.compensation.pairs import Pairs
    from feedtherm.analysis.compensation.regression import RegressionLaw

    cwd, result = study
    assert result.returncode == 0, result.stderr
    out = cwd / "out" / "paper_compensation_physics"
    summary = json.loads((out / "compensation.json").read_text())
    block = summary["adaptation"]
    assert block["file"] == "measured.csv" and "not adapted" in block["kalman"]
    rows = [line.split(",") for line in (cwd / "measured.csv").read_text().splitlines()[1:]]
    finals = {(c, q): float(v) for c, q, _, v in rows}
    for prior_file, adapted_file, kind in (("law_static.json", "law_adapted_static.json", "regression"),
                                           ("law.json", "law_adapted.json", "regression_lags")):
        prior, adapted = (json.loads((out / name).read_text()) for name in (prior_file, adapted_file))
        assert block["laws"][kind]["file"] == adapted_file and block["laws"][kind]["samples"] == 4
        posterior = adapted["posterior"]
        law = RegressionLaw(tuple(i["name"] for i in prior["inputs"]), tuple(prior["lags_s"]),
                            np.array(prior["weights_m_per_K"]), prior["bias_m"])
        readings = np.array([[finals[(c, n)] + 273.15 for n in law.sensors] for c in ADAPT_D_UM])
        features = np.repeat(readings, 1 + len(law.lags), axis=1).reshape(4, -1)  # settled lags: the reading
        pairs = Pairs(features, np.array(list(ADAPT_D_UM.values())) * 1e-6, np.full(4, 2e-6), tuple(ADAPT_D_UM))
        expected = adapt_law(law, pairs, np.array(posterior["scale_K"]), width=posterior["prior_width_m"],
                             reference=prior["reference"]["temperature_K"])
        np.testing.assert_allclose(adapted["weights_m_per_K"], expected.law.weights, rtol=1e-6, atol=1e-12)
        evaluator = CompensationLaw(adapted)
        d, sd = evaluator.update_with_sd(0.0, dict(zip(law.sensors, readings[1])))
        mean, sd_expected = expected.predict_features(features[1:2])
        assert d == pytest.approx(mean[0], rel=1e-6, abs=1e-12) and sd == pytest.approx(sd_expected[0], rel=1e-6)
        # the measured pairs are fitted better than by the simulation-trained law (made-up readings: through
        # the reference state, no line fits them all)
        before = law.bias + features[1] @ law.weights.ravel()
        assert abs(d - ADAPT_D_UM["b"] * 1e-6) < abs(before - ADAPT_D_UM["b"] * 1e-6)
        # and the adapted law still reads 0 for a machine at the reference temperature
        at_reference = CompensationLaw(adapted).update(0.0, {n: prior["reference"]["temperature_K"] for n in law.sensors})
        assert at_reference == pytest.approx(0.0, abs=1e-12)


def test_leave_one_condition_out_on_the_measured_bench(study):
    cwd, _ = study
    summary = json.loads((cwd / "out" / "paper_compensation_physics" / "compensation.json").read_text())
    loco = summary["leave_one_condition_out"]
    assert loco["sensors"] == ["T1", "T2", "T3", "T4", "T5"] and loco["lags_s"] == []
    assert [c["condition"] for c in loco["conditions"]] == ["I", "II", "III", "IV", "V"]
    # the measurements' own reference model: the paper's printed deviations, 2.9, 3.4, 3.8, 1.8, 6.2 µm
    assert [round(c["reference_model_um"], 1) for c in loco["conditions"]] == [2.9, 3.4, 3.8, 1.8, 6.2]
    for name in ("model_only", "adapted", "regression", "reference_model"):
        assert loco[name]["conditions"] == 5 and loco[name]["max_um"] >= loco[name]["rms_um"] > 0
    html = (cwd / "out" / "paper_compensation_physics" / "compensation.html").read_text()
    assert "leave one condition out" in html and "laws adapted to measured.csv" in html


FINALS_WITHOUT_D = "condition,quantity,unit,measured\nI,T1,C,27.1\nI,T3,C,34.5\n"
FINALS_WITHOUT_T3 = "condition,quantity,unit,measured\nI,T1,C,27.1\nI,D_um,um,29.9\n"


@pytest.mark.parametrize("text, message", [
    (FINALS_WITHOUT_D, "measured.csv: no measured D"),
    (FINALS_WITHOUT_T3, "measured.csv: condition I does not measure T3, an input of the law on T1, T3"),
    ("condition,quantity,unit\nI,T1,C\n", "measured.csv: line 1: header must be condition,quantity,unit,measured"),
    (None, "measured.csv: no such measurement file"),
])
def test_a_bad_adaptation_file_is_one_line_exit_2_and_nothing_written(tmp_path, text, message):
    if text is not None:
        (tmp_path / "measured.csv").write_text(text)
    result = run(tmp_path, "--sensors", "T1,T3", "--cycles", "1", "--adapt", "measured.csv", "--out", "study")
    assert result.returncode == 2 and result.stdout == ""
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and message in lines[0], result.stderr
    assert [p.name for p in tmp_path.iterdir()] == ([] if text is None else ["measured.csv"])


def test_the_paper_benchs_laws_are_on_carriable_sensors_and_read_zero_at_the_reference(study):
    from test_compensation_reference import check_carriable, check_zero_at_reference

    cwd, result = study
    assert result.returncode == 0, result.stderr
    out = cwd / "out" / "paper_compensation_physics"
    check_carriable(out)
    check_zero_at_reference("paper", out)


def test_the_studys_law_files_pass_the_checked_reader_unchanged(study):
    """Issue 57: every law file the study writes passes the reader a user's file goes through
    (analysis/compensation/law_files.py) without a warning and evaluates to the bit as the parsed
    document did; its conditioning prices each input at its kind's declared offset."""
    from feedtherm.analysis.compensation.apply import read_law
    from feedtherm.analysis.compensation.kalman import KalmanLaw

    cwd, result = study
    assert result.returncode == 0, result.stderr
    out = cwd / "out" / "paper_compensation_physics"
    summary = json.loads((out / "compensation.json").read_text())
    declared = {name: summary["noise"]["kinds"][c["kind"]]["offset_K"] for name, c in summary["candidates"].items()}
    times = np.arange(0.0, 3600.0, 60.0)
    for path in sorted(out.glob("law*.json")):
        document = json.loads(path.read_text())
        if path.name == "law_kalman.json":
            runs = []
            for law in (KalmanLaw.build(document), KalmanLaw.from_file(path)):
                estimator = law.estimator()
                inputs = (*estimator.sensors, estimator.model.ambient)
                runs.append([estimator.update(t, {n: 295.0 + 0.002 * t + i for i, n in enumerate(inputs)}, 1000.0, 900.0)
                             for t in times])
            assert np.array(runs[0]).tobytes() == np.array(runs[1]).tobytes()
        else:
            law = read_law(path)
            assert law.warnings == [], path.name
            runs = []
            for evaluator in (CompensationLaw(document), law):
                values = []
                for t in times:
                    readings = {n: 295.0 + 0.002 * t + i for i, n in enumerate(evaluator.inputs)}
                    if evaluator.stroke:
                        values += [evaluator.update(t, readings, evaluator.x_min), evaluator.at(evaluator.x_max)]
                    else:
                        values += list(evaluator.update_with_sd(t, readings)) if evaluator.posterior else \
                            [evaluator.update(t, readings)]
                runs.append(np.array(values))
            assert runs[0].tobytes() == runs[1].tobytes(), path.name
        offsets = document["conditioning"]["offset_K"]
        assert offsets == {n: declared[n] for n in offsets}, path.name
