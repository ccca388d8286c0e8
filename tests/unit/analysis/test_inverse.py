"""Inverse heat-source estimation: the transfer matrix is the model's own steady response, and
heats made by the model are recovered within their stated intervals."""

import numpy as np
import pytest

from feedtherm.analysis.inverse import Noise, infer, parse_groups, transfer
from feedtherm.cli import main
from feedtherm.errors import FeedthermError
from feedtherm.models.coupling import STEADY_TOLERANCE
from feedtherm.simulate import steady_state

SOURCES = ["guideways", "screw_motor", "nut_motor", "front_bearing", "rear_bearing", "nut_bearing", "screw_nut"]
SIDES = "screw_side=screw_motor,front_bearing,rear_bearing;nut_side=nut_motor,nut_bearing"
NOISE = Noise(temperature=0.5, elongation=2e-6)


@pytest.fixture(scope="module")
def by_source(paper):
    return transfer(paper, "I", parse_groups(None, SOURCES))


@pytest.fixture(scope="module")
def by_side(paper):
    return transfer(paper, "I", parse_groups(SIDES, SOURCES))


def test_the_loss_models_heats_give_the_models_steady_state(paper, paper_equations, by_source):
    """Linearity: baseline + R·q_prior is the steady state of the full model at condition I: to
    round-off at frozen coefficients, and to the coupled steady state's own convergence (1e-4 K)
    on the paper bench, whose coefficients follow the temperatures."""
    frozen = transfer(paper_equations, "I", parse_groups(None, SOURCES))
    steady = steady_state(paper_equations, "I")
    predicted = frozen.predict(frozen.prior)
    for i, name in enumerate(frozen.observations):
        assert predicted[i] == pytest.approx(steady[name], rel=1e-10, abs=1e-15), name
    steady = steady_state(paper, "I")
    predicted = by_source.predict(by_source.prior)
    for i, name in enumerate(by_source.observations):
        assert predicted[i] == pytest.approx(steady[name], abs=STEADY_TOLERANCE * (1e-5 if name == "D" else 1)), name
    # zero heat: every part at the 20 °C ambient, which is also D's reference temperature
    assert np.allclose(by_source.baseline[:-1], 293.15) and abs(by_source.baseline[-1]) < 1e-12
    # more heat never cools a sensor or shortens the screw
    assert np.all(by_source.matrix >= -1e-12)


def test_groups_share_their_watt_as_the_loss_models_do(by_source, by_side):
    """A group's column is its members' columns weighted by their shares of the group's heat."""
    members = ["screw_motor", "front_bearing", "rear_bearing"]
    columns = [by_source.matrix[:, SOURCES.index(m)] for m in members]
    powers = np.array([by_source.prior[SOURCES.index(m)] for m in members])
    expected = sum(p * c for p, c in zip(powers, columns)) / powers.sum()
    np.testing.assert_allclose(by_side.matrix[:, 0], expected, rtol=1e-10)
    assert by_side.prior[0] == pytest.approx(powers.sum())


def test_heats_made_by_the_model_are_recovered_without_noise(by_side):
    """Four groups, six observations, a prior too wide to matter: the data alone set the heats."""
    truth = by_side.prior * np.array([1.5, 0.7, 1.0, 2.0])
    measured = dict(zip(by_side.observations, by_side.predict(truth)))
    result = infer(by_side, measured, NOISE, prior_width=1e3)
    for estimate, true in zip(result.estimates, truth):
        if estimate.resolution > 0.99:
            assert estimate.inferred == pytest.approx(true, rel=0.02, abs=0.05), estimate.group
    assert sum(e.resolution > 0.99 for e in result.estimates) >= 2
    assert result.chi2 < 1e-6


def test_stated_intervals_cover_the_true_heats_as_often_as_they_say(by_source):
    """Truth drawn from the prior, noise from the noise model: the 95 % intervals hold the truth in
    about 95 % of the cases (a Bayesian interval's coverage averaged over its prior), though the
    seven heats are not all identifiable from six measurements."""
    rng = np.random.default_rng(20261123)
    width = 0.3
    tau = np.maximum(width * by_source.prior, width)
    sigma = np.array([NOISE.temperature] * 5 + [NOISE.elongation])
    inside = total = 0
    for _ in range(400):
        truth = by_source.prior + tau * rng.standard_normal(len(tau))
        if np.any(truth < 0):  # the estimator knows heats are not negative; keep the prior's support
            continue
        measured = dict(zip(by_source.observations, by_source.predict(truth) + sigma * rng.standard_normal(6)))
        result = infer(by_source, measured, NOISE, prior_width=width)
        inside += sum(e.low <= t <= e.high for e, t in zip(result.estimates, truth))
        total += len(truth)
    assert total > 1000
    assert 0.92 <= inside / total <= 0.98


def test_the_report_names_what_the_sensors_cannot_tell_apart(by_source):
    measured = dict(zip(by_source.observations, by_source.predict(by_source.prior)))
    # A weak prior (10 x the loss models' heats) leaves the pairs to the data alone.
    weak = infer(by_source, measured, NOISE, prior_width=10.0)
    pairs = {frozenset((a, b)) for a, b, _ in weak.not_told_apart}
    # T1 sits over the front bearing's seat, next to the screw motor: 1 W in either warms it alike;
    # the nut bearing and the thread both heat the nut under T3
    assert frozenset(("screw_motor", "front_bearing")) in pairs
    assert frozenset(("nut_bearing", "screw_nut")) in pairs
    result = infer(by_source, measured, NOISE)
    guideways = result.estimates[SOURCES.index("guideways")]
    assert guideways.resolution < 0.1  # 0.1 W spread over the rails: no sensor sees it


@pytest.mark.parametrize("text, message", [
    ("motors=screw_motor,nut_motr", "no heat source 'nut_motr'"),
    ("a=screw_motor;b=screw_motor", "'screw_motor' is in two groups"),
    ("motors", "is not NAME=SOURCE"),
    ("a=screw_motor;a=nut_motor", "group name 'a' is used twice"),
    ("nut_motor=screw_motor", "named like a source"),
])
def test_bad_groups_are_named(text, message):
    with pytest.raises(FeedthermError, match=message):
        parse_groups(text, SOURCES)


def test_the_command_writes_its_files_and_refuses_bad_input(tmp_path, capsys):
    out = tmp_path / "inference"
    assert main(["infer", "--conditions", "I", "--groups", SIDES, "--out", str(out)]) == 0
    rows = (out / "inference.csv").read_text().splitlines()
    assert rows[0].startswith("condition,group,sources,loss_model_W,inferred_W")
    assert sorted(r.split(",")[1] for r in rows[1:]) == ["guideways", "nut_side", "screw_nut", "screw_side"]
    assert (out / "inference.json").is_file()
    printed = capsys.readouterr().out
    assert "condition I: heat per group [W]" in printed and "inference.csv" in printed
    for args, message in [(["--conditions", "VI"], "no measurements of 'VI'"),
                          (["--groups", "x=nope"], "no heat source 'nope'"),
                          (["--sigma-temperature", "0"], "must be a positive number")]:
        code = None
        try:
            code = main(["infer", *args, "--out", str(tmp_path / "bad")])
        except SystemExit as exc:  # argparse's own errors
            code = exc.code
        err = capsys.readouterr().err.strip().splitlines()
        assert code == 2 and len(err) == 1 and message in err[0], err
        assert not (tmp_path / "bad").exists()
