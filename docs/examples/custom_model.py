"""Plug a model of your own into feedtherm: one isothermal node per part.

A model subclasses ``ThermalModel`` (feedtherm/models/interface.py) and states its operators
in C dT/dt + G T + A (T − T_amb) = q: capacities C [J/K], conductances G [W/K], the nodes and
areas each surface exposes (the base class builds A from the boundary conditions'
coefficients) and where each source's heat goes.  Registered under a name, it runs through
``simulate`` like the built-in models; the Solution's energy balance checks it.  Here each
part is isothermal, joints conduct area/TCR, surfaces expose their faces less what joined
parts cover (``exposed_area``, the area the boundary conditions report), and the moving
group's position changes nothing (so the run uses the averaged motion).

A model also says how its temperatures move the structure: ``displacement_rows()`` gives the
rows that read the elongation D (the description's ``mechanics.elongation``, a displacement
sensor: target relative to mount along x) and the screw's axial displacement relative to
``mechanics.positioning.reference``.  An isothermal part of one α expands uniformly,
α (T − T_ref) per metre, so a part's point moves by α (T − T_ref) (x − x_anchor) relative to
where the part is held, and the parts carry each other along the structure's axial load path.
The fast model's ``anchors`` (feedtherm/models/fast/bars.py) gives each part's parent and its
anchor x_anchor, as the fast model finds them from the supports and the joints that hold x: a
part fastened over a range is held at the middle of it (the screw at the middle of its front
bearing), the nut by the drive at its centre.  With every part at one temperature
D = α (T − T_ref) (x_target − x_mount), as for one lumped body.
"""

import numpy as np
import scipy.sparse as sp

from feedtherm.constants import ELONGATION_PROBE, KELVIN_OFFSET
from feedtherm.models.fast.bars import anchors
from feedtherm.models.interface import ThermalModel
from feedtherm.models.registry import ModelEntry, register_model
from feedtherm.simulate import simulate, steady_solve
from feedtherm.system.areas import exposed_area
from feedtherm.system.geometry import part_volume, screw_axis
from feedtherm.system.load import load_system
from feedtherm.system.mechanics import GROUND


class PartLumped(ThermalModel):
    """Each part one isothermal node; joints conduct area/TCR between them."""

    def __init__(self, system, options):
        self.system = system
        self.node = {part: i for i, part in enumerate(system.parts)}  # part -> state index
        self.n_nodes = len(self.node)
        materials = [system.materials[p.material] for p in system.parts.values()]
        self.capacity = np.array([m.density * m.specific_heat * part_volume(p)  # a vector: diagonal C [J/K]
                                  for m, p in zip(materials, system.parts.values())])
        G = np.zeros((self.n_nodes, self.n_nodes))  # row i: Σ_j g_ij (T_i − T_j) [W/K]
        for joint in system.joints:
            i, j = (self.node[part] for part in joint.between)
            g = joint.area / joint.tcr
            G[[i, j], [i, j]] += g
            G[[i, j], [j, i]] -= g
        self.G = sp.csr_matrix(G)
        stroke = system.kinematics.stroke
        self.positions = np.array([-stroke / 2, stroke / 2])  # offsets from mid-stroke: the two ends
        self.dx = stroke
        self.probe_names = [n for n in system.sensors if n != system.room.ambient_sensor] + [ELONGATION_PROBE]
        screw = system.parts[system.kinematics.screw]
        self.screw_edges = np.array([screw_axis(screw).start, screw_axis(screw).end])  # one axial section
        self.screw_centres = self.screw_edges.mean(keepdims=True)
        self.anchors = anchors(system)  # part -> (its parent, the x where it is held on it)
        if system.mechanics.elongation.axis != 0:
            raise ValueError("mechanics.elongation.direction: this model reads displacements along x only")

    def conductance(self, k):
        return self.G

    def surface_exposure(self, name, k):
        part = self.system.surfaces[name].part
        return np.array([self.node[part]]), np.array([exposed_area(self.system, name)])

    def heat_distribution(self, heat, k):
        return np.eye(self.n_nodes)[self.node[heat.part]]  # all of it into its part's node

    def axial(self, part, x):
        """Row over the nodes: ``row @ (T − T_ref)`` is the displacement along x of ``part`` at ``x`` [m]."""
        parent, anchor = self.anchors[part]  # the part expands from its anchor, which moves with the parent
        row = np.zeros(self.n_nodes)
        row[self.node[part]] = self.system.materials[self.system.parts[part].material].expansion * (x - anchor)
        return row if parent is None else row + self.axial(parent, anchor)

    def displacement_rows(self):
        mech = self.system.mechanics
        laser, reference = mech.elongation, mech.positioning.reference
        d = self.axial(laser.target.part, laser.target.point[0])
        if laser.mount != GROUND:
            d = d - self.axial(laser.mount.part, laser.mount.point[0])
        screw = [self.axial(self.system.kinematics.screw, x) - self.axial(reference.part, reference.point[0])
                 for x in self.screw_centres]
        rows = np.vstack([laser.direction[0] * d, *screw])
        return rows, -self.system.temperatures.reference * rows.sum(axis=1)  # zero at T_ref

    def probe(self, state, k):
        sensors = [state[self.node[self.system.sensors[n].part]] for n in self.probe_names[:-1]]
        return np.array([*sensors, self.displacements(state)[0]])

    def screw_mean(self, states):
        return np.asarray(states)[..., [self.node[self.system.kinematics.screw]]]

    def part_means(self, states):
        return {name: np.asarray(states)[..., i] for name, i in self.node.items()}

    @property
    def stats(self):
        return {"unknowns": self.n_nodes}


MODEL = ModelEntry("parts", "one isothermal node per part (docs/examples/custom_model.py)", PartLumped)


def main(duration: float = 7200.0) -> dict:
    register_model(MODEL)  # from another package: an entry point in the group "feedtherm.models"
    loaded = load_system("paper")
    run = simulate(loaded, condition="I", model=MODEL.name, duration=duration, motion="averaged")
    final, steady = run.summary_values("final"), run.summary_values("steady")
    sensors = [n for n in run.sensor_names if n != run.ambient_sensor]
    # the steady state itself (the model and its state), for the parts' temperatures
    solve = steady_solve(loaded, "I", model=MODEL.name)
    parts = {name: float(t) - KELVIN_OFFSET for name, t in solve.model.part_means(solve.state).items()}
    return {"model": run.info["model"], "ambient_C": final[run.ambient_sensor],
            "final_C": {n: final[n] for n in sensors}, "steady_C": {n: steady[n] for n in sensors},
            "steady_D_um": steady["D_um"], "steady_parts_C": parts,
            "energy_relative_error": run.energy.relative_error}


if __name__ == "__main__":
    r = main()
    print(f"model {r['model']!r}, condition I after 2 h, °C: "
          + "  ".join(f"{n} {t:.2f}" for n, t in r["final_C"].items()))
    print("steady state, °C: " + "  ".join(f"{n} {t:.2f}" for n, t in r["steady_C"].items())
          + f"  D {r['steady_D_um']:.1f} µm (screw {r['steady_parts_C']['screw']:.2f} °C, "
          f"base {r['steady_parts_C']['base']:.2f} °C)")
    print(f"energy balance relative error: {r['energy_relative_error']:.1e}")
