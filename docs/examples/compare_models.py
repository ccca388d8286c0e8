"""Compare the fast model with the 3D finite element model at condition I (steady state).

Both models take the same description and boundary conditions and are chosen by name from
the model registry; ``steady_state`` solves each one's cycle-averaged steady state directly
(one linear solve, no transient).  The FE model meshes every part with gmsh (about half a
minute the first time on a small machine; the mesh is cached under ~/.cache/feedtherm).
"""

from feedtherm.constants import KELVIN_OFFSET
from feedtherm.models.options import ModelOptions
from feedtherm.simulate import steady_state
from feedtherm.system.load import load_system

SENSORS = ["T1", "T2", "T3", "T4", "T5"]


def main(mesh: str = "coarse") -> dict:
    loaded = load_system("paper")
    fast = steady_state(loaded, "I", model="fast")  # sensors [K] and D [m]
    fem = steady_state(loaded, "I", model="fem", options=ModelOptions(mesh=mesh))
    return {
        "ambient_C": fast["T6"] - KELVIN_OFFSET,
        "fast_C": {n: fast[n] - KELVIN_OFFSET for n in SENSORS},
        "fem_C": {n: fem[n] - KELVIN_OFFSET for n in SENSORS},
        "difference_K": {n: fem[n] - fast[n] for n in SENSORS},  # FE − fast
        "fast_D_um": fast["D"] * 1e6,
        "fem_D_um": fem["D"] * 1e6,
        "difference_D_um": (fem["D"] - fast["D"]) * 1e6,
    }


if __name__ == "__main__":
    r = main()
    print(f"steady state at condition I (ambient {r['ambient_C']:.1f} °C)")
    print(f"{'':<8}{'fast':>8}{'FE':>8}{'FE − fast':>11}")
    for n in SENSORS:
        print(f"{n + ' [°C]':<8}{r['fast_C'][n]:>8.2f}{r['fem_C'][n]:>8.2f}{r['difference_K'][n]:>+11.2f}")
    print(f"{'D [µm]':<8}{r['fast_D_um']:>8.2f}{r['fem_D_um']:>8.2f}{r['difference_D_um']:>+11.2f}")
