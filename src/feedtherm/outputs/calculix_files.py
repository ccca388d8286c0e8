"""``feedtherm calculix``: the FE model written as a CalculiX deck, with what it was made from.

The set is ``feedtherm.inp`` (:func:`~feedtherm.models.fem.calculix.calculix_deck`) and
``deck.json``: the condition, the moving group's position, the time stepping, and the totals
the deck carries (heat, film conductance, joints), so that a user can check a CalculiX run
against them.  Both appear in the output directory together, or neither.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..boundary import BoundaryConditions
from ..models.fem.bench import FemDiscretization
from ..models.fem.calculix import calculix_deck
from .files import staged_directory, write_json

DECK_FILES = ("feedtherm.inp", "deck.json")


def write_calculix(model: FemDiscretization, bc: BoundaryConditions, k: int, out_dir: Path, *, condition: str,
                   time_step: float, duration: float, output_interval: float) -> list[Path]:
    """Write the deck of ``model`` at position ``k`` under ``bc`` (condition ``condition``) and its summary."""
    initial = bc.point.ambient
    deck = calculix_deck(model, bc, k, time_step=time_step, duration=duration, output_interval=output_interval,
                         initial=initial)
    links = model.ambient_links(bc, k)
    summary = {
        "system": model.system.meta.name, "condition": condition, "mode": bc.mode,
        "mesh": model.density, "vertices": int(model.n_nodes), "tetrahedra": int(model.tets.shape[1]),
        "position": int(k), "positions": len(model.positions), "offset_m": float(model.positions[k]),
        "time_step_s": time_step, "duration_s": duration, "output_interval_s": output_interval,
        "initial_temperature_K": initial,
        "heat_W": float(np.sum(model.heat_vector(bc, k))), "film_conductance_W_per_K": float(np.sum(links)),
        "joints": [{"between": list(j.joint.between), "area_m2": j.joint.area, "resistance_m2K_per_W": j.joint.tcr,
                    "mesh_contact_area_m2": model.contact_area(j, k)} for j in model.joints],
        "run": "ccx -i feedtherm  (temperatures [K] of every node in feedtherm.dat)",
    }
    out_dir = Path(out_dir)
    with staged_directory(out_dir, replaces=DECK_FILES) as stage:
        (stage / "feedtherm.inp").write_text(deck)
        write_json(stage / "deck.json", summary)
    return [out_dir / name for name in DECK_FILES]
