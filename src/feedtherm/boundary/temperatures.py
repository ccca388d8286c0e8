"""The temperatures at which temperature-dependent boundary conditions are evaluated.

Frozen boundary conditions (the paper's assumption 3) take every surface and every
lubricant at one declared temperature, ambient + ``temperatures.convection_delta_t``.
Under ``temperatures.coupling = "nonlinear"`` the models read each surface's and each
source's own temperature from the state and the boundary conditions are evaluated there
(:class:`LocalTemperatures`): convection and radiation coefficients at the surface's mean
temperature, lubricant viscosities at the temperature where the source's heat enters.
"""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass(frozen=True)
class LocalTemperatures:
    """Temperatures [K] of surfaces and sources, by name; a name left out takes the frozen value."""

    surfaces: dict[str, float] = field(default_factory=dict)
    sources: dict[str, float] = field(default_factory=dict)

    def largest_change(self, other: "LocalTemperatures") -> float:
        """Largest difference [K] between two readings of the same names."""
        pairs = [(self.surfaces, other.surfaces), (self.sources, other.sources)]
        return max((abs(mine[name] - theirs[name]) for mine, theirs in pairs for name in mine), default=0.0)

    def lagging(self, evaluated: "LocalTemperatures", tolerance: float) -> "LocalTemperatures":
        """This reading with every value within ``tolerance`` [K] of ``evaluated``'s (same names) left at that value.

        A coupled transient's re-evaluation moves the readings that have moved further; the
        others keep the temperature they were evaluated at, so that their coefficients need not
        be recomputed (:mod:`feedtherm.models.coupling`).
        """
        def lag(mine, theirs):
            return {name: value if abs(value - theirs[name]) > tolerance else theirs[name]
                    for name, value in mine.items()}
        return LocalTemperatures(lag(self.surfaces, evaluated.surfaces), lag(self.sources, evaluated.sources))

    def toward(self, other: "LocalTemperatures", fraction: float) -> "LocalTemperatures":
        """The reading ``fraction`` of the way from this one to ``other`` (same names)."""
        def blend(mine, theirs):
            return {name: mine[name] + fraction * (theirs[name] - mine[name]) for name in mine}
        return LocalTemperatures(blend(self.surfaces, other.surfaces), blend(self.sources, other.sources))

    def outside(self, low: float, high: float) -> tuple[str, float] | None:
        """The first surface or source whose temperature [K] is not finite within ``low``–``high``."""
        for values in (self.sources, self.surfaces):
            for name, value in values.items():
                if not low <= value <= high:  # NaN included
                    return name, value
        return None

    def hottest(self) -> tuple[str, float]:
        """The source (or, with none, the surface) with the highest temperature [K]."""
        values = self.sources or self.surfaces
        name = max(values, key=values.get)
        return name, values[name]
