"""The projected-model cache (models/reduced/store.py): a run of a cached reduced model is the run of
the model it was saved from, without building the full model; its key changes with anything the
full model, its basis or its projection are built from.

The fast model serves as the full model (built in a second): the cache does not know which model
it projects.  The FE model's own path (the registry's key inputs, a cached run that never builds
the FE model) is checked at the end, on a fake mesh file for the key and in
tests/integration/test_reduced_model.py for a run.
"""

from __future__ import annotations

import numpy as np
import pytest

from feedtherm.models import registry
from feedtherm.models.options import ModelOptions
from feedtherm.models.reduced import store
from feedtherm.models.reduced.store import cached_projected_model, projection_key
from feedtherm.simulate import execute, plan_run

DURATION = 1200.0  # [s]
TOLERANCE = 1e-3  # a small basis: the check is about the cache, not the basis


@pytest.fixture(scope="module")
def plan(paper):
    return plan_run(paper, condition="I", duration=DURATION)


class Builds:
    """The full model's factory, counting its calls."""

    def __init__(self, plan):
        self.plan, self.count = plan, 0

    def __call__(self):
        self.count += 1
        return self.plan.model.build(self.plan.loaded.system, self.plan.options)


def _inputs(paper):
    return lambda: {"system": paper.system.model_dump(mode="json"), "full_model": "fast"}


def _cached(plan, paper, builds):
    return cached_projected_model(paper.system, TOLERANCE, builds, _inputs(paper))


def _assert_same_run(a, b):
    for name in a.sensors:
        np.testing.assert_allclose(b.sensors[name], a.sensors[name], rtol=0.0, atol=1e-10, err_msg=name)
    np.testing.assert_allclose(b.elongation, a.elongation, rtol=0.0, atol=1e-16)
    np.testing.assert_allclose(b.screw_temperature, a.screw_temperature, rtol=0.0, atol=1e-10)


def test_a_cached_model_runs_as_the_one_it_was_saved_from_without_building_the_full_model(plan, paper, tmp_path,
                                                                                         monkeypatch):
    monkeypatch.setenv("FEEDTHERM_CACHE", str(tmp_path))
    builds = Builds(plan)
    built = _cached(plan, paper, builds)
    assert builds.count == 1 and not built.stats["projection_cached"]
    (path,) = (tmp_path / "projections").glob("*.npz")
    cached = _cached(plan, paper, builds)
    assert builds.count == 1 and cached.stats["projection_cached"]  # read back: no full model built
    _assert_same_run(execute(plan, model=built), execute(plan, model=cached))
    assert builds.count == 1  # the run asked for nothing the projection does not hold
    # what it does not hold, it takes from the full model, built once on demand
    np.testing.assert_array_equal(cached.boundary_basis(3).exposure.toarray(),
                                  built.full.boundary_basis(3).exposure.toarray())
    cached.surface_exposure(next(iter(paper.system.surfaces)), 5)
    assert builds.count == 2
    assert path.exists() and len(list((tmp_path / "projections").glob("*.npz"))) == 1


@pytest.mark.parametrize("damage", ["garbage", "truncated", "renamed"])
def test_a_damaged_or_foreign_file_is_rebuilt(plan, paper, tmp_path, monkeypatch, damage):
    monkeypatch.setenv("FEEDTHERM_CACHE", str(tmp_path))
    builds = Builds(plan)
    reference = execute(plan, model=_cached(plan, paper, builds))
    (path,) = (tmp_path / "projections").glob("*.npz")
    if damage == "garbage":
        path.write_bytes(b"not a projection")
    elif damage == "truncated":  # a file cut short (the writes are atomic: a disk's fault, not ours)
        path.write_bytes(path.read_bytes()[: path.stat().st_size // 2])
    else:  # another model's file under this key's name
        cached_projected_model(paper.system, 2 * TOLERANCE, builds, _inputs(paper))
        (other_path,) = set((tmp_path / "projections").glob("*.npz")) - {path}
        other_path.replace(path)
    count = builds.count
    rebuilt = _cached(plan, paper, builds)
    assert builds.count == count + 1 and not rebuilt.stats["projection_cached"]
    _assert_same_run(reference, execute(plan, model=rebuilt))
    assert _cached(plan, paper, builds).stats["projection_cached"]  # the rebuilt file is read back


# ---------------------------------------------------------------------------- the key


@pytest.fixture
def fe_key(paper, tmp_path, monkeypatch):
    """The registry's key of the reduced FE model, with mesh files of our own (no meshing)."""
    from feedtherm.models.fem.geometry import mesh_cache_path

    monkeypatch.setenv("FEEDTHERM_CACHE", str(tmp_path))

    def key(system=paper.system, options=ModelOptions(), mesh_bytes=b"mesh"):
        path = mesh_cache_path(system, options.mesh)
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(mesh_bytes)
        return projection_key(registry._reduced_inputs(system, options), options.reduction_tolerance)

    return key


def _with(model, **changes):
    return model.model_copy(update=changes)


def test_the_key_changes_with_anything_the_projection_is_built_from(paper, fe_key, monkeypatch):
    system = paper.system
    base = fe_key()
    assert fe_key() == base  # the same inputs, the same key
    material = system.parts[system.kinematics.screw].material
    box = system.parts["base"].boxes[0]
    variants = {
        "a material's heat capacity": fe_key(_with(system, materials={
            **system.materials, material: _with(system.materials[material], specific_heat=500.0)})),
        "a part's geometry": fe_key(_with(system, parts={
            **system.parts, "base": _with(system.parts["base"], boxes=[_with(box, size=(1.01, *box.size[1:])),
                                                                       *system.parts["base"].boxes[1:]])})),
        "a joint's area": fe_key(_with(system, joints=[_with(system.joints[0], area=system.joints[0].area * 2),
                                                       *system.joints[1:]])),
        "the mesh file": fe_key(mesh_bytes=b"another mesh"),
        "the mesh density": fe_key(options=ModelOptions(mesh="medium")),
        "the screw's sections": fe_key(options=ModelOptions(axial_cells=120)),
        "the positions": fe_key(options=ModelOptions(steps_per_stroke=40)),
        "the tolerance": fe_key(options=ModelOptions(reduction_tolerance=2e-4)),
    }
    with monkeypatch.context() as m:
        m.setattr(store, "operator_code_digest", lambda: "another feedtherm")
        variants["the operators' code"] = fe_key()
    with monkeypatch.context() as m:
        versions = {**store.library_versions(), "scipy": "0.0"}
        m.setattr(store, "library_versions", lambda: versions)
        variants["a library's version"] = fe_key()
    for name, key in variants.items():
        assert key != base, name
    assert len(set(variants.values())) == len(variants)
    # what the full model is not built from leaves the key alone: the solver of the time steps
    assert fe_key(options=ModelOptions(solver="direct", coupling_tolerance=0.5)) == base
    # and so do the numbers the projection takes as parameters, and what only the boundary conditions read
    foundation = system.surfaces["base_bottom"]
    alike = {
        "a material's conductivity and expansion": _with(system, materials={
            **system.materials, material: _with(system.materials[material], conductivity=50.0, expansion=1.3e-5)}),
        "a joint's resistance": _with(system, joints=[_with(system.joints[0], tcr=system.joints[0].tcr * 2),
                                                      *system.joints[1:]]),
        "a fixed coefficient": _with(system, surfaces={**system.surfaces, "base_bottom": _with(
            foundation, convection=_with(foundation.convection, coefficient=100.0), chtc_factor=1.5)}),
        "a loss model's number": _with(system, sources={**system.sources, "screw_nut": _with(
            system.sources["screw_nut"], friction_coefficient=0.1)}),
        "the conditions and declared ranges": _with(system, conditions={}, uncertainty=None, calibration=None),
    }
    for name, changed in alike.items():
        assert fe_key(changed) == base, name


def test_without_its_mesh_file_the_key_waits_for_the_build(paper, tmp_path, monkeypatch):
    monkeypatch.setenv("FEEDTHERM_CACHE", str(tmp_path))
    assert registry._reduced_inputs(paper.system, ModelOptions()) is None


def test_the_code_digest_covers_the_code_that_makes_operators_only(monkeypatch, tmp_path):
    package = tmp_path / "feedtherm"
    (package / "models" / "fem").mkdir(parents=True)
    (package / "analysis").mkdir()
    (package / "models" / "fem" / "a.py").write_text("x = 1\n")
    (package / "analysis" / "b.py").write_text("y = 1\n")
    (package / "models" / "fem" / "__pycache__").mkdir()
    (package / "models" / "fem" / "__pycache__" / "a.cpython-311.pyc").write_bytes(b"compiled")
    monkeypatch.setattr(store, "_PACKAGE", package)
    digests = []
    for change in (None, "bytecode", "analysis", "code", "new module"):
        if change == "bytecode":
            (package / "models" / "fem" / "__pycache__" / "a.cpython-311.pyc").write_bytes(b"recompiled")
        elif change == "analysis":
            (package / "analysis" / "b.py").write_text("y = 2\n")
        elif change == "code":
            (package / "models" / "fem" / "a.py").write_text("x = 2\n")
        elif change == "new module":
            (package / "models" / "fem" / "c.py").write_text("")
        store.operator_code_digest.cache_clear()
        digests.append(store.operator_code_digest())
    store.operator_code_digest.cache_clear()
    assert digests[0] == digests[1] == digests[2]  # bytecode is not code; an analysis makes no operator
    assert len({digests[2], digests[3], digests[4]}) == 3


def test_a_single_run_trains_at_its_description_and_a_batch_prepares_a_projection_over_the_declared_ranges(
        paper, tmp_path, monkeypatch):
    """``reduced_training`` (models/reduced/store.py): a single run builds a basis at its description's
    own numbers; a batch's preparation does not take that one, and builds one over the declared
    ranges, which then serves the batch's runs at other numbers inside them and any single run it holds."""
    from dataclasses import replace

    from feedtherm.models.reduced import training

    monkeypatch.setenv("FEEDTHERM_CACHE", str(tmp_path))
    monkeypatch.setattr(training, "RANDOM_POINTS", 0)  # the declared domain's corners only: three points
    monkeypatch.setattr(store, "_in_memory", type(store._in_memory)())
    builds = []
    fem_factory = registry._fem
    monkeypatch.setattr(registry, "_fem", lambda system, options: builds.append(system) or fem_factory(system, options))
    # the FE model on the coarse mesh with five positions; one declared range (the bolted joints' tcr)
    options = ModelOptions(reduction_tolerance=1e-3, mesh="coarse", axial_cells=10, steps_per_stroke=4)
    narrow = paper.system.model_copy(update={"calibration": None, "uncertainty": paper.system.uncertainty.model_copy(
        update={"parameters": {"tcr_bolted": paper.system.uncertainty.parameters["tcr_bolted"]}})})
    bolted = training.omitted_values(narrow)["joints[9].conductance"]

    single = registry.build_model("reduced", narrow, replace(options, reduced_training="description"))
    assert (single.stats["trained_over"], single.stats["projection_cached"], len(builds)) == ("description", False, 1)
    assert single.projection.domain["joints[9].conductance"] == pytest.approx((bolted, bolted))

    batch = registry.build_model("reduced", narrow, replace(options, reduced_training="batch"))
    assert (batch.stats["trained_over"], batch.stats["projection_cached"], len(builds)) == ("declared", False, 2)
    assert batch.projection.domain["joints[9].conductance"] == pytest.approx((160.0, 4000.0))
    assert batch.basis.snapshots > 2 * single.basis.snapshots  # trained at three points, not one

    within = narrow.model_copy(update={"joints": [j.model_copy(update={"tcr": j.tcr * (3.0 if i >= 9 else 1.0)})
                                                  for i, j in enumerate(narrow.joints)]})
    store._in_memory.clear()  # from disk, as another process reads them
    for system, training_ in ((within, "declared"), (within, "description"), (narrow, "batch")):
        model = registry.build_model("reduced", system, replace(options, reduced_training=training_))
        assert model.stats["projection_cached"] and model.stats["trained_over"] == "declared", training_
    again = registry.build_model("reduced", narrow, replace(options, reduced_training="description"))
    assert again.stats["projection_cached"] and len(builds) == 2
    assert len(list((tmp_path / "projections").glob("*.npz"))) == 2


def test_a_batch_prepares_its_reduced_model_over_the_declared_ranges(paper, monkeypatch):
    import feedtherm.simulate as simulate

    asked = []
    monkeypatch.setattr(simulate, "build_model", lambda name, system, options: asked.append((name, options)))
    simulate.prepare(paper.system, "reduced", "medium")
    simulate.prepare(paper.system, "reduced")
    assert [(name, o.mesh, o.reduced_training) for name, o in asked] == [("reduced", "medium", "batch"),
                                                                         ("reduced", "coarse", "batch")]
