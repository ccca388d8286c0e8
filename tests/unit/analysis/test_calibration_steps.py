"""How calibration spends its runs: Broyden's update, the convergence test, and the run cache.

The model is replaced by an analytic one (``fake_finals``), so that the tests check the fit's
arithmetic and count its runs without running the thermal model.
"""

import numpy as np
import pytest

from feedtherm.analysis import calibration
from feedtherm.analysis.calibration import RunCache, _Broyden, _converged, calibrate, cross_validate
from feedtherm.system.measurements import read_measurements
from feedtherm.system.paths import get_path

PARAMS = ["screw_nut_preload", "chtc_screw"]
CONDITIONS = ["I", "II", "III", "IV"]
TRUTH = {"sources.screw_nut.preload": 250.0, "surfaces.screw_shaft.chtc_factor": 1.5}
#: Per condition: how strongly T1 and T2 follow the preload [K/N] and the CHTC factor [K].
GAINS = {"I": (0.010, -2.0), "II": (0.014, -2.5), "III": (0.020, -1.0), "IV": (0.012, -3.0)}


def fake_finals(loaded, condition):
    """Smooth, slightly nonlinear values of the two parameters (no thermal model run)."""
    preload = float(get_path(loaded.system, "sources.screw_nut.preload"))
    chtc = float(get_path(loaded.system, "surfaces.screw_shaft.chtc_factor"))
    a, b = GAINS[condition]
    return {"T1": 20.0 + a * preload + b * chtc, "T2": 20.0 + 0.5 * a * preload + b * np.sqrt(chtc),
            "D_um": 10.0 + 0.05 * preload * chtc}


@pytest.fixture
def counted(monkeypatch):
    """The fake model in place of the thermal model, and the list of the runs it made."""
    runs = []

    def run(loaded, condition, *, model="fast", mesh=None):
        runs.append(condition)
        return fake_finals(loaded, condition)

    monkeypatch.setattr(calibration, "_final_values", run)
    return runs


@pytest.fixture
def measured(paper, tmp_path):
    from feedtherm.system.variants import with_values

    truth = with_values(paper, TRUTH)
    lines = ["condition,quantity,unit,measured"]
    for c in CONDITIONS:
        values = fake_finals(truth, c)
        lines += [f"{c},{q},{'um' if q == 'D_um' else 'C'},{float(v)!r}" for q, v in values.items()]
    path = tmp_path / "measured.csv"
    path.write_text("\n".join(lines) + "\n")
    return read_measurements(str(path), sensors=["T1", "T2"])


def test_broyden_update_meets_the_secant_condition_and_keeps_a_linear_jacobian():
    A = np.array([[2.0, -1.0], [0.5, 3.0], [1.0, 1.0]])
    linear = _Broyden(lambda u: A @ u - 1.0, np.array([0.2, 0.3]), A)
    np.testing.assert_allclose(linear(np.array([0.5, 0.1])), A)  # exact stays exact

    def curved(u):
        return np.array([u[0] ** 2 + u[1], np.sin(u[1]), u[0] * u[1]])

    u0, u1 = np.array([0.2, 0.3]), np.array([0.4, 0.35])
    jac0 = np.array([[0.4, 1.0], [0.0, np.cos(0.3)], [0.3, 0.2]])  # exact at u0
    jac1 = _Broyden(curved, u0, jac0)(u1)
    # J1·Δu = Δf (the secant condition), and J1 differs from J0 only along Δu
    np.testing.assert_allclose(jac1 @ (u1 - u0), curved(u1) - curved(u0), rtol=1e-12)
    orthogonal = np.array([-(u1 - u0)[1], (u1 - u0)[0]])
    np.testing.assert_allclose(jac1 @ orthogonal, jac0 @ orthogonal, rtol=1e-12)


def test_convergence_is_judged_by_the_bounded_gauss_newton_step():
    A = np.array([[1.0, 0.0], [0.0, 2.0], [1.0, 1.0]])
    b = A @ np.array([0.4, 0.6])
    assert _converged(A, A @ np.array([0.4, 0.6]) - b, np.array([0.4, 0.6]))  # at the minimum
    assert not _converged(A, A @ np.array([0.1, 0.9]) - b, np.array([0.1, 0.9]))  # far from it
    # the minimum lies beyond the upper bound of u[0]; on that bound the residual is least at
    # u[1] = 0.7 (d/du1 of (2u1 - 1.2)^2 + (u1 - 1.1)^2 = 0), where the bounded step is zero
    beyond = A @ np.array([1.5, 0.6])
    u = np.array([1.0, 0.7])
    assert not _converged(A, A @ np.array([0.7, 0.6]) - beyond, np.array([0.7, 0.6]))
    assert _converged(A, A @ u - beyond, u)


def test_the_cache_runs_each_point_once_even_through_the_fit_scaling(paper, counted):
    params = calibration.resolve_parameters(paper, PARAMS)
    lower = np.array([p.lower for p in params])
    upper = np.array([p.upper for p in params])
    x = np.array([187.3, 1.234567])
    with calibration._Model(paper, params, cache=RunCache()) as model:
        first = model.finals(x, ["I", "II"])
        scaled = lower + ((x - lower) / (upper - lower)) * (upper - lower)  # differs in the last bit
        again = model.finals(scaled, ["I", "II"])
        assert counted == ["I", "II"] and again == first
        base, steps, moved = model.sensitivities(x, lower, upper, ["I", "II"])
        assert len(counted) == 2 + 2 * len(params)  # the base point was cached
        assert base == first and len(moved) == len(steps) == len(params)


def test_the_fit_recovers_the_truth_and_the_folds_reuse_its_runs(paper, measured, counted):
    cache = RunCache()
    result = calibrate(paper, measured, ["I", "II", "III"], PARAMS, cache=cache)
    np.testing.assert_allclose(result.fitted, [TRUTH["sources.screw_nut.preload"],
                                               TRUTH["surfaces.screw_shaft.chtc_factor"]], rtol=1e-3)
    assert result.model_runs == len(counted)
    held = {(p.condition, p.quantity): p for p in result.held_out}
    assert abs(held[("IV", "T1")].deviation) < 1e-2  # an exact model predicts the held-out condition

    counted.clear()
    shared = cross_validate(paper, measured, PARAMS, start=result.fitted, cache=cache)
    with_cache = len(counted)
    counted.clear()
    alone = cross_validate(paper, measured, PARAMS, start=result.fitted)
    assert with_cache < len(counted)  # each fold's start and its Jacobian there were known
    for (c1, r1), (c2, r2) in zip(shared, alone):
        assert c1 == c2
        np.testing.assert_allclose(r1.fitted, r2.fitted, rtol=1e-6)
        np.testing.assert_allclose(r1.fitted, result.fitted, rtol=1e-3)
