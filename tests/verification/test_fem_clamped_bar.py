"""A bar clamped along its axis between walls that neither expand nor yield: case ``cases/clamped_bar.toml``.

Bar E = 5 GPa, ν = 0.3, α = 2e-5 1/K, 100 mm long, 20 mm across; walls 1000 times as stiff
(5 TPa) with α = 1e-12 1/K; the bar's end faces tied to the walls along x only; everything at
70 °C against T_ref = 20 °C (ΔT = 50 K). With ε_xx = 0 and the bar free across,

    σ_xx = −E α ΔT = −5e9 Pa · 2e-5 1/K · 50 K = −5.0e6 Pa,  σ_yy = σ_zz = τ = 0

(Timoshenko & Goodier, §150). The stress is computed from the run's displacement field
(``fields.displacements``) and temperatures by ``elastic.stress`` (constant in each
tetrahedron, linear elements).

What the FE model gives (coarse / medium): the bar's mean σ_xx is −E α ΔT (1 − 4.0e-4 / 4.1e-4),
the walls' compliance (the bar's ends move the walls by 2.2e-8 m each: D, the bar's length
change, is 4.4e-8 m against a free expansion of 1e-4 m); element by element σ_xx scatters by up to
1.2 % / 0.95 % and the other components reach 0.45 % / 0.31 % of E α ΔT. The scatter does not
shrink with stiffer walls (1.1 % at 500 GPa, 1.2 % at 5 TPa) nor with the tie penalty (10 or
1e4), and it is absent when the same bar expands freely between the same walls (1e-9): it is the
tie of two non-matching meshes carrying the bar's push, which does not transmit a uniform
traction uniformly (a non-conforming interface's patch test), largest near the tied end faces.
"""

import numpy as np
import pytest
from fem_cases import load_case

from feedtherm.models.fem.elastic import ElasticPart, stress
from feedtherm.simulate import simulate

E, ALPHA, DT = 5e9, 2e-5, 70.0 - 20.0
SIGMA = -E * ALPHA * DT


def bar_stresses(run, system) -> tuple[np.ndarray, np.ndarray]:
    """Stress (m, 3, 3) [Pa] and volume (m,) of the bar's tetrahedra at the run's last snapshot."""
    fields = run.fields
    constants = []
    for name in fields.part_names:
        material = system.materials[system.parts[name].material]
        constants.append(ElasticPart(material.youngs_modulus, material.poisson_ratio, material.expansion))
    rise = fields.temperatures[-1] - system.temperatures.reference
    sigma = stress(fields.points.T, fields.tets.T, fields.displacements[-1], rise, constants, fields.part_id)
    bar = fields.part_id == list(fields.part_names).index("bar")
    corners = fields.points[fields.tets[bar]]
    volume = np.abs(np.einsum("ij,ij->i", corners[:, 1] - corners[:, 0],
                              np.cross(corners[:, 2] - corners[:, 0], corners[:, 3] - corners[:, 0]))) / 6.0
    return sigma[bar], volume


def test_the_hand_value():
    assert SIGMA == pytest.approx(-5.0e6, rel=1e-12)


@pytest.mark.parametrize("mesh", ["coarse", "medium"])
def test_a_clamped_bar_carries_minus_e_alpha_dt(mesh):
    loaded = load_case("clamped_bar")
    run = simulate(loaded, condition="warm", model="fem", mesh=mesh)
    sigma, volume = bar_stresses(run, loaded.system)
    mean = np.einsum("i,ijk->jk", volume, sigma) / volume.sum()
    assert volume.sum() == pytest.approx(np.pi / 4 * 0.02**2 * 0.1, rel=2e-2)  # a polygonal cylinder
    # the bar's mean: −E α ΔT relieved only by the walls' compliance (4.1e-4 measured)
    assert mean[0, 0] == pytest.approx(SIGMA, rel=1e-3)
    others = mean - np.diag([mean[0, 0], 0.0, 0.0])
    assert np.abs(others).max() < 1e-3 * abs(SIGMA)
    # each element: the non-conforming ties' scatter (1.2 % / 0.95 % measured)
    assert np.abs(sigma[:, 0, 0] / SIGMA - 1.0).max() < 2e-2
    assert np.abs(sigma - np.einsum("i,jk->ijk", sigma[:, 0, 0], np.diag([1.0, 0.0, 0.0]))).max() < 1e-2 * abs(SIGMA)
    # the bar's length change (D reads it between its end faces' centres): what the walls yield
    assert abs(run.final["D"]) < 1e-3 * ALPHA * DT * 0.1
