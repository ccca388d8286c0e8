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
value and stay inside what it accepts) are in system/uncertainty_checks.py.
"""

from __future__ import annotations

from typing import Literal

from pydantic import field_validator, model_validator

from .base import ParameterPaths, Strict

#: The distributions a declared uncertainty may take.
DISTRIBUTIONS = ("uniform", "triangular", "normal", "lognormal")


class UncertaintyParameter(Strict):
    """One declared uncertainty: a value (or values scaled together) and its distribution."""

    kind: Literal["value", "scale"]
    paths: ParameterPaths
    distribution: Literal["uniform", "triangular", "normal", "lognormal"]
    range: tuple[str | float, str | float] | None = None
    sigma: str | float | None = None
    reason: str
    description: str = ""

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
