"""The energy account of FE runs: case ``cases/energy_ledger.toml``.

A ring (10 W, entering by volume) clamped on a shaft, both convecting to 20 °C; 1200 s in
steps of 20 s from the ambient. The run's account (:class:`feedtherm.solution.EnergyBalance`)
takes the heat in from the boundary conditions (10 W × 1200 s, not from the model's heat
vector), the heat lost from the surfaces' links and the heat stored from the capacities.
It closes to round-off with the direct solver (the old test's bound was 1e-3; it measured
1e-13, and 1e-9 is asserted) and to the iteration's tolerance with conjugate gradients.
A run whose solver alone is wrong — a source missing from the heat vector, or a surface
missing half its links in the step matrix while the account counts all of them — must fail
the check: the balance has teeth. At the steady state the surfaces lose the 10 W that come in.
"""

import re
from dataclasses import replace
from typing import ClassVar

import numpy as np
import pytest
from fem_cases import load_case, solve_steady

from feedtherm.errors import ModelError
from feedtherm.models.fem.bench import FemDiscretization
from feedtherm.models.options import ModelOptions
from feedtherm.models.registry import ModelEntry, register_model, unregister_model
from feedtherm.simulate import simulate

POWER, DURATION = 10.0, 1200.0
OPTIONS = ModelOptions(standstill_step=20.0)


def run(model="fem", solver="direct"):
    return simulate(load_case("energy_ledger"), condition="heating", model=model, solver=solver, options=OPTIONS,
                    sample_interval=60.0)


@pytest.fixture(scope="module")
def direct():
    return run()


def test_energy_balance_closes(direct):
    energy = direct.energy
    print(f"energy balance: in {energy.heat_in:.1f} J, lost {energy.heat_lost:.1f} J, stored {energy.heat_stored:.1f} J, "
          f"error {energy.relative_error:.1e}; {direct.info['steps']} steps, {direct.info['unknowns']} nodes")
    assert direct.info["steps"] == 60
    assert energy.heat_in == pytest.approx(POWER * DURATION, rel=1e-12)
    assert energy.heat_lost > 0.05 * energy.heat_in and energy.heat_stored > 0.05 * energy.heat_in
    assert abs(energy.relative_error) < 1e-9


def test_conjugate_gradients_agree_with_the_direct_solver(direct):
    cg = run(solver="cg")
    assert cg.info["solver"].startswith("cg") and direct.info["solver"].startswith("direct")
    assert abs(cg.energy.relative_error) < 1e-8
    for name in ("ring", "shaft_end"):
        np.testing.assert_allclose(cg.sensors[name], direct.sensors[name], atol=1e-6)
        assert cg.steady[name] == pytest.approx(direct.steady[name], abs=1e-6)


class TamperedFem(FemDiscretization):
    """The FE model with an error in what the solver gets, injected from the test.

    ``drop`` removes sources from the heat vector; ``link_scale`` scales a surface's links in
    the step matrix only (the account keeps the exact ones).
    """

    drop: ClassVar[tuple[str, ...]] = ()
    link_scale: ClassVar[dict[str, float]] = {}

    def heat_vector(self, bc, k):
        return super().heat_vector(replace(bc, heats={n: h for n, h in bc.heats.items() if n not in self.drop}), k)

    def ambient_coupling(self, bc, k):
        exact = super().ambient_coupling(bc, k)
        scaled = bc.surfaces | {n: replace(t, convection=t.convection * f) for n, t in bc.surfaces.items()
                                if (f := self.link_scale.get(n)) is not None}
        return replace(exact, matrix=self.ambient_links(replace(bc, surfaces=scaled), k))


@pytest.mark.parametrize("drop, link_scale", [(("ring",), {}), ((), {"ring": 0.5})])
def test_a_solver_error_fails_the_balance(drop, link_scale):
    tampered = type("Tampered", (TamperedFem,), {"drop": drop, "link_scale": link_scale})
    register_model(ModelEntry("tampered-fem", "the FE model with a solver error (test)",
                              lambda system, options: tampered(system, options.mesh), uses_mesh=True))
    try:
        # the run's own health check refuses the result: the balance, computed apart from the
        # solver's matrices, does not close
        with pytest.raises(ModelError) as info:
            run(model="tampered-fem")
    finally:
        unregister_model("tampered-fem")
    print(f"tampered (drop {drop}, links {link_scale}): {info.value}")
    error = float(re.search(r"differ by (\S+) of the heat", str(info.value)).group(1))
    assert abs(error) > 1e-3


def test_steady_state_loses_what_comes_in():
    steady = solve_steady(load_case("energy_ledger"), "heating", "coarse")
    lost = {name: steady.surface_heat(name) for name in ("ring", "shaft")}
    assert sum(lost.values()) == pytest.approx(POWER, rel=1e-10)
    assert lost["shaft"] > 0.05 * POWER  # heat crosses the joint into the shaft and leaves there too
