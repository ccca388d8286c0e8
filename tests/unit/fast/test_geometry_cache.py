"""The fast model reuses the contact geometry of a description whose faces did not move: the
operators it builds equal those of a build from scratch, and a moved face is not reused."""

import numpy as np
import pytest

from feedtherm.models.fast import assemble, contacts
from feedtherm.models.options import ModelOptions
from feedtherm.simulate import discretize
from feedtherm.system.variants import with_values


def operators(system):
    model = discretize(system, "fast", ModelOptions())
    k = len(model.positions) // 3
    exposure = model.surface_exposure("worktable", k)
    return model.conductance(k).toarray(), exposure[0].copy(), exposure[1].copy()


@pytest.fixture
def empty_cache(monkeypatch):
    monkeypatch.setattr(assemble, "_GEOMETRY", type(assemble._GEOMETRY)())


def test_a_changed_resistance_reuses_the_geometry_and_gives_the_fresh_operators(paper, empty_cache):
    operators(paper.system)
    changed = with_values(paper, {"joints[6].tcr": 3 * paper.system.joints[6].tcr,
                                  "joints[7].tcr": 0.5 * paper.system.joints[7].tcr}).system
    before = len(assemble._GEOMETRY)
    reused = operators(changed)
    assert len(assemble._GEOMETRY) == before  # same faces: same entry
    assemble._GEOMETRY.clear()
    fresh = operators(changed)
    for a, b in zip(reused, fresh):
        np.testing.assert_array_equal(a, b)
    # and the resistances did act: the sliding nut-screw joint conducts less than before
    assert not np.array_equal(operators(paper.system)[0], reused[0])


def test_a_joints_area_and_a_materials_numbers_reuse_the_geometry_and_give_the_fresh_model(paper, empty_cache):
    """A joint's area and a material's conductivity, capacity and expansion move no face: the
    contacts are found in the kept geometry, and the operators, the capacities and the boundary
    bases (their film resistances go with the conductivities) equal a fresh build's, bit for bit."""
    _bases(paper.system)
    changed = with_values(paper, {"joints[6].area": 2.0 * paper.system.joints[6].area,
                                  "joints[9].area": 0.5 * paper.system.joints[9].area,
                                  "materials.q345b.conductivity": 40.0, "materials.gcr15.conductivity": 30.0,
                                  "materials.q345b.density": 7000.0, "materials.q345b.specific_heat": 500.0,
                                  "materials.gcr15.expansion": 1.3e-5}).system
    before = len(assemble._GEOMETRY)

    def built(system):
        model, averaged = _bases(system)
        return model, [model.conductance(k).toarray() for k in (0, len(model.positions) // 3)] \
            + [model.averaged_conductance().toarray(), model.capacity, averaged.film, averaged.exposure.toarray(),
               model.boundary_basis(5).film, model.boundary_basis(5).exposure.toarray()]

    _, reused = built(changed)
    assert len(assemble._GEOMETRY) == before  # no face moved: the same entry
    assemble._GEOMETRY.clear()
    _, fresh = built(changed)
    for a, b in zip(reused, fresh):
        np.testing.assert_array_equal(a, b)
    # and they did act: on the contacts' links, the films and the capacities
    _, original = built(paper.system)
    for i in (0, 1, 3, 4, 6):
        assert not np.array_equal(original[i], reused[i]), i
    assert len(assemble._GEOMETRY) == 1


def test_a_moved_face_is_a_new_geometry(paper, empty_cache):
    operators(paper.system)
    bigger = with_values(paper, {"parts.worktable.boxes[0].size[2]": 0.030}).system
    operators(bigger)
    assert len(assemble._GEOMETRY) == 2


def _bases(system):
    model = discretize(system, "fast", ModelOptions())
    return model, model.boundary_basis(None)


def test_boundary_bases_are_shared_by_a_geometry_and_equal_a_fresh_build(paper, empty_cache):
    _, original = _bases(paper.system)
    hotter = with_values(paper, {"sources.screw_nut.preload": 300.0,
                                 "surfaces.screw_shaft.chtc_factor": 2.0}).system
    _, reused = _bases(hotter)
    assert reused is original  # no face moved and the heat goes where it went: the same basis
    assemble._GEOMETRY.clear()
    _, fresh = _bases(hotter)
    assert fresh is not original
    for a, b in ((reused.exposure, fresh.exposure), (reused.distribution, fresh.distribution)):
        np.testing.assert_array_equal(a.toarray(), b.toarray())


def test_a_source_sent_elsewhere_gets_its_own_basis(paper, empty_cache):
    model, original = _bases(paper.system)
    names = list(paper.system.sources)
    i = names.index("front_bearing")
    moved = with_values(paper, {"sources.front_bearing.into": {"screw": 1.0}}).system
    _, other = _bases(moved)
    assert other is not original
    assert not np.array_equal(other.distribution.toarray()[i], original.distribution.toarray()[i])


def test_the_cycle_average_is_the_positions_conductances_averaged(paper):
    """Assembled once from every position's sliding links weighted by its time share, it is the
    interface's average of the positions' matrices (to rounding)."""
    from feedtherm.models.interface import ThermalModel

    model = discretize(paper.system, "fast", ModelOptions())
    assembled = model.averaged_conductance()
    by_positions = ThermalModel.averaged_conductance(model)
    assert len(model.positions) > 2 and abs(assembled - by_positions).max() <= 1e-13 * abs(by_positions).max()
    # the sliding contacts move with the nut: the average is none of the positions' own
    assert abs(assembled - model.conductance(0)).max() > 1e-3 * abs(by_positions).max()


def test_a_contact_keeps_the_sums_of_its_latest_conductivities_only(paper, empty_cache):
    """An uncertainty study draws a conductivity per sample: the kept sums stay bounded, and a
    conductivity met again after it was dropped gives the same operators."""
    first = operators(with_values(paper, {"materials.q345b.conductivity": 40.0}).system)[0]
    for k in (41.0, 42.0, 43.0, 44.0, 45.0):
        operators(with_values(paper, {"materials.q345b.conductivity": k}).system)
    (cache,) = assemble._GEOMETRY.values()
    kept = [len(c["sums"]) for by_position in cache["contacts"].values() for c in by_position.values() if "sums" in c]
    assert kept and max(kept) == contacts.KEPT_CONDUCTIVITIES
    again = operators(with_values(paper, {"materials.q345b.conductivity": 40.0}).system)[0]
    np.testing.assert_array_equal(first, again)


def test_the_parts_grids_are_kept_read_only_and_equal_a_fresh_cut(paper):
    """A model per run of a batch cuts the same primitives again (three quarters of a build): the grids
    are kept by primitive, holes, cell size and feature lines, shared read-only by the models, and each
    equals the grid cut afresh; another cell size or another feature line is another grid."""
    from dataclasses import fields as dataclass_fields

    from feedtherm.models.fast import grids

    system = paper.system
    base = system.parts["base"]
    box, holes = base.boxes[0], list(base.holes)
    breaks = ([box.origin[0] + 0.1], [], [box.origin[2] + 0.01])
    kept = grids.box_grid(box, holes, 0.04, breaks)
    assert grids.box_grid(box, holes, 0.04, [list(b) for b in breaks]) is kept
    assert grids.box_grid(box, holes, 0.03, breaks) is not kept
    assert grids.box_grid(box, holes, 0.04, ([box.origin[0] + 0.2], [], [])) is not kept
    fresh = grids._box_grid(box, holes, 0.04, [list(b) for b in breaks])
    cylinder = next(c for p in system.parts.values() for c in p.cylinders)
    pairs = [(kept, fresh), (grids.cylinder_grid(cylinder, 0.02, (cylinder.origin[0] + 0.01,)),
                             grids._cylinder_grid(cylinder, 0.02, (cylinder.origin[0] + 0.01,)))]
    for grid, cut in pairs:
        arrays = 0
        for f in dataclass_fields(grid):
            a, b = getattr(grid, f.name), getattr(cut, f.name)
            for x, y in zip(*((v if isinstance(v, (list, tuple)) else [v]) for v in (a, b))):
                if isinstance(x, np.ndarray):
                    np.testing.assert_array_equal(x, y)
                    assert not x.flags.writeable
                    arrays += 1
                else:
                    assert x == y
        assert arrays >= 4
        with pytest.raises(ValueError):
            grid.volumes[0] = 1.0
    one, two = (discretize(with_values(paper, {"materials.q345b.conductivity": k}).system, "fast", ModelOptions())
                for k in (41.0, 50.0))
    assert one.layout.cells["base"].grids[0] is two.layout.cells["base"].grids[0]
