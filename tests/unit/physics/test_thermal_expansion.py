import numpy as np
import pytest

from feedtherm.physics.thermal_expansion import displacement_axial, elongation_axial


def test_uniform_rise_gives_alpha_l_dt():
    # A 0.4 m steel bar 5 K above the reference: D = 1.2e-5 * 0.4 * 5 = 24 µm
    edges = np.linspace(-0.1, 0.5, 61)
    T = np.full(60, 298.15)
    assert elongation_axial(edges, T, 1.2e-5, 293.15, 0.0, 0.4) == pytest.approx(24e-6, rel=1e-12)


def test_displacement_is_zero_at_the_fixed_point_and_negative_behind_it():
    edges = np.array([0.0, 0.1, 0.2, 0.3])
    T = np.array([303.15, 293.15, 313.15])  # +10 K, 0 K, +20 K over 0.1 m cells
    u = displacement_axial(edges, T, 1e-5, 293.15, 0.1, np.array([0.0, 0.1, 0.25, 0.3]))
    # x = 0.0: -(1e-5 * 10 * 0.1) = -1e-5; x = 0.25: 0 + 1e-5 * 20 * 0.05 = 1e-5; x = 0.3: 2e-5
    assert u == pytest.approx([-1e-5, 0.0, 1e-5, 2e-5], abs=1e-15)


def test_time_series_broadcast():
    edges = np.linspace(0.0, 1.0, 11)
    T = np.vstack([np.full(10, 293.15), np.full(10, 303.15)])
    assert elongation_axial(edges, T, 1e-5, 293.15, 0.0, 1.0) == pytest.approx([0.0, 1e-4])
