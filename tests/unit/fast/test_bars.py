"""The fast model's displacements: every part an axial bar along x, carried along the load path.

Every expected value is worked out by hand below from the paper bench's description
(src/feedtherm/benches/paper/description.toml), in millimetres unless said:

* x-extents: base [-300, 700]; front_housing [-220, 30] (housing [-30, 30] and its bracket
  [-220, -30], one after the other); front_bearing [-15, 15]; screw [-60, 450].
* the base is held along x at the front foot, x = -250; the chain to the laser's target
  (the screw's rear end face, x = 450) over the joints that hold x is
  base -> front_housing -> front_bearing -> screw (the rear bearing releases x).
* anchors: front_housing at the middle of [-300, 700] ∩ [-220, 30] = [-220, 30]: -95;
  front_bearing at the middle of [-220, 30] ∩ [-15, 15]: 0; screw at the middle of
  [-15, 15] ∩ [-60, 450]: 0.
* mount: the base at x = 480; positioning reference: the base at x = 0.
* α = 1.2e-5 1/K for the base and housings (Q345B) and the bearing and screw (GCr15).

So, with part temperatures uniform per part (rises ΔT_b, ΔT_h, ΔT_r, ΔT_s over T_ref):

    u_screw(x) = α [ΔT_b (-95 + 250) + ΔT_h (0 + 95) + ΔT_r (0 - 0) + ΔT_s (x - 0)]
    u_base(x)  = α ΔT_b (x + 250)
    D          = u_screw(450) - u_base(480)
"""

from types import SimpleNamespace

import numpy as np
import pytest

from feedtherm.errors import ModelError
from feedtherm.models.fast.bars import Bar, node_extents
from feedtherm.models.fast.cells import part_cells
from feedtherm.models.fast.discretization import FastDiscretization
from feedtherm.models.options import ModelOptions
from feedtherm.system.schema import Cylinder, Part
from feedtherm.system.variants import with_values

ALPHA = 1.2e-5  # [1/K] Q345B and GCr15
MM = 1e-3


@pytest.fixture(scope="module")
def model(paper):
    return FastDiscretization(paper.system, ModelOptions())


def at_rises(model, rises: dict[str, float], others: float = 0.0) -> np.ndarray:
    """A state at T_ref plus a uniform rise per part (``others`` for every part not named)."""
    T = np.full(model.n_nodes, model.system.temperatures.reference + others)
    for part, rise in rises.items():
        T[model.layout.part_nodes(part)] = model.system.temperatures.reference + rise
    return T


def test_a_uniform_rise_moves_the_target_by_the_expansion_between_it_and_the_mount(model):
    # every part of the loop is steel at α: D = α ΔT [155 + 95 + 0 + 450 - 730] mm = α ΔT (-30 mm)
    dT = 10.0
    D = model.displacements(at_rises(model, {}, others=dT))[0]
    assert D == pytest.approx(ALPHA * dT * (155 + 95 + 0 + 450 - 730) * MM, rel=1e-9)
    assert D == pytest.approx(-3.6e-6, rel=1e-9)


def test_each_part_of_the_chain_counts_over_its_own_stretch(model):
    # base +1 K, front housing +2 K, front bearing +3 K, screw +4 K; the rest (nut group,
    # rear bearing and housing, motors, guideways) +50 K, which is on no stretch D reads:
    # D = α [1·155 + 2·95 + 3·0 + 4·450 - 1·730] mm = α · 1415 mm
    T = at_rises(model, {"base": 1.0, "front_housing": 2.0, "front_bearing": 3.0, "screw": 4.0}, others=50.0)
    assert model.displacements(T)[0] == pytest.approx(ALPHA * 1415 * MM, rel=1e-9)
    # D is the last probe, read by the same row
    (probe, probe_offset), (rows, offset) = model.probe_rows(), model.displacement_rows()
    assert np.array_equal(probe[-1], rows[0]) and probe_offset[-1] == offset[0]


def test_a_linear_rise_along_the_screw_gives_the_exact_integral(model):
    # T = T_ref + g (x - x0) on the screw (x0 = -60 mm, its front end), T_ref elsewhere: the
    # base, housing and bearing do not move, so D = u_screw(450) = α g ∫_0^450 (x + 60) dx
    # = α g [0.45²/2 + 0.06 · 0.45] m² = α g · 0.12825 m². Cell-wise constant temperatures
    # integrate a linear rise exactly over whole cells; x = 0 and 450 mm are cell edges.
    g = 20.0  # [K/m]
    screw = model.layout.screw
    assert np.isclose(screw.edges, 0.0).any() and screw.edges[-1] == pytest.approx(0.45)
    T = at_rises(model, {})
    T[screw.nodes] += g * (screw.centres[:, None] - (-0.060))
    assert model.displacements(T)[0] == pytest.approx(ALPHA * g * 0.12825, rel=1e-9)
    assert ALPHA * g * 0.12825 == pytest.approx(3.078e-5)


def test_the_base_strains_by_its_section_mean(model):
    # Only the base's two risers (x from -200 to 600, section 40 x 90 mm each) at +ΔT; the slab
    # (400 x 40 mm) at T_ref: between x = -200 and 600 the section mean is ΔT · 7200/23200,
    # the slab alone beyond. u_screw(450) = u_base(-95) = α ΔT (7200/23200)(-95 + 200) mm,
    # u_base(480) = α ΔT (7200/23200)(480 + 200) mm: D = -α ΔT (7200/23200) · 575 mm.
    base = model.layout.cells["base"]
    dT = 10.0
    T = at_rises(model, {})
    for grid, first in zip(base.grids[1:], base.first[1:]):  # boxes 1 and 2: the risers
        T[first:first + grid.size] += dT
    assert model.displacements(T)[0] == pytest.approx(-ALPHA * dT * 7200 / 23200 * 575 * MM, rel=1e-9)


def test_the_screw_profile_is_relative_to_the_positioning_reference(model):
    # u_screw(x) - u_base(0): uniform ΔT: α ΔT [155 + 95 + x - 250] = α ΔT x;
    # per part (base 1, housing 2, bearing 3, screw 4 K): α [155 - 250 + 2·95 + 4 x] = α (95 + 4 x) mm
    x = model.screw_centres
    profile = model.displacements(at_rises(model, {}, others=5.0))[1:]
    np.testing.assert_allclose(profile, ALPHA * 5.0 * x, rtol=1e-9, atol=1e-18)
    assert profile[-1] == pytest.approx(ALPHA * 5.0 * 0.4475, rel=1e-9)  # the rear cell, 445-450 mm
    T = at_rises(model, {"base": 1.0, "front_housing": 2.0, "front_bearing": 3.0, "screw": 4.0}, others=50.0)
    np.testing.assert_allclose(model.displacements(T)[1:], ALPHA * (0.095 + 4 * x), rtol=1e-9)


def test_the_reference_temperature_reads_zero(model):
    rows, offset = model.displacement_rows()
    assert rows.shape == (1 + len(model.screw_centres), model.n_nodes)
    # zero up to the round-off of rows @ T (terms α·L·T_ref of about 1e-3 m, to 2e-16 each)
    np.testing.assert_allclose(model.displacements(at_rises(model, {})), 0.0, atol=1e-17)


def test_a_sensor_on_a_stand_of_its_own_and_one_looking_back(paper):
    # mount "ground": D = u_screw(450) = α ΔT (155 + 95 + 450) mm; direction -x: -D
    dT = 10.0
    grounded = FastDiscretization(with_values(paper, {"mechanics.elongation.mount": "ground"}).system,
                                  ModelOptions())
    assert grounded.displacements(at_rises(grounded, {}, dT))[0] == pytest.approx(ALPHA * dT * 0.700, rel=1e-9)
    back = FastDiscretization(with_values(paper, {"mechanics.elongation.direction": (-1.0, 0.0, 0.0)}).system,
                              ModelOptions())
    assert back.displacements(at_rises(back, {}, dT))[0] == pytest.approx(ALPHA * dT * 0.030, rel=1e-9)


@pytest.mark.parametrize("direction", [(0.0, 1.0, 0.0), (0.0, 0.0, -1.0), (0.6, 0.8, 0.0)])
def test_a_sensor_not_along_x_is_for_the_fe_model(paper, direction):
    variant = with_values(paper, {"mechanics.elongation.direction": direction}).system
    with pytest.raises(ModelError, match=r"^mechanics\.elongation\.direction: .*along x only; use --model fem$"):
        FastDiscretization(variant, ModelOptions())


def test_a_part_off_the_axial_load_path_has_no_displacement(paper):
    # the screw motor released along x on its bracket: no chain of x ties reaches it
    joint = next(i for i, j in enumerate(paper.system.joints) if set(j.between) == {"screw_motor", "front_housing"})
    variant = with_values(paper, {f"joints[{joint}].release": ["x"],
                                  "mechanics.elongation.target.part": "screw_motor"}).system
    with pytest.raises(ModelError, match=r"^mechanics\.elongation\.target: part 'screw_motor' is on no chain"):
        FastDiscretization(variant, ModelOptions())


def test_a_cylinder_across_x_is_one_bin():
    # a pin along y, 20 mm across at x = 100 mm: every cell spans x = 90 ... 110 mm, and the
    # section mean there is the capacity-weighted mean of all of them
    pin = Part(material="m", cylinders=[Cylinder(origin=("100 mm", "0 mm", "0 mm"), length="50 mm",
                                                 outer_diameter="20 mm", axis="y")])
    cells = part_cells("pin", pin, 50.0, 0.01, 0)
    layout = SimpleNamespace(bodies={}, cells={"pin": cells}, capacity=cells.volumes * 4e6)
    nodes, lo, hi = node_extents(layout, "pin")
    np.testing.assert_allclose(lo, 0.090)
    np.testing.assert_allclose(hi, 0.110)
    bar = Bar(layout, "pin", 1e-5)
    np.testing.assert_allclose(bar.edges, [0.090, 0.110])
    np.testing.assert_allclose(bar.mean, [cells.volumes / cells.volumes.sum()])
    # from x = 90 mm to 120 mm at +10 K: only the 20 mm of material strains: 1e-5 · 10 · 0.02 m
    assert (bar.stretch(0.090, [0.120], len(nodes)) @ np.full(len(nodes), 10.0))[0] == pytest.approx(2e-6)
