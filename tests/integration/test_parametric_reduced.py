"""The parametric reduced model (models/reduced/training.py, projection.py, store.py): one projection
for every description that differs from it only in its conductivities, contact resistances,
fixed coefficients and expansions, within the ranges the description declares.

Checked here: the FE model's operators are exactly linear in those numbers; a projection weighs
its terms by another description's values exactly as that description's own full model
projected onto the same basis; the training domain is the declared ranges; a description
inside the domain runs on the cached projection, one outside builds its own; and, against the
FE model itself, random points of the declared ranges on the coarse mesh
(benchmarks/bench_parametric.py does the same on the medium mesh).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from feedtherm.analysis.calibration import CALIBRATION_OPTIONS
from feedtherm.analysis.uncertainty.declared import resolve_uncertainties, variant
from feedtherm.analysis.uncertainty.sampling import to_values
from feedtherm.models import registry
from feedtherm.models.fem.bench import FemDiscretization
from feedtherm.models.interface import cycle_weights
from feedtherm.models.options import ModelOptions
from feedtherm.models.reduced import ProjectedModel, moment_basis, project, training
from feedtherm.models.reduced.training import declared_domain, inside, training_points
from feedtherm.simulate import execute, plan_run
from feedtherm.system.variants import with_values

SENSORS = ["T1", "T2", "T3", "T4", "T5"]
#: The coarse mesh with 5 positions of the moving group, not 41: a basis is trained at several points,
#: each a few factorisations per shift, and the checks here do not depend on the number of positions.
FEW_POSITIONS = {"mesh": "coarse", "axial_cells": 10, "steps_per_stroke": 4}


@pytest.fixture(scope="module")
def fem(paper):
    return FemDiscretization(paper.system, "coarse", axial_cells=10, min_positions=4)


@pytest.fixture(scope="module")
def other(paper):
    """The paper's bench with other numbers the projection takes as parameters (a sliding joint among them)."""
    return with_values(paper, {"materials.q345b.conductivity": 41.0, "joints[6].tcr": 4e-4, "joints[10].tcr": 5e-3,
                               "materials.gcr15.expansion": 1.28e-5, "materials.q345b.expansion": 1.15e-5})


def test_the_fe_operators_are_linear_in_the_affine_parameters(fem):
    parameters = fem.affine_parameters()
    kinds = {p.kind for p in parameters}
    assert kinds == {"conductance", "expansion"}
    assert {p.name for p in parameters if p.moves} == {"joints[6].conductance", "joints[7].conductance"}  # the sliding joints
    for k in range(len(fem.positions)):
        total = sum(p.value * fem.conductance_term(p.name, k) for p in parameters if p.kind == "conductance")
        assert abs(total - fem.conductance(k)).max() <= 1e-12 * abs(fem.conductance(k)).max()
    rows, offsets = fem.displacement_rows()
    terms = [(p.value, fem.displacement_term(p.name)) for p in parameters if p.kind == "expansion"]
    assert np.allclose(sum(a * t[0] for a, t in terms), rows, rtol=0.0, atol=1e-12 * np.abs(rows).max())
    assert np.allclose(sum(a * t[1] for a, t in terms), offsets, rtol=0.0, atol=1e-12 * np.abs(offsets).max())


def test_a_projection_takes_another_descriptions_numbers_as_its_own_full_model_would(paper, fem, other):
    basis = moment_basis(fem, tolerance=1e-2, use_cache=False)  # any basis: the check is the projection
    projection = project(fem, basis)
    theirs = project(FemDiscretization(other.system, "coarse", axial_cells=10, min_positions=4), basis)
    model = ProjectedModel.from_projection(projection, other.system, lambda: None)
    assert model.expansion_changed
    for k in range(len(fem.positions)):
        assert np.allclose(model.conductance(k), theirs.conductance[k], rtol=0.0,
                           atol=1e-12 * np.abs(theirs.conductance[k]).max())
        rows, offsets = model._probe_rows(k)
        assert np.allclose(rows, theirs.probe_rows[k], rtol=0.0, atol=1e-12 * np.abs(theirs.probe_rows[k]).max())
        assert np.allclose(offsets, theirs.probe_offsets[k], rtol=0.0, atol=1e-12 * np.abs(theirs.probe_offsets[k]).max())
    # the cycle average a cycle-averaged run steps with, formed from the projection's averages and the
    # terms, is the average of the positions' operators (a fresh model: none of them formed yet)
    fresh = ProjectedModel.from_projection(projection, other.system, lambda: None)
    averaged = fresh.averaged_conductance()
    assert not fresh._at_position  # without forming a position's operator
    by_positions = sum(w * theirs.conductance[k] for k, w in enumerate(cycle_weights(len(fem.positions))))
    assert np.allclose(averaged, by_positions, rtol=0.0, atol=1e-12 * np.abs(by_positions).max())
    rows, offsets = model.displacement_rows()
    assert np.allclose(rows, theirs.displacement_rows, rtol=0.0, atol=1e-12 * np.abs(rows).max())
    assert np.allclose(offsets, theirs.displacement_offsets, rtol=0.0, atol=1e-12 * np.abs(offsets).max())
    # at its own description the projection is what it was
    own = ProjectedModel.from_projection(projection, paper.system, lambda: None)
    assert own._conductance is projection.conductance and not own.expansion_changed


def test_the_training_domain_is_what_the_description_declares(paper):
    names = ["materials.q345b.conductivity", "materials.gcr15.conductivity", "joints[9].conductance",
             "joints[0].conductance", "surfaces.base_bottom.coefficient"]
    domain = declared_domain(paper.system, names)
    assert domain["materials.q345b.conductivity"] == (40.0, 52.0)  # [uncertainty] steel_conductivity
    assert domain["materials.gcr15.conductivity"] == (48.0, 48.0)  # nothing declares it
    # joints[9]: tcr 1.25e-3 scaled by [0.2, 5] (both tcr_bolted and calibration's tcr): 1/(5 * 1.25e-3) .. 1/(0.2 * 1.25e-3)
    assert domain["joints[9].conductance"] == pytest.approx((160.0, 4000.0))
    assert domain["joints[0].conductance"] == pytest.approx((160.0, 4000.0))  # calibration's tcr reaches every joint
    assert domain["surfaces.base_bottom.coefficient"] == (5.0, 6760.0)  # foundation
    points = training_points(domain, {})
    assert points == training_points(domain, {})  # a fixed seed: the same basis every time
    # two corners, the foundation's ends, three random points; the undeclared conductivity stays
    assert len(points) == 7 and all("materials.gcr15.conductivity" not in p for p in points)
    assert points[0] == {n: lo for n, (lo, hi) in domain.items() if hi > lo}
    assert all(inside(domain, p) for p in points)
    assert not inside(domain, {"joints[9].conductance": 4001.0}) and not inside(domain, {"unknown": 1.0})


def test_inside_the_domain_the_projection_is_reused_and_outside_another_is_built(paper, tmp_path, monkeypatch):
    monkeypatch.setenv("FEEDTHERM_CACHE", str(tmp_path))
    builds = []
    fem_factory = registry._fem

    def counted(system, options):
        builds.append(system)
        return fem_factory(system, options)

    monkeypatch.setattr(registry, "_fem", counted)
    monkeypatch.setattr(training, "RANDOM_POINTS", 0)  # the domain's logic, not the basis's accuracy: its corners only
    options = ModelOptions(reduction_tolerance=1e-3, **FEW_POSITIONS)
    # a description with one declared range only, so that the basis trains on its two corners
    narrow = paper.system.model_copy(update={"calibration": None, "uncertainty": None})
    narrow = narrow.model_copy(update={"uncertainty": paper.system.uncertainty.model_copy(update={
        "parameters": {"tcr_bolted": paper.system.uncertainty.parameters["tcr_bolted"]}})})
    first = registry.build_model("reduced", narrow, options)
    assert len(builds) == 1 and not first.stats["projection_cached"]
    domain = first.projection.domain
    assert domain["joints[9].conductance"] == pytest.approx((160.0, 4000.0))
    assert domain["joints[0].conductance"] == (800.0, 800.0)  # only the bolted joints are declared
    assert domain["materials.gcr15.expansion"] == (0.0, math.inf)  # the displacements are linear in it
    within = narrow.model_copy(update={"joints": [j.model_copy(update={"tcr": j.tcr * (3.0 if i >= 9 else 1.0)})
                                                  for i, j in enumerate(narrow.joints)]})
    again = registry.build_model("reduced", within, options)
    assert len(builds) == 1 and again.stats["projection_cached"]
    assert again.projection is first.projection  # kept in memory: a batch reads the file once
    assert not np.allclose(again.conductance(0), first.conductance(0))
    outside = narrow.model_copy(update={"joints": [j.model_copy(update={"tcr": j.tcr * (2.0 if i == 0 else 1.0)})
                                                   for i, j in enumerate(narrow.joints)]})
    built = registry.build_model("reduced", outside, options)
    assert len(builds) == 2 and not built.stats["projection_cached"]
    assert len(list((tmp_path / "projections").glob("*.npz"))) == 2
    # both are on disk: either description finds its own
    assert registry.build_model("reduced", within, options).stats["projection_cached"]
    assert registry.build_model("reduced", outside, options).stats["projection_cached"]
    assert len(builds) == 2


def test_the_check_compares_with_the_full_model_where_the_residual_indicator_is_largest(fem):
    """A basis trained at the nominal description only: its residual is far larger where the bench's
    joints conduct ten times as well than where it was trained, and the check goes there.  (The
    residual is not round-off even where the basis was trained: the modes the POD drops are the
    stiff ones, which the operator amplifies; on the coarse mesh it ranks random points of the
    domain as their true errors do at the top, 0.21 against 0.10-0.16 for a share of 1.5 % against
    0.4-1.0 %.)"""
    from feedtherm.models.reduced.basis import residual_indicator, steady_check

    basis = moment_basis(fem, use_cache=False)
    far = {p.name: 10.0 * p.value for p in fem.affine_parameters() if p.name.startswith("joints[")}
    at_home, away = residual_indicator(fem, basis, {}), residual_indicator(fem, basis, far)
    assert away > 10.0 * at_home
    check = steady_check(fem, basis, ({}, far, {}), checked=1)
    assert check["steady_check_point"] == 1 and check["steady_check_points"] == 1
    assert check["steady_check_candidates"] == 3 and check["steady_check_indicator"] == pytest.approx(away)
    assert check["steady_check_share"] > 0.01  # the nominal basis misses the far point's answers
    assert steady_check(fem, basis, ({}, far), checked=2)["steady_check_share"] == check["steady_check_share"]


def test_the_checks_reduced_operators_are_the_points_operators_projected(fem):
    """The steady check weighs projected terms (``VᵀA(θ)V`` as an affine sum) where projecting each
    candidate's operator afresh costs a product with the whole mesh: the same matrix, at a point
    that changes a sliding joint (a moving term), a bolted joint, a material and a fixed coefficient."""
    from feedtherm.models.reduced.basis import TrainingOperators, _ProjectedSteadyOperator, _steady_operator

    V = np.linalg.qr(np.random.default_rng(3).standard_normal((fem.n_nodes, 40)))[0]
    values = {p.name: p.value for p in fem.affine_parameters()}
    point = {"joints[6].conductance": 3.0 * values["joints[6].conductance"],
             "joints[9].conductance": 0.5 * values["joints[9].conductance"],
             "materials.q345b.conductivity": 41.0, "surfaces.base_bottom.coefficient": 25.0}
    projected = _ProjectedSteadyOperator(fem, V)
    for at in (point, {}, {"surfaces.base_bottom.coefficient": 4000.0}):
        direct = V.T @ (_steady_operator(fem, at) @ V)
        reduced = projected.at(TrainingOperators(fem, at))
        assert np.allclose(reduced, direct, rtol=0.0, atol=1e-12 * np.abs(direct).max()), at


def test_the_reduced_model_follows_the_fe_model_at_random_points_of_the_declared_ranges(paper, tmp_path, monkeypatch):
    """Condition I over 3 h, the runs of calibration and uncertainty (cycle-averaged, 60 s steps), at
    three points drawn from every declared distribution, on the projection of the nominal bench."""
    monkeypatch.setenv("FEEDTHERM_CACHE", str(tmp_path))
    options = replace(CALIBRATION_OPTIONS, **FEW_POSITIONS)
    nominal = registry.build_model("reduced", paper.system, options)
    assert len(nominal.positions) == 5
    assert nominal.basis.snapshots > 400  # trained at eight points, not at the nominal description's alone
    # checked against the full model's steady answers at the two of 16 points where it was not
    # trained whose residuals are largest (2.3 % of an answer's range at worst when written at two
    # random points; the nominal basis alone: 63 %)
    assert nominal.stats["steady_check_points"] == 2 and nominal.stats["steady_check_candidates"] == 16
    assert nominal.stats["steady_check_share"] < 0.05
    prior = resolve_uncertainties(paper)
    points = to_values(prior, np.random.default_rng(7).random((3, len(prior))))
    for i, x in enumerate(points):
        point = variant(paper, prior, x, f"point {i}")
        runs = [execute(plan_run(point, condition="I", model=name, options=options, sample_interval=60.0,
                                 allow_overload=True)) for name in ("reduced", "fem")]
        reduced, full = runs
        assert reduced.info["mesh_statistics"]["projection_cached"]
        for name in SENSORS:
            assert np.max(np.abs(reduced.sensors[name] - full.sensors[name])) <= 0.1, (i, name)
        assert np.max(np.abs(reduced.elongation - full.elongation)) <= 0.2e-6, i


def test_a_batch_prepares_a_model_that_keeps_its_builds_once_and_no_other(paper, monkeypatch):
    from feedtherm.models.registry import ModelEntry, register_model, unregister_model
    from feedtherm.simulate import prepare

    built = []
    for name, prepares in (("kept", True), ("not-kept", False)):
        register_model(ModelEntry(name, "a test's", lambda system, options, name=name: built.append(
            (name, options.mesh)) or FemDiscretization(system, "coarse"), uses_mesh=True, prepares=prepares))
    try:
        prepare(paper.system, "kept", "medium")
        prepare(paper.system, "not-kept", "medium")
        prepare(paper.system, "fast")
    finally:
        unregister_model("kept")
        unregister_model("not-kept")
    assert built == [("kept", "medium")]
    assert registry.model_entry("reduced").prepares and not registry.model_entry("fem").prepares
