"""The energy ledger from the files: a run's stored heat, heat in and heat lost, recomputed from
what ``feedtherm run`` writes alone (``parts.csv``, ``heat.csv`` and the parts' capacities in
``summary.json``), against the run's own energy account (``summary.json``'s ``energy_J``).

- stored: ``Σ_p C_p (T̄_p(t) − T̄_p(0))``, with T̄_p the capacity-weighted mean of parts.csv;
- in and lost: the rectangle rule over heat.csv's rows, ``Σ_{i>0} Q_i (t_i − t_{i−1})``, each row
  the mean heat over the interval since the previous one (docs/outputs.md), so the rule is exact.

Each agrees to 1e-9 (in practice 1e-12 or better), and ``in − lost − stored`` stays at round-off
row by row.  The cases: the paper bench (fast model, its nonlinear coupling: natural
convection, radiation and oil viscosities at the simulated temperatures) with the nut moving and
over a duty cycle that stops; the energy-account verification case, which has no feed drive, on
the fast, FE (coarse mesh) and reduced models, frozen and with a nonlinear coupling (its
surfaces radiating, so their coefficients follow their temperatures).  A few seconds each.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from feedtherm.cli import main

CASES = Path(__file__).resolve().parents[1] / "verification" / "cases"
TOLERANCE = 1e-9


def read_ledger(out: Path) -> dict:
    """Everything the recomputation uses, read from the files alone."""
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    parts_header = (out / "parts.csv").read_text(encoding="utf-8").splitlines()[0].split(",")
    heat_header = (out / "heat.csv").read_text(encoding="utf-8").splitlines()[0].split(",")
    parts = np.loadtxt(out / "parts.csv", delimiter=",", skiprows=1, ndmin=2)
    heat = np.loadtxt(out / "heat.csv", delimiter=",", skiprows=1, ndmin=2)
    return {"summary": summary, "parts_header": parts_header, "heat_header": heat_header, "parts": parts,
            "heat": heat}


def recomputed(ledger: dict) -> dict[str, np.ndarray]:
    """Heat stored, in and lost since the start [J] at every row, from the files."""
    capacity = ledger["summary"]["ledger"]["part_capacity_J_per_K"]
    parts, heat = ledger["parts"], ledger["heat"]
    names = ledger["parts_header"][1:]
    assert sorted(names) == sorted(capacity)
    C = np.array([capacity[name] for name in names])
    stored = (parts[:, 1:] - parts[0, 1:]) @ C
    np.testing.assert_array_equal(parts[:, 0], heat[:, 0])  # the same rows
    dt = np.diff(heat[:, 0])
    heat_in = np.concatenate([[0.0], np.cumsum(heat[1:, 1:-1].sum(axis=1) * dt)])
    lost = np.concatenate([[0.0], np.cumsum(heat[1:, -1] * dt)])
    return {"heat_stored": stored, "heat_in": heat_in, "heat_lost": lost}


def assert_the_ledger_closes(out: Path) -> dict:
    ledger = read_ledger(out)
    summary = ledger["summary"]
    assert ledger["heat_header"][-1] == "lost"
    assert summary["ledger"]["files"]["heat.csv"]["columns"] == ledger["heat_header"]
    assert summary["ledger"]["files"]["parts.csv"]["columns"] == ledger["parts_header"]
    energy = summary["energy_J"]
    terms = recomputed(ledger)
    for name, series in terms.items():
        assert series[-1] == pytest.approx(energy[name], rel=TOLERANCE), name
    # the account at every row: what came in, less what was lost, is what is stored
    scale = max(abs(energy["heat_in"]), abs(energy["heat_lost"]) + abs(energy["heat_stored"]))
    residual = terms["heat_in"] - terms["heat_lost"] - terms["heat_stored"]
    assert np.max(np.abs(residual)) < TOLERANCE * scale
    assert energy["heat_stored"] > 0.05 * energy["heat_in"]  # a real share of the heat is stored
    return ledger


def run(tmp_path: Path, *args: str) -> Path:
    out = tmp_path / "run"
    assert main(["run", *args, "--no-plots", "--out", str(out)]) == 0
    return out


def test_the_paper_bench_with_the_nut_moving(tmp_path):
    """Resolved motion: the nut's heat enters where it is, the parts under it change step by step."""
    out = run(tmp_path, "paper", "--condition", "I", "--duration", "900", "--sample-interval", "30")
    ledger = assert_the_ledger_closes(out)
    assert ledger["summary"]["model"] == "fast"
    assert len(ledger["parts_header"]) == 16 and len(ledger["heat_header"]) == 9  # 15 parts, 7 sources
    # the coupled heats follow the temperatures: the nut bearing's oil thins as it warms, the
    # motors' windings' resistance grows
    heat, header = ledger["heat"], ledger["heat_header"]
    assert heat[-1, header.index("nut_bearing")] < 0.99 * heat[1, header.index("nut_bearing")]
    assert heat[-1, header.index("screw_motor")] > 1.01 * heat[1, header.index("screw_motor")]


def test_the_paper_bench_over_a_duty_cycle_that_stops(tmp_path):
    """Two hours of condition I, one of standstill (cycle-averaged motion): the heats change at the
    segments' boundary, within a row's interval as well."""
    out = run(tmp_path, "paper", "--cycle", "I_then_standstill", "--motion", "averaged",
              "--sample-interval", "700")
    ledger = assert_the_ledger_closes(out)
    heat, header = ledger["heat"], ledger["heat_header"]
    motor = heat[:, header.index("screw_motor")]
    assert motor[1] > 1.0 and motor[-1] == 0.0  # the motor stops
    straddles = (heat[:-1, 0] < 7200.0) & (heat[1:, 0] > 7200.0)  # a row's interval holds the stop
    assert straddles.any()
    assert 0.0 < motor[1:][straddles][0] < motor[1]


def coupled_case(tmp_path: Path) -> Path:
    """The verification case, coupled: both surfaces radiate (ε = 0.8), their coefficients evaluated at
    their own temperatures as the run goes."""
    text = (CASES / "energy_ledger.toml").read_text(encoding="utf-8")
    assert text.count("emissivity = 0\n") == 2 and 'convection_delta_t = "1 K"\n' in text
    text = text.replace("emissivity = 0\n", "emissivity = 0.8\n")
    text = text.replace('convection_delta_t = "1 K"\n', 'convection_delta_t = "1 K"\ncoupling = "nonlinear"\n')
    path = tmp_path / "energy_ledger_coupled.toml"
    path.write_text(text, encoding="utf-8")
    return path


@pytest.mark.parametrize("coupling", ["frozen", "nonlinear"])
@pytest.mark.parametrize("model", ["fast", "fem", "reduced"])
def test_a_system_without_a_feed_drive_on_every_model(tmp_path, model, coupling):
    case = CASES / "energy_ledger.toml" if coupling == "frozen" else coupled_case(tmp_path)
    mesh = [] if model == "fast" else ["--mesh", "coarse"]
    out = run(tmp_path, str(case), "--condition", "heating", "--model", model, *mesh, "--sample-interval", "60")
    ledger = assert_the_ledger_closes(out)
    summary = ledger["summary"]
    assert summary["model"] == model
    assert ledger["heat_header"] == ["time_s", "ring", "lost"]
    assert ledger["parts_header"] == ["time_s", "shaft", "ring"]
    np.testing.assert_array_equal(ledger["heat"][:, 1], 10.0)  # the fixed 10 W source, every row
    assert summary["energy_J"]["heat_in"] == pytest.approx(10.0 * 1200.0, rel=1e-12)
    # ρcV of the parts: steel's 7800 kg/m³ × 461.5 J/(kg·K) times the volume the model meshes
    rho_c = 7800.0 * 461.5
    shaft = np.pi / 4 * 0.020**2 * 0.1
    ring = np.pi / 4 * (0.040**2 - 0.020**2) * 0.040
    capacity = summary["ledger"]["part_capacity_J_per_K"]
    assert capacity["shaft"] == pytest.approx(rho_c * shaft, rel=0.02)  # a tetrahedral mesh's facets: about 1 %
    assert capacity["ring"] == pytest.approx(rho_c * ring, rel=0.02)
    lost = ledger["heat"][1:, -1]
    if coupling == "nonlinear":
        # radiation grows faster than the rise: the coupled run loses more than the frozen one would
        assert lost[-1] > 0.0 and np.all(np.diff(lost) > 0.0)
