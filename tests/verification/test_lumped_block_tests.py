r"""A test's start and room, through the command line (``cases/lumped_block.toml``).

An aluminium cube, 50 mm a side, every face cooled by h = 10 W/(m²·K), no heat: Bi = h (V/A)/k
= 10 · 8.333e-3 / 200 = 4.2e-4, so it is a lumped body (Incropera et al., 7th ed., §5.1–5.2):

    ρ c V dT/dt = −h A (T − T_air(t)),    τ = ρ c (V/A) / h = 2700 · 900 · 8.333e-3 / 10 = 2025 s.

* ``cooling``: started 5 K above air at a constant 20 °C, T(t) = 20 + 5 e^{−t/τ}.
* ``ramp``: started at the air, the logged air rising at r = 1 K/h (its log,
  ``lumped_block_room.csv``, is exactly linear between its samples): with θ = T − T_air(0),
  dθ/dt = (r t − θ)/τ, θ(0) = 0, so θ(t) = r (t − τ (1 − e^{−t/τ})).

Implicit Euler in the 10 s steps of a standstill lags the exact decay by about (t/τ)(Δt/τ)/2
of it, 0.5 % at t = 2τ; the issue's bound is 1 %.
"""

import csv
import math

import numpy as np
import pytest

from feedtherm.cli import main

CASE = "tests/verification/cases/lumped_block.toml"
TAU = 2700 * 900 * (0.05 / 6) / 10  # [s]
RATE = 1.0 / 3600  # [K/s]


def run(test: str, out) -> dict[str, np.ndarray]:
    assert main(["run", CASE, "--test", test, "--no-plots", "--out", str(out)]) == 0
    with open(out / "sensors.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    return {key: np.array([float(r[key]) for r in rows]) for key in rows[0]}


def test_tau_worked_out():
    assert TAU == pytest.approx(2025.0)


def test_a_start_5_k_above_the_room_decays_as_a_lumped_block(tmp_path):
    series = run("cooling", tmp_path)
    t, block = series["time_s"], series["centre"]
    exact = 20.0 + 5.0 * np.exp(-t / TAU)
    assert block[0] == pytest.approx(25.0, abs=1e-9)  # the declared start
    assert np.all(series["ambient"] == 20.0)
    # within 1 % of the initial excess throughout, and of the excess itself while it is above 1 K
    assert np.max(np.abs(block - exact)) <= 0.01 * 5.0
    early = exact - 20.0 > 1.0
    assert np.max(np.abs((block - 20.0)[early] / (exact - 20.0)[early] - 1.0)) <= 0.01


def test_a_logged_room_air_ramp_is_followed_as_a_lumped_block(tmp_path):
    series = run("ramp", tmp_path)
    t, block, air = series["time_s"], series["centre"], series["ambient"]
    assert air == pytest.approx(20.0 + RATE * t, abs=5e-5)  # the run's air is the log's (4 decimals written)
    exact = RATE * (t - TAU * (1.0 - np.exp(-t / TAU)))
    rise = block - 20.0
    assert rise[-1] == pytest.approx(exact[-1], rel=0.01)
    # within 1 % of the response throughout, and of the rise itself once the first 1200 s have passed:
    # early on the rise is r t^2 / (2 tau), and implicit Euler's is r t (t + dt) / (2 tau), dt / t above it
    assert np.max(np.abs(rise - exact)) <= 0.01 * exact[-1]
    later = t >= 1200.0
    assert np.max(np.abs(rise[later] / exact[later] - 1.0)) <= 0.01
    # the block lags the air by about tau at the end: (T_air - T) -> r tau
    assert air[-1] - block[-1] == pytest.approx(RATE * TAU * (1.0 - math.exp(-t[-1] / TAU)), rel=0.01)
