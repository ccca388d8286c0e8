"""Sensor noise in a compensation study (issue 34, item 1): kinds, noisy readings, ridge, conditioning."""

import numpy as np
import pytest

from feedtherm.analysis.candidates import candidate_sensors
from feedtherm.analysis.compensation.conditioning import kalman_conditioning, regression_conditioning
from feedtherm.analysis.compensation.data import CycleRecord, CycleSet
from feedtherm.analysis.compensation.kalman import KalmanLaw
from feedtherm.analysis.compensation.law import law_document
from feedtherm.analysis.compensation.metrics import residuals
from feedtherm.analysis.compensation.noise import DEFAULT_NOISE, KindLevels, SensorNoise, noisy_set
from feedtherm.analysis.compensation.regression import RegressionLaw, fit_regression, lagged
from feedtherm.analysis.compensation.selection import fit_on, fit_validated, greedy_selection, predictor
from feedtherm.analysis.compensation.stroke import StrokeLaw, stroke_conditioning
from feedtherm.errors import FeedthermError
from feedtherm.system.load import load_system

NAMES = ["A", "B", "C"]


def _walk(rng, n, scale):
    """A smooth random signal [K] of about ``scale`` amplitude."""
    x = lagged(np.arange(n) * 60.0, np.cumsum(rng.normal(0, 1, (n, 1)), axis=0), 1200.0)[:, 0]
    x = x - x.mean()
    return scale * x / np.abs(x).max()


def _constructed(name, seed, n_cycles=4, n=400):
    """The constructed case: latent u (10 K), v (1 K), w (0.1 K); D = (u + v) x 1 µm/K.

    A = u and B = u + 0.01 v are nearly collinear: noise-free, D = A + 100 (B - A) exactly, with
    weights -99 and +100 µm/K.  C = v + w sees v directly: D = A + C - w, weights 1 and 1 µm/K,
    short of exact by w (0.1 K amplitude: about 0.05 µm RMS).
    """
    rng = np.random.default_rng(seed)
    records = []
    for i in range(n_cycles):
        u, v, w = _walk(rng, n, 10.0), _walk(rng, n, 1.0), _walk(rng, n, 0.1)
        readings = 293.15 + np.column_stack([u, u + 0.01 * v, v + w])
        records.append(CycleRecord(f"{name}-{i}", np.arange(n) * 60.0, readings, 1e-6 * (u + v),
                                   np.zeros(n), np.zeros(n)))
    return CycleSet(name, list(NAMES), records)


def _noise(white, offset):
    return SensorNoise({"contact": KindLevels(white, offset, "test"), "infrared": KindLevels(white, offset, "test")},
                       {n: "contact" for n in NAMES})


def test_noisy_selection_prefers_the_well_conditioned_set():
    """Given A, the noise-free selection adds B (exact, by a difference of weights ±100 µm/K); read
    through sensors of 0.1 K noise and 0.1 K offsets it adds C: B - A is then 0.01 v under noise of
    0.14 K, while C carries v itself."""
    train, validation = _constructed("train", 1), _constructed("validation", 2)
    clean = greedy_selection(train, validation, 2, start=("A",))
    assert clean[-1].sensors == ("A", "B") and clean[-1].validation_rms < 1e-9
    assert np.abs(clean[-1].law.weights).max() > 90e-6  # ill-conditioned: ~100 µm/K

    noise = _noise(0.1, 0.1)
    noisy = greedy_selection(noisy_set(train, noise, 0, 0, one_machine=True),
                             noisy_set(validation, noise, 0, 1, one_machine=False), 2, start=("A",))
    assert noisy[-1].sensors == ("A", "C")
    assert np.abs(noisy[-1].law.weights).max() < 1.5e-6  # about 1 µm/K each
    assert regression_conditioning(noisy[-1].law)["within_limit"]
    # without a start, likewise: one of the collinear pair (A or B, equally good alone) and C
    free = greedy_selection(noisy_set(train, noise, 0, 0, True), noisy_set(validation, noise, 0, 1, False), 2)
    assert "C" in free[-1].sensors and len({"A", "B"} & set(free[-1].sensors)) == 1


def test_the_ridge_chosen_on_validation():
    """Trained on exact readings of A and B: on a validation machine read exactly, no ridge (the fit
    is exact); on machines whose sensors are off by 0.1 K (offsets, no white noise), a ridge, with
    far smaller weights and a smaller validation error than least squares."""
    train, validation = _constructed("train", 3), _constructed("validation", 4)
    exact = fit_validated(train, validation, ("A", "B"))
    assert exact.ridge == 0.0
    assert residuals(predictor(exact, NAMES), validation).rms < 1e-9

    off = noisy_set(validation, _noise(0.0, 0.1), 7, 1, one_machine=False)
    ridged = fit_validated(train, off, ("A", "B"))
    plain = fit_on(train, ("A", "B"))
    assert ridged.ridge > 0.0
    assert np.abs(ridged.weights).max() < 0.2 * np.abs(plain.weights).max()
    assert residuals(predictor(ridged, NAMES), off).rms < 0.5 * residuals(predictor(plain, NAMES), off).rms


def test_a_one_sensor_ridge_by_hand():
    """w = Σ x y / (Σ x² + n α) on centred data (the module's formula), and α = 0 is least squares."""
    x = np.array([0.0, 1.0, 2.0, 3.0])
    y = np.array([0.0, 2.0, 3.0, 7.0]) * 1e-6
    t = np.arange(4) * 60.0
    xc, yc = x - x.mean(), y - y.mean()
    for alpha in (0.0, 0.25, 1.0):
        law = fit_regression([(t, (293.15 + x)[:, None], y)], ("x",), ridge=alpha)
        expected = (xc @ yc) / (xc @ xc + 4 * alpha)
        assert law.weights[0, 0] == pytest.approx(expected, rel=1e-12)
        assert law.bias + law.weights[0, 0] * (293.15 + x.mean()) == pytest.approx(y.mean(), rel=1e-12)


def test_noisy_readings_are_reproducible_with_one_offset_per_machine():
    cycles = _constructed("validation", 5, n_cycles=3, n=2000)
    noise = _noise(0.3, 0.5)
    first, again = noisy_set(cycles, noise, 9, 1, False), noisy_set(cycles, noise, 9, 1, False)
    other = noisy_set(cycles, noise, 10, 1, False)
    for a, b, c, clean in zip(first.cycles, again.cycles, other.cycles, cycles.cycles):
        np.testing.assert_array_equal(a.sensors, b.sensors)
        assert not np.array_equal(a.sensors, c.sensors)
        np.testing.assert_array_equal(a.truth, clean.sensors)
        error = a.sensors - clean.sensors
        assert np.std(error, axis=0) == pytest.approx([0.3] * 3, rel=0.1)  # white, 2000 samples
    offsets = [np.mean(r.sensors - r.truth, axis=0) for r in first.cycles]
    assert not np.allclose(offsets[0], offsets[1], atol=0.05)  # each validation cycle is another machine
    train = noisy_set(cycles, noise, 9, 0, one_machine=True)
    means = [np.mean(r.sensors - r.truth, axis=0) for r in train.cycles]
    np.testing.assert_allclose(means[0], means[1], atol=0.05)  # one machine: one offset per sensor
    np.testing.assert_array_equal(first.clean().cycles[0].sensors, cycles.cycles[0].sensors)


def test_the_offset_cost_of_a_lagged_law_is_its_steady_state_gain():
    law = RegressionLaw(("a", "b"), (900.0, 3600.0), np.array([[30e-6, -25e-6, 1e-6], [2e-6, 0.0, 0.0]]), 0.0,
                        ridge=0.01)
    c = regression_conditioning(law)
    assert c["max_abs_weight_um_per_K"] == pytest.approx(30.0)
    assert c["offset_error_um"] == pytest.approx({"a": 0.6, "b": 0.2})  # |30 - 25 + 1| x 0.1, |2| x 0.1
    assert c["offset_transient_um"]["a"] == pytest.approx(5.6)
    assert c["within_limit"] and c["ridge_K"] == pytest.approx(0.1)
    assert not regression_conditioning(RegressionLaw(("a",), (), np.array([[874e-6]]), 0.0))["within_limit"]


def test_each_input_is_priced_at_its_own_kinds_declared_offset():
    """a is a contact sensor (declared offset 0.1 K), b an infrared one (0.5 K), by hand:
    a: |30 - 25 + 1| µm/K x 0.1 K = 0.6 µm, while the lags settle (30 + 25 + 1) x 0.1 = 5.6 µm;
    b: |2| µm/K x 0.5 K = 1.0 µm, the worst (at 0.1 K, as before, it read 0.2 µm and a was the worst)."""
    law = RegressionLaw(("a", "b"), (900.0, 3600.0), np.array([[30e-6, -25e-6, 1e-6], [2e-6, 0.0, 0.0]]), 0.0)
    offsets = SensorNoise(dict(DEFAULT_NOISE), {"a": "contact", "b": "infrared"}).offsets()
    assert offsets == {"a": 0.1, "b": 0.5}
    c = regression_conditioning(law, offsets)
    assert c["offset_K"] == {"a": 0.1, "b": 0.5}
    assert c["offset_error_um"] == pytest.approx({"a": 0.6, "b": 1.0})
    assert c["offset_transient_um"] == pytest.approx({"a": 5.6, "b": 1.0})
    assert c["max_offset_error_um"] == pytest.approx(1.0)
    assert law_document(law, {}, offsets=offsets)["conditioning"] == c  # law.json's block
    # a stroke law, order 1, no lags: a's weight along ξ is 2 + ξ µm/K, b's 4 - ξ; the largest over the
    # stroke |2 + 1| x 0.1 K = 0.3 µm and |4 + 1| x 0.5 K = 2.5 µm, above the 2 µm limit
    stroke = StrokeLaw(("a", "b"), (), 1, np.array([[2e-6, 1e-6], [4e-6, -1e-6]]), np.zeros(2), 0.1, 0.3)
    block = stroke_conditioning(stroke, offsets=offsets)
    assert block["offset_error_um"] == pytest.approx({"a": 0.3, "b": 2.5})
    assert block["offset_K"] == {"a": 0.1, "b": 0.5} and not block["within_limit"]


def test_the_kalman_estimators_offset_cost_scales_with_each_inputs_declared_offset():
    """The filter is linear in its readings (its gains do not depend on them): T1 read 0.5 K high
    moves D̂ by five times what 0.1 K does."""
    from law_documents import kalman_document

    law = KalmanLaw.build(kalman_document())
    n = 60
    times = np.arange(n) * 60.0
    readings = 293.15 + np.column_stack([np.linspace(0, 4, n), np.linspace(0, 1, n)])  # T1, ambient
    record = CycleRecord("test-0", times, readings, np.zeros(n), np.full(n, 800.0), np.zeros(n))
    contact = kalman_conditioning(law, record, ["T1", "ambient"], {"T1": 0.1, "ambient": 0.1})
    infrared = kalman_conditioning(law, record, ["T1", "ambient"], {"T1": 0.5, "ambient": 0.1})
    assert infrared["offset_K"] == {"T1": 0.5, "ambient": 0.1}
    assert contact["offset_error_um"]["T1"] > 0
    assert infrared["offset_error_um"]["T1"] == pytest.approx(5 * contact["offset_error_um"]["T1"], rel=1e-9)
    assert infrared["offset_error_um"]["ambient"] == pytest.approx(contact["offset_error_um"]["ambient"], rel=1e-12)
    assert infrared["max_abs_gain_um_per_K"] == pytest.approx(contact["max_abs_gain_um_per_K"], rel=1e-9)


def test_a_studys_offsets_are_the_declared_ones_of_each_kind(paper, tmp_path):
    """What the study prices the conditioning at: the description's [compensation] values, per kind."""
    path = _with_section(tmp_path, '[compensation.infrared]\noffset = "1 K"\nreason = "a pyrometer of ±2 K"\n')
    loaded = load_system(str(path))
    kinds = {n: c.kind for n, c in candidate_sensors(loaded.system).items()}
    offsets = SensorNoise.of(loaded.system, kinds).offsets()
    assert offsets["T4"] == 1.0 and offsets["T1"] == DEFAULT_NOISE["contact"].offset  # T4 infrared, T1 contact


@pytest.fixture(scope="module")
def paper():
    return load_system("paper")


def _with_section(tmp_path, text):
    from feedtherm.benches import bench

    source = bench("paper").description
    path = tmp_path / "description.toml"
    path.write_text(source.read_text() + "\n" + text)
    return path


def test_kinds_infrared_on_turning_parts_contact_elsewhere(paper):
    # a part that moves with the table without turning carries its sensor's cable in the drag chain
    system = paper.system
    candidates = candidate_sensors(system)
    for name, c in candidates.items():
        if c.where in ("declared", "ambient"):
            continue
        turning = c.part in ("screw", "nut", "belt")  # the paper's dual drive turns its nut and its belt
        assert c.kind == ("infrared" if turning else "contact"), name
    assert candidates["T4"].kind == "infrared" and candidates["T1"].kind == "contact"
    assert candidates["T3"].kind == "contact"  # declared: keeps the paper's PT100 on the nut housing


def test_a_description_restricts_the_kinds_and_overrides_the_levels(paper, tmp_path):
    path = _with_section(tmp_path, '[compensation]\nkinds = ["contact"]\n\n[compensation.infrared]\n'
                                   'offset = "1 K"\nreason = "a pyrometer of ±2 K"\n')
    loaded = load_system(str(path))
    candidates = candidate_sensors(loaded.system)
    generated = [c for c in candidates.values() if c.where not in ("declared", "ambient")]
    assert generated and all(c.kind == "contact" for c in generated)
    assert not any(c.part == "screw" for c in generated)
    assert "T4" in candidates  # a declared sensor is mounted: it stays
    assert len(candidates) < len(candidate_sensors(paper.system))
    noise = SensorNoise.of(loaded.system, {n: c.kind for n, c in candidates.items()})
    assert noise.levels["infrared"].offset == 1.0 and noise.levels["infrared"].noise == DEFAULT_NOISE["infrared"].noise
    assert noise.levels["contact"] == DEFAULT_NOISE["contact"]
    assert SensorNoise.of(paper.system, {}).levels == DEFAULT_NOISE


@pytest.mark.parametrize("section, message", [
    ('[compensation.contact]\nnoise = "-0.1 K"\nreason = "r"\n', "compensation.contact.noise: must not be negative"),
    ('[compensation.infrared]\noffset = "0.5 K"\n', "compensation.infrared: reason: a declared noise"),
    ('[compensation]\nkinds = []\n', "compensation.kinds"),
    ('[compensation]\nkinds = ["contact", "laser"]\n', "compensation.kinds"),
    ('[compensation.contact]\nnoise = "0.1 m"\nreason = "r"\n', "compensation.contact.noise"),
])
def test_bad_noise_settings_are_refused_naming_the_field(tmp_path, section, message):
    with pytest.raises(FeedthermError) as info:
        load_system(str(_with_section(tmp_path, section)))
    text = str(info.value)
    assert "\n" not in text and message in text, text
