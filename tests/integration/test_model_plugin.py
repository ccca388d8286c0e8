"""A model plugs in through the registry: a toy lumped model with dense operators.

The whole machine as one body: capacity C = Σ ρ c V over the parts, one link h·A to the
ambient summed over the surfaces, all the heat Q into it.  Its exact answer is

    T(t) = T_amb + (Q / hA) · (1 − exp(−t / τ)),   τ = C / hA,

and a body of one expansion coefficient expands uniformly, so D = α (T − T_ref) (x_target − x_mount)
along the laser's axis (the paper bench's screw and base are both steel of α = 1.2e-5 1/K).  The
model's operators are 1 × 1 dense
matrices, so the run goes through the integrator's dense path; ``simulate``, the Solution,
the energy balance and the CLI's model list take it like any built-in model.
"""

import numpy as np
import pytest

from feedtherm.boundary import boundary_conditions
from feedtherm.cli import main
from feedtherm.constants import ELONGATION_PROBE
from feedtherm.models.interface import AmbientCoupling, ThermalModel
from feedtherm.models.registry import ModelEntry, register_model, unregister_model
from feedtherm.simulate import simulate
from feedtherm.system.geometry import bounds, part_volume, surface_area


class LumpedBody(ThermalModel):
    """The machine as one isothermal body (a toy: the interface's smallest model)."""

    def __init__(self, system, options):
        self.system = system
        self.n_nodes = 1
        self.capacity = np.array([[sum(system.materials[p.material].density * system.materials[p.material].specific_heat
                                       * part_volume(p) for p in system.parts.values())]])
        stroke = system.kinematics.stroke
        self.positions = np.array([-stroke / 2, stroke / 2])
        self.dx = stroke
        self.probe_names = [n for n in system.sensors if n != system.room.ambient_sensor] + [ELONGATION_PROBE]
        lo, hi = bounds(system.parts[system.kinematics.screw])
        self.screw_edges = np.array([lo[0], hi[0]])
        self.screw_centres = self.screw_edges.mean(keepdims=True)
        self.alpha = system.materials[system.parts[system.kinematics.screw].material].expansion
        self.system_areas = {name: surface_area(s, system.parts[s.part]) for name, s in system.surfaces.items()}

    def conductance(self, k):
        return np.zeros((1, 1))

    def surface_exposure(self, name, k):
        return np.zeros(1, dtype=int), np.array([self.system_areas[name]])

    def ambient_coupling(self, bc, k):
        hA = self.ambient_links(bc, k)
        sink_heat = hA * bc.point.ambient
        return AmbientCoupling(np.diag(hA), hA, sink_heat, float(sink_heat.sum()))

    def heat_distribution(self, heat, k):
        return np.ones(1)

    def displacement_rows(self):
        mech = self.system.mechanics
        span = mech.elongation.target.point[0] - mech.elongation.mount.point[0]
        lengths = np.array([span, *(self.screw_centres - mech.positioning.reference.point[0])])
        rows = self.alpha * lengths[:, None]
        return rows, -self.system.temperatures.reference * rows[:, 0]

    def probe(self, state, k):
        d = self.displacements(state)[0]
        return np.array([state[0]] * (len(self.probe_names) - 1) + [d])

    def screw_mean(self, states):
        return np.asarray(states)[..., :1]

    def part_means(self, states):
        return {name: np.asarray(states)[..., 0] for name in self.system.parts}

    @property
    def stats(self):
        return {"unknowns": 1}


@pytest.fixture
def lumped():
    register_model(ModelEntry("lumped", "one isothermal body (test)", LumpedBody))
    yield "lumped"
    unregister_model("lumped")


def test_a_registered_model_runs_through_simulate_with_its_exact_answer(paper_equations, lumped):
    # frozen coefficients: the lumped body's answer is the exponential of one time constant
    paper = paper_equations
    run = simulate(paper, condition="I", model=lumped, duration=7200.0, motion="averaged")
    model = LumpedBody(paper.system, None)
    bc = boundary_conditions(paper.system, "I")
    hA = model.ambient_links(bc, 0)[0]
    C = model.capacity[0, 0]
    rise = bc.total_heat / hA
    tau = C / hA
    exact = bc.point.ambient + rise * (1 - np.exp(-run.times / tau))
    # implicit Euler's own exact answer: the remaining rise shrinks by 1/(1 + dt/τ) per step
    dt = run.info["time_step_s"]
    euler = bc.point.ambient + rise * (1 - (1 + dt / tau) ** (-run.times / dt))
    assert np.max(np.abs(run.sensors["T1"] - euler)) < 1e-9 * rise
    # and it tends to the continuous answer: error below dt/(2τ e) of the rise, to first order
    assert np.max(np.abs(run.sensors["T1"] - exact)) < 1.1 * dt / (2 * tau * np.e) * rise
    assert run.steady["T1"] == pytest.approx(bc.point.ambient + rise, rel=1e-12)
    laser = paper.system.mechanics.elongation
    assert run.steady["D"] == pytest.approx(model.alpha * (run.steady["T1"] - paper.system.temperatures.reference)
                                            * (laser.target.point[0] - laser.mount.point[0]), rel=1e-12)
    assert abs(run.energy.relative_error) < 1e-9
    assert run.info["model"] == "lumped" and run.info["solver"].startswith("dense")


def test_the_cli_lists_a_registered_model(lumped, capsys):
    assert main(["models"]) == 0
    listed = capsys.readouterr().out
    assert "fast" in listed and "fem" in listed and "lumped" in listed


def test_an_unknown_model_is_one_line_with_the_closest_name(paper, capsys, tmp_path):
    assert main(["run", "--condition", "I", "--model", "fsat", "--out", str(tmp_path / "x")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "no model 'fsat'" in err[0] and "did you mean 'fast'" in err[0]
    assert not (tmp_path / "x").exists()
