"""The reduced model (models/reduced): a projection that keeps the full model's answers.

The projections are checked against the full operators multiplied out directly, the basis
against its definition, and the runs against the full model's own run of the same plan.
The fast model serves as the full model where the check is about the projection (it is
built in a second); ``--model reduced`` on the FE model itself, its files and its cache are
checked in ``test_cli_run_fields.py``, on one build.
"""

from __future__ import annotations

import os
from dataclasses import replace

import numpy as np
import pytest
import scipy.sparse as sp

from feedtherm.boundary import boundary_conditions
from feedtherm.models import registry
from feedtherm.models.reduced import ProjectedModel, moment_basis
from feedtherm.models.integrator import Integrator
from feedtherm.models.reduced import basis as basis_module
from feedtherm.models.reduced.basis import inputs, reference_coefficients, split_inputs
from feedtherm.models.reduced.disk import prune
from feedtherm.simulate import execute, plan_run

DURATION = 1800.0  # [s]: the nut's warm-up, where the moving heat matters most


@pytest.fixture(scope="module")
def plan(paper):
    return plan_run(paper, condition="I", duration=DURATION)


@pytest.fixture(scope="module")
def full(plan, paper):
    return plan.model.build(paper.system, plan.options)


@pytest.fixture(scope="module")
def reduced(full):
    return ProjectedModel(full, moment_basis(full, tolerance=1e-4))


@pytest.fixture(scope="module")
def runs(plan, full, reduced):
    return execute(plan, model=full), execute(plan, model=reduced)


def test_the_basis_is_capacity_orthonormal_and_starts_with_the_uniform_state(full, reduced):
    V, C = reduced.V, np.asarray(full.capacity)
    assert np.allclose(V.T @ (C[:, None] * V), np.eye(V.shape[1]), atol=1e-9)
    assert np.allclose(V[:, 0], V[0, 0]) and V[0, 0] > 0.0
    # so a uniform state is represented exactly
    T = reduced.full_state(reduced.uniform_state(293.15))
    assert np.allclose(T, 293.15, rtol=0.0, atol=1e-9)


def test_the_basis_size_follows_the_tolerance(full, reduced):
    coarse = moment_basis(full, tolerance=1e-2)
    assert coarse.size < reduced.basis.size
    # every kept singular value is above the tolerance times the largest, the dropped ones below
    s = coarse.singular_values
    assert s.min() >= 1e-2 * s.max() and coarse.size == s.size + 1  # + the uniform state


def test_the_snapshots_take_a_fixed_coefficient_as_declared_and_the_reference_elsewhere(full, paper):
    # as the model's links take them: in series with its conduction from the nodes to the face
    basis = full.boundary_basis(0)
    surfaces = basis.surfaces
    h = reference_coefficients(full)
    film = np.zeros(len(surfaces)) if basis.film is None else basis.film
    for name, value, r in zip(surfaces, h, film):
        convection = paper.system.surfaces[name].convection
        expected = convection.coefficient if convection.kind == "fixed" else basis_module.REFERENCE_HTC
        assert value == pytest.approx(expected / (1.0 + expected * r), rel=1e-12), name
    # the paper bench's foundation, 800 W/(m²·K) as declared, behind the base's half cell
    assert paper.system.surfaces["base_bottom"].convection.coefficient == pytest.approx(800.0)
    assert 0.0 < h[surfaces.index("base_bottom")] < 800.0


def _projected_error(full, V, state) -> np.ndarray:
    """|probe(P T) - probe(T)| with P the capacity-orthogonal projection onto V."""
    C = np.asarray(full.capacity)
    return np.abs(full.probe(V @ (V.T @ (C * state)), 0) - full.probe(state, 0))


def test_the_basis_spans_the_steady_state_of_a_condition(full, reduced, plan):
    # With 10 W/(m²·K) on the foundation (800 declared) while the snapshots were taken, the
    # best approximation of this state missed T1 by 0.12 K on the coarse FE mesh.
    steady = Integrator(full, plan.options, None).steady(0, plan.segments[0].bc, None)
    error = _projected_error(full, reduced.V, steady)
    assert np.all(error[:-1] <= 0.01), dict(zip(full.probe_names, error))
    assert error[-1] <= 0.01e-6


def test_the_inputs_stay_sparse_and_split_into_fixed_and_moving(full):
    fixed, moving = split_inputs(full)
    assert sp.issparse(fixed) and all(sp.issparse(m) for m in moving)
    dense = [inputs(full, k).toarray() for k in range(len(full.positions))]
    same = np.array([all(np.array_equal(d[:, j], dense[0][:, j]) for d in dense) for j in range(dense[0].shape[1])])
    assert 0 < same.sum() < same.size  # the paper bench has both
    assert np.array_equal(fixed.toarray(), dense[0][:, same])
    for k in (0, 13, len(dense) - 1):
        assert np.array_equal(moving[k].toarray(), dense[k][:, ~same])


def test_a_basis_is_read_back_from_the_cache_for_the_same_model_only(full, tmp_path, monkeypatch):
    monkeypatch.setenv("FEEDTHERM_CACHE", str(tmp_path))
    built = moment_basis(full, tolerance=1e-3)
    again = moment_basis(full, tolerance=1e-3)
    assert not built.cached and again.cached
    assert np.array_equal(again.vectors, built.vectors) and again.snapshots == built.snapshots
    assert len(list((tmp_path / "bases").glob("*.npz"))) == 1
    # another tolerance, or a model whose operators differ, is another basis
    assert not moment_basis(full, tolerance=2e-3).cached
    monkeypatch.setattr(full, "capacity", full.capacity * 1.01)
    assert not moment_basis(full, tolerance=1e-3).cached
    assert len(list((tmp_path / "bases").glob("*.npz"))) == 3
    # a damaged file is rebuilt, not read
    monkeypatch.undo()
    monkeypatch.setenv("FEEDTHERM_CACHE", str(tmp_path))
    for path in (tmp_path / "bases").glob("*.npz"):
        path.write_bytes(b"not a basis")
    rebuilt = moment_basis(full, tolerance=1e-3)
    assert not rebuilt.cached and np.allclose(rebuilt.vectors, built.vectors)


def test_the_basis_cache_keeps_the_most_recently_used_within_its_budget(tmp_path):
    sizes = {"old": 400, "used": 300, "new": 200}
    for age, (name, size) in enumerate(sizes.items()):
        (tmp_path / f"{name}.npz").write_bytes(b"x" * size)
        os.utime(tmp_path / f"{name}.npz", (1e9 + age, 1e9 + age))
    (tmp_path / ".killed.123.partial.npz").write_bytes(b"x")
    os.utime(tmp_path / ".killed.123.partial.npz", (1e9, 1e9))
    os.utime(tmp_path / "old.npz", (2e9, 2e9))  # read back recently: used last
    prune(tmp_path, keep=tmp_path / "new.npz", budget=650)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["new.npz", "old.npz"]  # 200 + 400 ≤ 650; 300 more is not


@pytest.mark.parametrize("k", [0, 7, 20, 40])
def test_projected_operators_are_the_full_ones_multiplied_out(full, reduced, paper, k):
    V = reduced.V
    G = full.conductance(k)
    assert np.allclose(reduced.conductance(k), V.T @ (G @ V), rtol=1e-10, atol=1e-10 * np.abs(G).max())
    bc = boundary_conditions(paper.system, "I")
    full_ambient, ambient = full.ambient_coupling(bc, k), reduced.ambient_coupling(bc, k)
    links = full_ambient.matrix
    assert np.allclose(ambient.matrix, V.T @ (links[:, None] * V), rtol=1e-10, atol=1e-12)
    assert np.allclose(ambient.source, V.T @ full_ambient.source, rtol=1e-10, atol=1e-9)
    assert ambient.source_total == pytest.approx(full_ambient.source_total, rel=1e-12)
    assert np.allclose(reduced.heat_vector(bc, k), V.T @ full.heat_vector(bc, k), rtol=1e-10, atol=1e-12)


def test_the_cycle_averaged_ambient_operator_is_the_full_ones_averaged_as_the_coefficients_change(full, reduced, paper):
    """The projection's averaged exposures are one array (the moving surfaces' change added in); a
    re-evaluation weighs only the changed coefficients in, or all of them past half; the step
    matrices are keyed by the coefficients."""
    V = reduced.V
    first = boundary_conditions(paper.system, "I")
    h = reduced.projection.averaged.coefficients(first)[0]
    name = next(iter(first.surfaces))
    surface = first.surfaces[name]
    one_changed = replace(first, surfaces={**first.surfaces, name: replace(surface, convection=2.0 * surface.convection)})
    for bc in (first, one_changed, boundary_conditions(paper.system, "V"), first):
        links = full.ambient_coupling(bc, None).matrix
        ambient = reduced.ambient_coupling(bc, None)
        assert np.allclose(ambient.matrix, V.T @ (links[:, None] * V), rtol=1e-10, atol=1e-12)
        assert np.allclose(reduced.ambient_coupling(bc, 7).matrix, V.T @ (full.ambient_coupling(bc, 7).matrix[:, None] * V),
                           rtol=1e-10, atol=1e-12)
    assert ambient.key == h.tobytes() != reduced.ambient_coupling(one_changed, None).key


def test_readouts_are_the_full_models_of_the_lifted_state(full, reduced):
    z = np.random.default_rng(3).normal(size=reduced.n_nodes)
    T = reduced.full_state(z)
    assert np.allclose(reduced.probe(z, 5), full.probe(T, 5), rtol=1e-12)
    assert np.allclose(reduced.screw_mean(z), full.screw_mean(T), rtol=1e-12)
    means = full.part_means(T)
    for part, value in reduced.part_means(z).items():
        assert value == pytest.approx(float(means[part]), rel=1e-12)


def test_probes_are_projected_alike_from_the_full_models_rows_or_column_by_column(full, reduced, monkeypatch):
    rows, offset = full.probe_rows(0)
    T = np.random.default_rng(4).normal(size=full.n_nodes)
    assert np.allclose(rows @ T + offset, full.probe(T, 0), rtol=1e-14)
    from_rows = reduced._probe_rows(9)
    monkeypatch.setattr(full, "probe_rows", lambda k: None)  # a model that does not give its rows
    by_columns = ProjectedModel(full, reduced.basis)._probe_rows(9)
    assert np.allclose(from_rows[0], by_columns[0], rtol=1e-12, atol=1e-15)
    assert np.allclose(from_rows[1], by_columns[1], rtol=1e-12, atol=1e-15)


def test_a_reduced_run_follows_the_full_run(runs):
    full_run, reduced_run = runs
    for name in full_run.sensors:
        assert np.max(np.abs(reduced_run.sensors[name] - full_run.sensors[name])) <= 0.1, name
    assert np.max(np.abs(reduced_run.elongation - full_run.elongation)) <= 0.2e-6
    # the uniform state is in the basis: its Galerkin equation is the energy balance
    assert abs(reduced_run.energy.relative_error) <= 1e-9
