"""Identifiability from the fit's Jacobian: two parameters acting through one quantity are
reported whatever their units (the condition number alone depends on them)."""

import numpy as np

from feedtherm.analysis.calibration import COLLINEAR_CORRELATION, SINGULAR_CONDITION_NUMBER, _uncertainty


def test_two_parameters_through_one_torque_are_reported_in_any_units():
    # T3 and T4 per unit friction coefficient and per newton of preload: proportional columns
    # (the torque is their product) up to a second-order term of 1e-4, as the paper bench's fit
    # gives.  In these units the condition number is about 3e7, below the singular threshold.
    jac = np.array([[282.558861, 0.197424214], [259.718776, 0.181481468]])
    singular = np.linalg.svd(jac, compute_uv=False)
    assert singular[0] / singular[-1] < SINGULAR_CONDITION_NUMBER
    se, corr, reasons, *_ = _uncertainty(jac, np.array([0.1, -0.1]), np.array([0.134, 182.5]), 2,
                                         ["screw_nut_friction", "screw_nut_preload"])
    assert abs(corr[0, 1]) > COLLINEAR_CORRELATION
    assert reasons[0].startswith("not identifiable: the data fix only its combination with screw_nut_preload")
    assert reasons[1].startswith("not identifiable: the data fix only its combination with screw_nut_friction")


def test_parameters_with_distinct_effects_are_identifiable():
    # one sensor each with a little cross-talk: JᵀJ = [[1.04, 0.4], [0.4, 1.04]], so by hand the
    # estimates' correlation is that of its inverse, -0.4/1.04 = -0.385
    jac = np.array([[1.0, 0.2], [0.2, 1.0]])
    se, corr, reasons, *_ = _uncertainty(jac, np.array([0.01, -0.02]), np.array([10.0, 10.0]), 2, ["a", "b"])
    assert abs(corr[0, 1] + 0.4 / 1.04) < 1e-12
    assert reasons == ["", ""]
