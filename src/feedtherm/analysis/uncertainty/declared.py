"""The description's declared uncertainties, resolved to concrete paths and SI numbers."""

from __future__ import annotations

from ...errors import FeedthermError
from ...system.load import LoadedSystem
from ...system.paths import expand_path, get_path, si_unit_at
from ...system.quantities import to_base_si
from ...system.uncertainty_checks import uncertainty_problems
from ...system.variants import with_values
from ..sensitivity import source_of
from .types import UncertainParameter


def resolve_uncertainties(loaded: LoadedSystem) -> list[UncertainParameter]:
    """Every ``[uncertainty.parameters]`` entry with its paths expanded and its numbers in SI.

    Raises
    ------
    FeedthermError
        One line when the description declares no uncertainties.
    """
    declared = loaded.system.uncertainty
    if declared is None or not declared.parameters:
        raise FeedthermError(f"{loaded.origin}: declares no uncertainties; add [uncertainty.parameters.<name>] "
                             f"tables with kind, paths, distribution, range or sigma and reason "
                             f"(docs/uncertainty.md)")
    problems = uncertainty_problems(loaded.system)  # the loader refused the errors; a dangling path is left
    if problems:
        path, reason, _ = problems[0]
        raise FeedthermError(f"{loaded.origin}: {path}: {reason}")
    out = []
    for name, spec in declared.parameters.items():
        paths = tuple(p for path in spec.paths for p in expand_path(loaded.system, path))
        first = float(get_path(loaded.system, paths[0]))
        low, high = (to_base_si(b) for b in spec.range) if spec.range is not None else (None, None)
        out.append(UncertainParameter(
            name=name, description=spec.description, kind=spec.kind, paths=paths,
            declared=first if spec.kind == "value" else 1.0, distribution=spec.distribution,
            low=low, high=high, sigma=None if spec.sigma is None else to_base_si(spec.sigma),
            unit=(si_unit_at(loaded.system, paths[0]) or "") if spec.kind == "value" else "",
            reason=spec.reason, provenance=source_of(loaded, paths[0])))
    return out


def changes(loaded: LoadedSystem, parameters: list[UncertainParameter], x) -> dict[str, float]:
    """The description values the parameters set when they take the values ``x`` [SI or factors]."""
    out: dict[str, float] = {}
    for p, value in zip(parameters, x):
        for path in p.paths:
            out[path] = float(value) if p.kind == "value" else float(get_path(loaded.system, path)) * float(value)
    return out


def variant(loaded: LoadedSystem, parameters: list[UncertainParameter], x, label: str) -> LoadedSystem:
    """``loaded`` with the parameters at ``x``."""
    return with_values(loaded, changes(loaded, parameters, x), origin_suffix=label)
