"""Declared uncertainties: the distribution of an assumed value, with its reason.

A description's optional ``[uncertainty.parameters.<name>]`` tables say how far an assumed value
(or a group of values with one physical cause) may lie from the value declared, and why::

    [uncertainty.parameters.screw_nut_friction]
    kind = "value"                 # or "scale": a factor on every path's declared value
    paths = ["sources.screw_nut.friction_coefficient"]
    distribution = "uniform"       # uniform | triangular | normal | lognormal
    range = [0.05, 0.15]           # bounds (truncation for normal/lognormal), quantities allowed
    reason = "lubricated steel on bronze: 0.05-0.15 in handbooks"

``triangular``'s mode, ``normal``'s mean and ``lognormal``'s median are the declared value
(1 for a scale): a prior centred elsewhere would contradict the description's own value.
``sigma`` is a normal distribution's standard deviation (in the value's unit) or a lognormal
one's of ln x.  The section changes no value: ``feedtherm uncertainty`` samples it.

The rules that need the rest of the description (paths name values, ranges contain the declared
value) are checked by :func:`check_uncertainties` when the description is loaded.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Literal

from pydantic import field_validator, model_validator

from .base import Strict

if TYPE_CHECKING:  # pragma: no cover
    from .schema import FeedSystem

#: The distributions a declared uncertainty may take.
DISTRIBUTIONS = ("uniform", "triangular", "normal", "lognormal")


class UncertaintyParameter(Strict):
    """One declared uncertainty: a value (or values scaled together) and its distribution."""

    kind: Literal["value", "scale"]
    paths: list[str]
    distribution: Literal["uniform", "triangular", "normal", "lognormal"]
    range: tuple[str | float, str | float] | None = None
    sigma: str | float | None = None
    reason: str
    description: str = ""

    @field_validator("paths")
    @classmethod
    def _some_paths(cls, value: list[str]) -> list[str]:
        if not value:
            raise ValueError("name at least one path")
        return value

    @field_validator("reason")
    @classmethod
    def _a_reason(cls, value: str) -> str:
        if not value.strip():
            raise ValueError("an uncertainty needs a reason (a source or an engineering argument)")
        return value

    @model_validator(mode="after")
    def _fields_of_the_distribution(self) -> "UncertaintyParameter":
        if self.distribution in ("uniform", "triangular"):
            if self.range is None:
                raise ValueError(f"range: a {self.distribution} distribution needs range = [low, high]")
            if self.sigma is not None:
                raise ValueError(f"sigma: a {self.distribution} distribution has no sigma (its range says it all)")
        elif self.sigma is None:
            raise ValueError(f"sigma: a {self.distribution} distribution needs sigma "
                             + ("(its standard deviation)" if self.distribution == "normal" else "(the standard deviation of ln x)"))
        return self


class Uncertainty(Strict):
    parameters: dict[str, UncertaintyParameter]


def _number(value, where: str, unit: str) -> float:
    """``value`` in SI base units; it must have the dimension of ``unit`` ("" for a number)."""
    from .quantities import same_dimension, to_base_si

    try:
        number = to_base_si(value)
    except ValueError as exc:
        raise ValueError(f"{where}: {exc}") from None
    if not same_dimension(value, unit):
        raise ValueError(f"{where}: {value!r} is not " + (f"a quantity in {unit} or a unit of its dimension" if unit
                                                          else "a plain number (the value has no unit)"))
    return number


def check_uncertainties(system: "FeedSystem") -> None:
    """Raise ``ValueError("uncertainty.parameters.<name>.<field>: <reason>")`` for the first bad declaration.

    Paths must name numeric values (``[*]`` expands to every index); the values of a ``value``
    parameter must be one value; the range must contain the declared value (1 for a scale);
    ``sigma`` must be positive; a lognormal's values and range positive.
    """
    if system.uncertainty is None:
        return
    from .variants import expand_path, get_path, si_unit_at  # variants imports the loader, which imports the schema

    for name, spec in system.uncertainty.parameters.items():
        where = f"uncertainty.parameters.{name}"
        paths = []
        for path in spec.paths:
            try:
                expanded = expand_path(system, path)
                values = [get_path(system, p) for p in expanded]
            except (KeyError, IndexError, AttributeError, TypeError):
                raise ValueError(f"{where}.paths: {path!r} does not name a value of the description") from None
            if not values or any(isinstance(v, bool) or not isinstance(v, (int, float)) for v in values):
                raise ValueError(f"{where}.paths: {path!r} does not name a number")
            paths.extend(expanded)
        values = [float(get_path(system, p)) for p in paths]
        if spec.kind == "value" and any(not math.isclose(v, values[0], rel_tol=1e-9, abs_tol=0.0) for v in values):
            raise ValueError(f"{where}.paths: a 'value' parameter sets one value at every path, but they hold "
                             f"different values ({values[0]:g}, ...); use kind = \"scale\"")
        declared = values[0] if spec.kind == "value" else 1.0
        # a value's range and a normal's sigma are in the value's unit; factors and ln x have none
        unit = (si_unit_at(system, paths[0]) or "") if spec.kind == "value" else ""
        if spec.sigma is not None:
            sigma = _number(spec.sigma, f"{where}.sigma", "" if spec.distribution == "lognormal" else unit)
            if not sigma > 0:
                raise ValueError(f"{where}.sigma: must be positive, got {spec.sigma!r}")
        if spec.range is not None:
            low, high = (_number(b, f"{where}.range", unit) for b in spec.range)
            if not low < high:
                raise ValueError(f"{where}.range: the lower bound must be below the upper")
            if not low <= declared <= high:
                what = "the declared factor 1" if spec.kind == "scale" else f"the declared value {declared:g} (SI)"
                raise ValueError(f"{where}.range: [{low:g}, {high:g}] (SI) excludes {what}; a prior that "
                                 f"excludes the description's own value contradicts it")
            if spec.distribution == "lognormal" and low <= 0:
                raise ValueError(f"{where}.range: a lognormal distribution needs a positive range")
        if spec.distribution == "lognormal" and declared <= 0:
            raise ValueError(f"{where}.paths: a lognormal distribution needs a positive declared value (its median)")
