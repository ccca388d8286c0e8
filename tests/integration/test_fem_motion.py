"""The FE model's position-resolved and cycle-averaged motions agree at equilibrium."""

import pytest

from feedtherm.plan import plan_run
from feedtherm.simulate import execute, simulate


def test_resolved_motion_stays_at_the_cycle_averaged_steady_state(paper):
    # Start both motions from the cycle-averaged steady state (coarse mesh) and run three
    # reciprocation cycles: the resolved motion oscillates about that state and its cycle
    # mean stays on it; the averaged motion does not move at all.
    cycles = 3 * 2 * 0.200 / 0.006  # three cycles of the 200 mm stroke at 0.36 m/min = 200 s
    resolved = simulate(paper, condition="I", model="fem", mesh="coarse", duration=cycles, start="steady",
                        sample_interval=5.0)
    averaged = simulate(paper, condition="I", model="fem", mesh="coarse", duration=cycles, start="steady",
                        motion="averaged", sample_interval=5.0)
    for name in ["T1", "T2", "T3", "T4", "T5"]:
        assert averaged.final[name] == pytest.approx(averaged.steady[name], abs=1e-6)
        assert resolved.final[name] == pytest.approx(averaged.final[name], abs=0.15), name
    assert resolved.final["D"] == pytest.approx(averaged.final["D"], abs=0.3e-6)
    assert abs(resolved.energy.relative_error) < 1e-3 and abs(averaged.energy.relative_error) < 1e-3


def test_positions_beyond_the_factor_memory_follow_the_direct_run(paper, monkeypatch):
    """With --factor-memory below two factors, "auto" factorises the first position it visits and steps every
    other position by conjugate gradients: the transient of one factor per position (the coarse mesh under
    PARDISO, which it otherwise leaves to SuperLU)."""
    pytest.importorskip("pypardiso")
    from feedtherm.models import pardiso

    monkeypatch.setattr(pardiso, "MIN_UNKNOWNS", 0)
    direct = simulate(paper, condition="I", model="fem", mesh="coarse", duration=60.0, solver="direct")
    lean = execute(plan_run(paper, condition="I", model="fem", mesh="coarse", duration=60.0, factor_memory=1.0))
    assert "beyond the memory budget" in lean.info["solver"], lean.info["solver"]
    assert lean.info["cg_iterations"] > 0
    for name in ["T1", "T2", "T3", "T4", "T5"]:
        assert lean.sensors[name] == pytest.approx(direct.sensors[name], abs=1e-4), name
    assert lean.elongation == pytest.approx(direct.elongation, abs=1e-10)
    assert abs(lean.energy.relative_error) < 1e-4


def test_conjugate_gradients_follow_the_cached_lu_through_a_moving_run(paper):
    # Jacobi-preconditioned CG (the fine mesh's steps beyond the factors' memory budget, or
    # where PARDISO is missing) and one LU per position (the coarse and medium meshes): on the
    # coarse mesh both must give the same transient (moving nut, position changes at every step).
    runs = {solver: simulate(paper, condition="I", model="fem", mesh="coarse", duration=120.0, sample_interval=10.0,
                             solver=solver) for solver in ("direct", "cg")}
    assert runs["direct"].info["solver"].startswith("direct") and runs["cg"].info["solver"].startswith("cg")
    for name in ["T1", "T2", "T3", "T4", "T5"]:
        # the sensors warm by tenths of a kelvin; CG's tolerance leaves about 1e-6 K per step
        assert runs["cg"].sensors[name] == pytest.approx(runs["direct"].sensors[name], abs=1e-4), name
    assert runs["cg"].elongation == pytest.approx(runs["direct"].elongation, abs=1e-10)
    assert abs(runs["cg"].energy.relative_error) < 1e-4



def test_the_windowed_motion_follows_the_exact_one(paper):
    """The default resolved motion of the FE model steps window by window (models/windows.py): on
    the coarse mesh over the first hour of condition I it stays with the exact motion, grid
    position by grid position, within the issue's bounds (T1-T5 0.05 K, D 0.1 um) at the end and
    at every sample, with a step matrix per window instead of one per position."""
    runs = {motion: simulate(paper, condition="I", model="fem", mesh="coarse", duration=3600.0, motion=motion,
                             sample_interval=10.0) for motion in ("resolved", "exact")}
    windowed, exact = runs["resolved"], runs["exact"]
    windows = windowed.info["motion_windows"]
    assert windows["cells"] == [10] and windows["grid_cells"] == 40  # 4 windows of 50 mm (6 mm/s for 10 s: 60 mm)
    assert "motion_windows" not in exact.info
    assert windowed.info["steps"] * 5 == exact.info["steps"]  # 10 cells a step, where the exact motion takes 2
    for name in ["T1", "T2", "T3", "T4", "T5"]:
        assert windowed.final[name] == pytest.approx(exact.final[name], abs=0.05), name
        assert max(abs(windowed.sensors[name] - exact.sensors[name])) < 0.05, name
    assert windowed.final["D"] == pytest.approx(exact.final["D"], abs=0.1e-6)
    assert max(abs(windowed.elongation - exact.elongation)) < 0.1e-6
    assert abs(windowed.energy.relative_error) < 1e-4
