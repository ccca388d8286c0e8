"""The integrator's direct branch: reused elimination orders, step matrices, and the time loop's
per-step kernels checked against implicit Euler written out plainly; the samples' readings, and
where its conjugate gradients start."""

import numpy as np
import pytest
import scipy.sparse as sp
from scipy.sparse.linalg import spsolve

from feedtherm.models.direct import EliminationOrder, _OrderedLU, factorize
from feedtherm.models.integrator import Integrator, PositionPath, operator_sum
from feedtherm.plan import plan_run


def spd(n: int, seed: int, extra: float = 0.0) -> sp.csr_matrix:
    """A symmetric, diagonally dominant conductance-like matrix with a 2D grid's pattern."""
    rng = np.random.default_rng(seed)
    side = int(np.sqrt(n))
    grid = sp.diags([1.0, 1.0], [1, side], shape=(n, n))
    weights = sp.triu(grid, format="csr")
    weights.data = rng.uniform(0.5, 2.0, weights.nnz)
    W = weights + weights.T
    return (sp.diags(np.asarray(W.sum(axis=1)).ravel() + 0.1 + extra) - W).tocsr()


def test_a_reused_order_gives_the_same_solution_and_fill_as_a_fresh_ordering():
    first, second = spd(400, 1), spd(400, 1) + sp.diags(np.linspace(0.0, 3.0, 400))  # same pattern, new values
    fresh = factorize(first)
    order = EliminationOrder(fresh)
    reused = factorize(second, order)
    assert isinstance(reused, _OrderedLU)
    b = np.random.default_rng(2).normal(size=400)
    np.testing.assert_allclose(reused.solve(b), spsolve(second.tocsc(), b), rtol=1e-12, atol=1e-12)
    assert reused._lu.L.nnz == factorize(second).L.nnz  # the same fill as ordering it anew


def test_an_order_permutes_a_matrix_of_its_pattern_as_indexing_does():
    A = spd(225, 3)
    order = EliminationOrder(factorize(A))
    B = (A + sp.diags(np.arange(225.0))).tocsr()
    expected = B[order.order][:, order.order].toarray()
    np.testing.assert_array_equal(order.permute(B).toarray(), expected)


def test_operator_sum_adds_diagonals_to_a_sparse_matrix():
    A = spd(100, 4)
    d1, d2 = np.linspace(1.0, 2.0, 100), np.linspace(-0.5, 0.5, 100)
    np.testing.assert_allclose(operator_sum(A, d1, d2).toarray(), A.toarray() + np.diag(d1 + d2), rtol=1e-15)
    missing = sp.csr_matrix(np.triu(np.ones((5, 5)), 1))  # no diagonal stored: added, not gathered
    np.testing.assert_allclose(operator_sum(missing, np.ones(5)).toarray(), missing.toarray() + np.eye(5))
    dense = np.eye(3)
    np.testing.assert_allclose(operator_sum(dense, np.ones(3)), 2.0 * np.eye(3))


def test_a_position_is_factorised_with_its_order_once_known(paper):
    plan = plan_run(paper, condition="I", duration=60.0)
    model = plan.model.build(paper.system, plan.options)
    integrator = Integrator(model, plan.options, None)
    bc = plan.segments[0].bc
    first = integrator.factors(0, bc, 4, 1.5)
    again = integrator.factors(0, bc, 4, 0.5)  # another dt: the same pattern
    assert not isinstance(first, _OrderedLU) and isinstance(again, _OrderedLU)
    A = integrator._step_matrix(0, bc, 4, 0.5)
    b = model.capacity * 300.0
    np.testing.assert_allclose(again.solve(b), spsolve(A.tocsc(), b), rtol=1e-11)


@pytest.mark.parametrize("motion", ["resolved", "averaged"])
def test_the_time_loop_is_implicit_euler_written_out(paper, motion):
    """An uncoupled run of the fast model against the step equations of the integrator's notes,
    solved step by step from freshly assembled matrices."""
    plan = plan_run(paper, condition="I", duration=600.0, motion=motion)
    model = plan.model.build(paper.system, plan.options)
    integrator = Integrator(model, plan.options, None)
    seg = plan.segments[0]
    T0 = model.uniform_state(293.15)
    trace = integrator.run(plan.segments, T0, np.array([0.0, 600.0]))

    dt, cells = integrator._step(seg)
    path, T, t, heat_lost = PositionPath(len(model.positions)), T0.copy(), 0.0, 0.0
    while t < seg.t1 - 1e-9:
        step = min(dt, seg.t1 - t)
        path.advance(cells * step / dt)
        k = None if motion == "averaged" else path.k
        G = model.conductance(k) if k is not None else integrator.conductance(None)
        links, sink_heat = model._links(seg.bc, k)
        A = (G + sp.diags(model.capacity / step + links)).tocsc()
        T = spsolve(A, model.capacity / step * T + model.heat_vector(seg.bc, k) + sink_heat)
        heat_lost += (links @ T - sink_heat.sum()) * step
        t += step
    assert len(trace.step_end) == round(600.0 / dt)
    np.testing.assert_allclose(trace.final_state, T, rtol=0.0, atol=1e-9)
    assert trace.heat_lost == pytest.approx(heat_lost, rel=1e-10)
    assert trace.heat_in == pytest.approx(seg.bc.total_heat * 600.0, rel=1e-12)


def test_the_sample_readings_taken_in_blocks_are_each_sample_states_readings(paper, monkeypatch):
    """The screw profile, the displacements and the part means of the samples are read a block of
    states at a time: a block that fills several times and a last one left part-full give each
    sample's readings of its own state (every sample is kept as a snapshot here to compare)."""
    from dataclasses import replace

    import feedtherm.models.integrator as integrator_module

    plan = plan_run(paper, condition="I", duration=600.0)
    options = replace(plan.options, snapshot_interval=0.0)
    model = plan.model.build(paper.system, options)
    monkeypatch.setattr(integrator_module, "SAMPLE_BLOCK_ENTRIES", 4 * model.n_nodes)
    times = np.arange(0.0, 601.0, 10.0)  # 61 samples: 15 full blocks of 4 and one of 1
    trace = Integrator(model, options, None).run(plan.segments, model.uniform_state(293.15), times)
    states = [state for _, state, _ in trace.snapshots]
    assert len(states) == len(trace.sample_screw) == len(trace.sample_displacement) == len(trace.sample_parts) == 61
    for state, screw, displacement, parts in zip(states, trace.sample_screw, trace.sample_displacement,
                                                 trace.sample_parts):
        np.testing.assert_allclose(screw, model.screw_mean(state), rtol=1e-13)
        np.testing.assert_allclose(displacement, model.displacements(state), rtol=1e-12, atol=1e-15)  # [m]
        assert parts == pytest.approx({p: float(v) for p, v in model.part_means(state).items()}, rel=1e-13)
    assert np.ptp(np.array(trace.sample_displacement)[:, 0]) > 0.0  # D moves: the samples are not one state


def test_step_matrices_are_keyed_by_the_surface_coefficients_so_equal_links_share_a_factorisation(paper):
    """A full-state model's ambient operator carries its coefficients as its key: boundary conditions
    that differ only in a sink temperature (the links are the same) share a position's factors,
    a changed coefficient gets its own."""
    from dataclasses import replace

    plan = plan_run(paper, condition="I", duration=60.0)
    model = plan.model.build(paper.system, plan.options)
    integrator = Integrator(model, plan.options, None)
    bc = plan.segments[0].bc
    name = next(iter(bc.surfaces))
    surface = bc.surfaces[name]
    warmer_sink = replace(bc, surfaces={**bc.surfaces, name: replace(surface, sink=surface.sink + 5.0)})
    more_convection = replace(bc, surfaces={**bc.surfaces, name: replace(surface, convection=2.0 * surface.convection)})
    h = model.boundary_basis(4).coefficients(bc)[0]
    assert model.ambient_coupling(bc, 4).key == h.tobytes() == model.ambient_coupling(warmer_sink, 4).key
    np.testing.assert_array_equal(model.ambient_coupling(bc, 4).matrix, model.ambient_coupling(warmer_sink, 4).matrix)
    first = integrator.factors(0, bc, 4, 1.5)
    assert integrator.factors(1, warmer_sink, 4, 1.5) is first
    other = integrator.factors(2, more_convection, 4, 1.5)
    assert other is not first
    A = integrator._step_matrix(2, more_convection, 4, 1.5)
    b = model.capacity * 300.0
    np.testing.assert_allclose(other.solve(b), spsolve(A.tocsc(), b), rtol=1e-11)


@pytest.mark.parametrize("max_step, kept", [(30.0, True), (0.7, False)])
def test_cg_steps_keep_increments_only_where_the_phases_of_the_stroke_recur(paper, monkeypatch, max_step, kept):
    """Conjugate gradients start from earlier cycles' increments where a step advances the nut by
    whole grid cells; a step capped below that (a slow table) advances it by a fraction, its phases
    need not recur, and keeping an increment for each would grow without bound: none is kept."""
    from dataclasses import replace

    from feedtherm.models.iterative import IncrementHistory

    phases = set()
    plain_record = IncrementHistory.record
    monkeypatch.setattr(IncrementHistory, "record",
                        lambda self, phase, increment: (phases.add(phase), plain_record(self, phase, increment)))
    plan = plan_run(paper, condition="I", duration=300.0, solver="cg")
    options = replace(plan.options, max_step=max_step)
    model = plan.model.build(paper.system, options)
    integrator = Integrator(model, options, None)
    assert not integrator.direct
    trace = integrator.run(plan.segments, model.uniform_state(293.15), np.array([0.0, 300.0]))
    if kept:
        cells = integrator._step(plan.segments[0])[1]
        assert cells >= 1.0 and cells.is_integer()
        assert len(phases) == 20 * 2  # 20 steps a stroke, each way
    else:
        assert 0.0 < integrator._step(plan.segments[0])[1] < 1.0
        assert not phases
    assert len(trace.step_end) > 100


def test_conjugate_gradients_start_from_the_increments_of_earlier_cycles(paper, monkeypatch):
    """A step at a phase of the stroke starts from the increments of the last two steps at that phase
    (models/iterative.py, *Where the iterations start*).  From the cycle-averaged steady state the
    resolved field settles into its cycle over many cycles: by the ninth the steps need less than
    half the iterations they need from the extrapolated states, for the same transient.  The fast
    model stepped by conjugate gradients shows it as the FE model does (benchmarks/study_cg_guess.py)."""
    from feedtherm.models.iterative import IncrementHistory
    from feedtherm.simulate import simulate

    plain_solve = Integrator.solve

    def run() -> tuple:
        counts = []

        def counted(self, *args):
            before = self.cg_iterations
            state = plain_solve(self, *args)
            counts.append(self.cg_iterations - before)
            return state

        monkeypatch.setattr(Integrator, "solve", counted)
        solution = simulate(paper, condition="I", duration=600.0, sample_interval=10.0, start="steady", solver="cg")
        assert solution.info["solver"].startswith("cg")
        assert len(counts) == 360  # nine cycles of 40 steps
        return solution, sum(counts[-80:])  # the last two cycles

    cycles, late = run()
    monkeypatch.setattr(IncrementHistory, "guess", lambda self, phase, start, fallback: fallback)
    extrapolated, late_extrapolated = run()
    assert late < 0.6 * late_extrapolated, (late, late_extrapolated)
    for name in ["T1", "T2", "T3", "T4", "T5"]:
        assert cycles.sensors[name] == pytest.approx(extrapolated.sensors[name], abs=1e-4), name
    assert cycles.elongation == pytest.approx(extrapolated.elongation, abs=1e-10)
    assert abs(cycles.energy.relative_error) < 1e-4
