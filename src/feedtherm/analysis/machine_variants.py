"""Another machine of the same design: the description's uncertain inputs drawn within ranges.

A compensation law is judged on model mismatch, not on its own model: the held-out cycles are
simulated on a *variant* of the description whose heats and convection coefficients differ
from the nominal ones as they would on another machine built to the same drawings.  Until the
description declares ranges of its own, each source's heat and each surface's CHTC is scaled
by a factor drawn uniformly within ±:data:`DEFAULT_SPREAD`, independently, once per cycle.

Contact resistances and preloads are left at their nominal values here: the heats already
carry the preloads' effect (a bearing's or a thread's friction heat), and the issue that asks
for these studies (issue 16) names heats and CHTCs as the interim ranges.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import FeedthermError
from ..system.load import LoadedSystem
from ..system.variants import with_values

#: Half-width of the uniform factor on every heat and CHTC (±20 %).  An assumption, from the
#: scatter of friction losses between bearings of one type (SKF's friction model is stated to
#: about ±20-30 %) and of convection correlations (±20-25 % for the natural and forced
#: correlations of Incropera et al., ch. 7 and 9); issue 16 names ±20 % until a description
#: declares its own ranges.
DEFAULT_SPREAD = 0.2


@dataclass(frozen=True)
class MachineVariant:
    """The factors of one variant: source name -> heat factor, surface name -> CHTC factor."""

    heat: dict[str, float]
    chtc: dict[str, float]

    def changes(self, loaded: LoadedSystem) -> dict[str, float]:
        """Dotted paths -> values (the factors times any already in the description)."""
        system = loaded.system
        out = {f"sources.{name}.heat_factor": system.sources[name].heat_factor * f for name, f in self.heat.items()}
        out.update({f"surfaces.{name}.chtc_factor": system.surfaces[name].chtc_factor * f
                    for name, f in self.chtc.items()})
        return out

    def apply(self, loaded: LoadedSystem, label: str = "another machine") -> LoadedSystem:
        return with_values(loaded, self.changes(loaded), origin_suffix=label)

    def as_dict(self) -> dict:
        return {"heat_factor": dict(self.heat), "chtc_factor": dict(self.chtc)}


def draw_variant(loaded: LoadedSystem, rng: np.random.Generator, spread: float = DEFAULT_SPREAD) -> MachineVariant:
    """Factors uniform in ``[1 - spread, 1 + spread]`` for every source and surface, in declaration order.

    Parameters
    ----------
    loaded : LoadedSystem
    rng : numpy.random.Generator
        Drawn from once per source, then once per surface (the order of the description).
    spread : float
        Half-width of the factors, in [0, 1).
    """
    if not 0.0 <= spread < 1.0:
        raise FeedthermError(f"the spread of a machine variant must be in [0, 1), got {spread:g}")
    system = loaded.system
    heat = {name: float(rng.uniform(1 - spread, 1 + spread)) for name in system.sources}
    chtc = {name: float(rng.uniform(1 - spread, 1 + spread)) for name in system.surfaces}
    return MachineVariant(heat, chtc)
