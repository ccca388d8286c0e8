r"""A steel pin fin heated from its held base, through the command line (``cases/pin_fin_steel.toml``).

The pin: L = 0.1 m, D = 10 mm, k = 50 W/(m·K), ρc = 7850 · 460 J/(m³·K), h = 25 W/(m²·K) on its side
and tip to air at 20 °C; at t = 0 the pin is at 20 °C and its base is held at 100 °C (θ₀ = 80 K).
Bi = h (D/4)/k = 1.3e-3: one-dimensional.  With θ = T − T_air, P = πD, A = πD²/4,

    ∂θ/∂t = α ∂²θ/∂x² − μ θ,   α = k/(ρc) = 1.385e-5 m²/s,   μ = hP/(ρcA) = 4h/(ρcD) = 2.769e-3 1/s,
    θ(0, t) = θ₀,   −k ∂θ/∂x = h θ at x = L,   θ(x, 0) = 0.

Steady (Incropera et al., Fundamentals of Heat and Mass Transfer, Table 3.4, case A), m² = hP/(kA):

    θ_s(x)/θ₀ = [cosh m(L−x) + (h/mk) sinh m(L−x)] / [cosh mL + (h/mk) sinh mL],   mL = 1.414.

Transient, by separation of variables: w = θ_s − θ solves the homogeneous problem with w(0, t) = 0, the
same convective tip and w(x, 0) = θ_s(x).  Its modes are X_n = sin λ_n x with −k λ cos λL = h sin λL,
i.e. tan λ_n L = −k λ_n / h (one root in each ((n − ½)π/L, nπ/L)), orthogonal on [0, L] (a
Sturm–Liouville problem), decaying as e^{−(α λ_n² + μ) t}:

    θ(x, t) = θ_s(x) − Σ_n c_n sin(λ_n x) e^{−(α λ_n² + μ) t},   c_n = ∫ θ_s X_n dx / ∫ X_n² dx.

Worked out for the first root: k/h = 2 m, so tan 0.1λ = −2λ; near 0.1λ = π/2 the tangent is
−1/(0.1λ − π/2), so 0.1λ − π/2 ≈ 1/(2λ) ≈ 1/31.4: λ₁ ≈ 10 · (1.5708 + 0.0318) = 16.03 1/m.

The base is held by a penalty film of 1e-7 m²·K/W: in series with the fin's steady conductance it
lowers the base's steady excess by 6e-5 of it (0.005 K), within the bounds below.

Requirements (issue 57): the reduced model within 0.2 K of θ at every sensor over the first 300 s, and
never more than 0.1 K below the air while the pin is only being heated; the fast model's steady
reading within 1 % of θ_s at every sensor.  Implicit Euler's own error over the first seconds of a
held base is of the step's order (3 K at 25 mm with the standstill's 10 s steps; 0.11 K for the FE
model at 0.1 s), so the run steps at 0.1 s (``--max-step``).
"""

import csv
import math

import numpy as np
import pytest
from scipy.optimize import brentq
from scipy.special import erfc

from feedtherm.cli import main

CASE = "tests/verification/cases/pin_fin_steel.toml"
L, D, K, RHO_C, H, THETA0, T_AIR = 0.1, 0.01, 50.0, 7850.0 * 460.0, 25.0, 80.0, 20.0
ALPHA, MU = K / RHO_C, 4.0 * H / (RHO_C * D)
M = math.sqrt(4.0 * H / (K * D))
SENSORS = {"quarter": 0.025, "mid": 0.05, "three_quarter": 0.075, "tip": 0.1}
MODES = 300


def steady(x):
    r = H / (M * K)
    return THETA0 * (np.cosh(M * (L - x)) + r * np.sinh(M * (L - x))) / (math.cosh(M * L) + r * math.sinh(M * L))


def roots(n: int = MODES) -> np.ndarray:
    """λ_n of tan λL = −kλ/h, the n-th in ((n − ½)π/L, nπ/L)."""
    f = lambda lam: H * math.sin(lam * L) + K * lam * math.cos(lam * L)  # noqa: E731
    return np.array([brentq(f, (i - 0.5) * math.pi / L + 1e-12, i * math.pi / L - 1e-12) for i in range(1, n + 1)])


def series(x: float, t: np.ndarray) -> np.ndarray:
    lam = roots()
    grid = np.linspace(0.0, L, 20001)
    modes = np.sin(np.outer(lam, grid))
    c = np.trapezoid(steady(grid) * modes, grid, axis=1) / np.trapezoid(modes**2, grid, axis=1)
    decay = np.exp(-np.outer(ALPHA * lam**2 + MU, t))
    return steady(x) - (c * np.sin(lam * x)) @ decay


def run(tmp_path, *args) -> dict[str, np.ndarray]:
    out = tmp_path / "run"
    assert main(["run", CASE, "--condition", "still_air", "--no-plots", "--out", str(out), *args]) == 0
    with open(out / "sensors.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    return {key: np.array([float(r[key]) for r in rows]) for key in rows[0]}


def test_the_worked_out_numbers():
    assert ALPHA == pytest.approx(1.385e-5, rel=1e-3) and MU == pytest.approx(2.769e-3, rel=1e-3)
    assert M * L == pytest.approx(1.414, rel=1e-3)
    assert roots(1)[0] == pytest.approx(16.03, abs=0.02)


def semi_infinite(x: float, t: float) -> float:
    """The rod heated from its held end while the tip is still far (x, √(αt) ≪ L): with the loss taken out
    as e^{−μt}, θ/θ₀ = ½ e^{−mx} erfc(x/2√(αt) − √(μt)) + ½ e^{mx} erfc(x/2√(αt) + √(μt)), m = √(μ/α)."""
    a, b = x / (2.0 * math.sqrt(ALPHA * t)), math.sqrt(MU * t)
    return THETA0 * 0.5 * (math.exp(-M * x) * erfc(a - b) + math.exp(M * x) * erfc(a + b))


def test_the_series_is_the_semi_infinite_rod_early_and_the_steady_fin_late():
    assert M == pytest.approx(math.sqrt(MU / ALPHA), rel=1e-12)
    for x in SENSORS.values():
        assert abs(series(x, np.array([1.0]))[0]) < 1e-3  # erfc(3.4) at 25 mm: nothing has arrived
        assert series(x, np.array([20000.0]))[0] == pytest.approx(steady(x), rel=1e-9)
    for t in (5.0, 10.0, 30.0):  # √(αt) ≤ 20 mm: the tip, 75 mm beyond 25 mm, is not yet felt
        assert series(0.025, np.array([t]))[0] == pytest.approx(semi_infinite(0.025, t), abs=2e-3)


def test_the_reduced_model_follows_the_heated_fin_from_its_first_seconds(tmp_path):
    got = run(tmp_path, "--model", "reduced", "--duration", "300", "--max-step", "0.1", "--sample-interval", "1")
    t = got["time_s"]
    assert t[-1] == pytest.approx(300.0) and len(t) == 301
    for name, x in SENSORS.items():
        excess = got[name] - T_AIR
        exact = series(x, t)
        exact[0] = 0.0
        assert np.max(np.abs(excess - exact)) < 0.2, name  # 0.14 K at 25 mm, 5 s (2026-11-29)
        assert excess.min() > -0.1, name  # before: 1.0 K below the air at 25 mm, 3 s


def test_the_fast_model_reads_the_steady_fin_within_1_percent_at_every_sensor(tmp_path):
    got = run(tmp_path, "--duration", "20000", "--sample-interval", "1000")  # 55 time constants 1/μ
    for name, x in SENSORS.items():
        assert got[name][-1] - T_AIR == pytest.approx(steady(x), rel=0.01), name  # before: 1.3 % at the tip
