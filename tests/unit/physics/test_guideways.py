"""Guideway friction heat (paper Eq. 13, standard form and as printed).

Expected values are paper Table 1 / docs/paper-audit.md numbers or hand calculations in comments.
Feed of condition I (Table 5): 0.18 m/min = 0.18/60 = 0.003 m/s.
"""

from __future__ import annotations

import numpy as np
import pytest

from feedtherm.physics.guideways import (
    friction_force_guideway,
    heat_guideway,
    heat_guideway_paper,
)

V_I = 0.18 / 60.0  # 0.003 m/s


def test_friction_force_audit_defaults():
    # docs/paper-audit.md §4: μ = 0.005, moving mass 60 kg (W = 60·9.81 = 588.6 N), 4 carriages × 4 N:
    # 0.005·588.6 + 4·4 = 2.943 + 16 = 18.943 N (docs/paper-audit.md §1: "about 15–20 N").
    assert friction_force_guideway(0.005, 588.6, 4.0, 4) == pytest.approx(18.943)


def test_heat_audit_defaults_at_condition_I():
    # 18.943 N · 0.003 m/s = 0.05683 W (docs/paper-audit.md: "≈0.05 W"), ~7× below Table 1's 0.39 W.
    h = heat_guideway(friction_force_guideway(0.005, 588.6, 4.0, 4), V_I)
    assert h == pytest.approx(0.05683, rel=1e-4)
    assert 0.39 / h == pytest.approx(6.86, rel=1e-2)


def test_heat_sign_of_speed_ignored_and_arrays():
    # Reciprocating table: ±0.003 m/s and condition III 0.54 m/min = 0.009 m/s.
    np.testing.assert_allclose(heat_guideway(20.0, [-V_I, 0.009]), [0.06, 0.18])


def test_paper_table1_needs_130_N():
    # Table 1: 0.39 W at 0.003 m/s -> λ f_g F_g = 0.39/0.003 = 130 N (docs/paper-audit.md §1 row 13).
    assert 0.39 / V_I == pytest.approx(130.0)
    assert heat_guideway_paper(1.0, 0.005, 26000.0, V_I) == pytest.approx(0.39)  # 0.005·26 kN


def test_paper_table1_from_speed_in_m_per_min():
    # Entering the feed as 0.18 (m/min) instead of 0.003 (m/s):
    # λ f_g F_g = 0.39/0.18 = 2.167 N ≈ 2.2 N reproduces 0.39 W.
    lam_f_F = 0.39 / 0.18
    assert lam_f_F == pytest.approx(2.2, abs=0.05)
    assert heat_guideway_paper(1.0, 1.0, lam_f_F, 0.18) == pytest.approx(0.39)
    # The same λ f_g F_g at the correct SI speed gives 60× less: 2.167·0.003 = 0.0065 W.
    assert heat_guideway_paper(1.0, 1.0, lam_f_F, V_I) == pytest.approx(0.0065, rel=1e-3)


def test_standard_and_paper_forms_agree_without_seals_and_lambda_1():
    # With λ = 1 and no seals, Eq. 13 printed equals the standard form:
    # 0.005·588.6·0.003 = 0.008829 W.
    standard = heat_guideway(friction_force_guideway(0.005, 588.6, 0.0, 4), V_I)
    assert standard == pytest.approx(0.008829, rel=1e-4)
    assert heat_guideway_paper(1.0, 0.005, 588.6, V_I) == pytest.approx(standard)


@pytest.mark.parametrize(
    ("args", "match"),
    [
        ((-0.005, 588.6, 4.0, 4), "mu"),
        ((0.005, -1.0, 4.0, 4), "normal_load"),
        ((0.005, 588.6, -4.0, 4), "seal"),
        ((0.005, 588.6, 4.0, 2.5), "n_carriages"),
        ((0.005, 588.6, 4.0, -1), "n_carriages"),
    ],
)
def test_friction_force_rejects_bad_inputs(args, match):
    with pytest.raises(ValueError, match=match):
        friction_force_guideway(*args)


def test_heat_rejects_bad_inputs():
    with pytest.raises(ValueError, match="friction_force"):
        heat_guideway(-1.0, V_I)
    with pytest.raises(ValueError, match="speed"):
        heat_guideway(18.9, float("inf"))
    with pytest.raises(ValueError, match="lam"):
        heat_guideway_paper(-1.0, 0.005, 588.6, V_I)
