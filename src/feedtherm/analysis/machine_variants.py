"""Another machine of the same design: the description's uncertain inputs drawn within ranges.

A compensation law is judged on model mismatch, not on its own model: the held-out cycles are
simulated on a *variant* of the description, another machine built to the same drawings.  A
variant draws, once per cycle and independently:

- every declared uncertainty of ``[uncertainty.parameters]`` from its own distribution (the
  frictions, preloads, winding resistances, contact resistances, conductivities, CHTC groups,
  the room's air speed, the expansion coefficients of the screw and of the measuring loop, as
  the description declares them; :mod:`~feedtherm.analysis.uncertainty.sampling`), and
- on top, a factor on each source's heat and each surface's CHTC, uniform within
  ±:data:`DEFAULT_SPREAD`: the scatter of the loss and convection models themselves, which no
  declared parameter carries.

A description without ``[uncertainty.parameters]`` varies the heats and CHTCs alone.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import FeedthermError
from ..system.load import LoadedSystem
from ..system.variants import with_values
from .uncertainty.declared import changes as declared_changes
from .uncertainty.declared import resolve_uncertainties
from .uncertainty.sampling import ppf
from .uncertainty.types import UncertainParameter

#: Half-width of the uniform factor on every heat and CHTC (±20 %).  An assumption, from the
#: scatter of friction losses between bearings of one type (SKF's friction model is stated to
#: about ±20-30 %) and of convection correlations (±20-25 % for the natural and forced
#: correlations of Incropera et al., ch. 7 and 9); issue 16 names ±20 % until a description
#: declares its own ranges.
DEFAULT_SPREAD = 0.2


@dataclass(frozen=True)
class MachineVariant:
    """The draws of one variant: declared uncertainty name -> value [SI, or a factor for a "scale"
    kind] (``declared``), and on top source name -> heat factor, surface name -> CHTC factor."""

    heat: dict[str, float]
    chtc: dict[str, float]
    declared: dict[str, float] = field(default_factory=dict)

    def apply(self, loaded: LoadedSystem, label: str = "another machine") -> LoadedSystem:
        """``loaded`` with the declared draws, then the factors times any already in the description."""
        if self.declared:
            parameters = {p.name: p for p in resolve_uncertainties(loaded)}
            chosen = [parameters[name] for name in self.declared]
            loaded = with_values(loaded, declared_changes(loaded, chosen, list(self.declared.values())),
                                 origin_suffix=label)
        system = loaded.system
        factors = {f"sources.{name}.heat_factor": system.sources[name].heat_factor * f for name, f in self.heat.items()}
        factors.update({f"surfaces.{name}.chtc_factor": system.surfaces[name].chtc_factor * f
                        for name, f in self.chtc.items()})
        return with_values(loaded, factors, origin_suffix=label)

    def as_dict(self) -> dict:
        return {"declared": dict(self.declared), "heat_factor": dict(self.heat), "chtc_factor": dict(self.chtc)}


def declared_uncertainties(loaded: LoadedSystem) -> list[UncertainParameter]:
    """The description's ``[uncertainty.parameters]``, resolved; none when it declares none."""
    if loaded.system.uncertainty is None or not loaded.system.uncertainty.parameters:
        return []
    return resolve_uncertainties(loaded)


def draw_variant(loaded: LoadedSystem, rng: np.random.Generator, spread: float = DEFAULT_SPREAD,
                 declared: bool = True) -> MachineVariant:
    """Another machine: the declared uncertainties, then the heat and CHTC factors.

    Parameters
    ----------
    loaded : LoadedSystem
    rng : numpy.random.Generator
        Drawn from once per source, then once per surface (the order of the description), then
        once per declared uncertainty (its order): the heat and CHTC factors of a seed do not
        depend on what the description declares.
    spread : float
        Half-width of the factors, in [0, 1).
    declared : bool
        Draw the ``[uncertainty.parameters]`` too (False: the heats and CHTCs alone).
    """
    if not 0.0 <= spread < 1.0:
        raise FeedthermError(f"the spread of a machine variant must be in [0, 1), got {spread:g}")
    system = loaded.system
    heat = {name: float(rng.uniform(1 - spread, 1 + spread)) for name in system.sources}
    chtc = {name: float(rng.uniform(1 - spread, 1 + spread)) for name in system.surfaces}
    values = {}
    for parameter in declared_uncertainties(loaded) if declared else []:
        values[parameter.name] = float(ppf(parameter, rng.uniform()))
    return MachineVariant(heat, chtc, values)
