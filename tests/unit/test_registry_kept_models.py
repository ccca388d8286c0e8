"""The registry keeps the last model an entry with ``build_options`` built (models/registry.py).

A build of the same description (the same object) with the same of those options returns the kept
model; another description, other build options or :func:`forget_built_models` build anew; options
outside the key (the time stepping) do not; an entry without ``build_options`` never keeps one.  On
the FE model itself: the runs of one description build it once, and a run on the kept model gives
a fresh model's numbers bit for bit.
"""

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from feedtherm.models.fast.discretization import FastDiscretization
from feedtherm.models.options import ModelOptions
from feedtherm.models.registry import ModelEntry, build_model, forget_built_models, register_model, unregister_model
from feedtherm.simulate import simulate
from feedtherm.system.load import load_system
from feedtherm.system.variants import with_values


@pytest.fixture
def counted():
    """Two entries of the fast model, their builds counted: "kept" keyed on the axial cells, "every" not keyed."""
    builds = []

    def factory(system, options):
        builds.append(options)
        return FastDiscretization(system, options)

    register_model(ModelEntry("kept", "the fast model, kept (a test's)", factory,
                              build_options=lambda options: options.axial_cells))
    register_model(ModelEntry("every", "the fast model, built every time (a test's)", factory))
    try:
        yield builds
    finally:
        unregister_model("kept")
        unregister_model("every")
        forget_built_models()


def test_the_same_description_and_build_options_get_the_kept_model(paper, counted):
    options = ModelOptions()
    first = build_model("kept", paper.system, options)
    assert build_model("kept", paper.system, replace(options, motion="averaged", solver="cg")) is first
    assert len(counted) == 1
    other_cells = build_model("kept", paper.system, replace(options, axial_cells=60))
    assert other_cells is not first and len(counted) == 2
    assert build_model("kept", paper.system, options) is not first  # one kept at a time: the 60 cells' replaced it
    variant = with_values(paper, {"materials.q345b.conductivity": 41.0})
    assert build_model("kept", variant.system, options) is not build_model("kept", paper.system, options)
    kept = build_model("kept", paper.system, options)
    forget_built_models()
    assert build_model("kept", paper.system, options) is not kept
    count = len(counted)
    assert build_model("every", paper.system, options) is not build_model("every", paper.system, options)
    assert len(counted) == count + 2


def test_the_fe_runs_of_one_description_build_it_once_with_the_fresh_models_numbers(monkeypatch):
    """Two runs of one description (a block heated at standstill, tests/verification/cases/energy_ledger.toml)
    on the FE model: one build; and a run on the kept model equals one on a fresh model bit for bit."""
    pytest.importorskip("gmsh")
    from feedtherm.models.fem import bench

    loaded = load_system(str(Path(__file__).parents[1] / "verification" / "cases" / "energy_ledger.toml"))
    options = ModelOptions(standstill_step=20.0)

    def run(solver):
        return simulate(loaded, condition="heating", model="fem", solver=solver, options=options, sample_interval=60.0)

    forget_built_models()
    builds = []
    original = bench.FemDiscretization.__init__

    def counted_init(self, *args, **kwargs):
        builds.append(args)
        original(self, *args, **kwargs)

    monkeypatch.setattr(bench.FemDiscretization, "__init__", counted_init)
    first, kept = run("cg"), run("direct")
    assert len(builds) == 1 and first.final["D"] == pytest.approx(kept.final["D"], rel=1e-6)
    forget_built_models()
    fresh = run("direct")
    assert len(builds) == 2
    for name, series in fresh.sensors.items():
        np.testing.assert_array_equal(kept.sensors[name], series)
    np.testing.assert_array_equal(kept.elongation, fresh.elongation)
    forget_built_models()
