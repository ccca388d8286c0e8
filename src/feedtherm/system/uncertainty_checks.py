"""The rules of a description's declared uncertainties that need the rest of the description.

The section itself (system/uncertainties.py) is part of the schema.  Its paths must name values,
and its ranges contain the declared value and stay inside what it accepts (an expansion
coefficient's stays positive): :func:`uncertainty_problems`, which ``feedtherm check`` lists and
the loader applies after the description's own checks (so that a bad value is reported as such,
not as a prior that excludes it).
"""

from __future__ import annotations

import math

from .paths import expand_path, get_path, refusal_at, si_unit_at, unresolved
from .quantities import same_dimension, to_base_si
from .schema import FeedSystem
from .uncertainties import UncertaintyParameter


def _number(value, where: str, unit: str) -> float:
    """``value`` in SI base units; it must have the dimension of ``unit`` ("" for a number)."""
    try:
        number = to_base_si(value)
    except ValueError as exc:
        raise _Problem(where, str(exc)) from None
    if not same_dimension(value, unit):
        raise _Problem(where, f"{value!r} is not " + (f"a quantity in {unit} or a unit of its dimension" if unit
                                                      else "a plain number (the value has no unit)"))
    return number


def uncertainty_problems(system: FeedSystem) -> list[tuple[str, str, str]]:
    """``(field path, reason, severity)`` for the first problem of each declared uncertainty.

    Errors (``feedtherm check`` and the loader refuse the description): a range or sigma of
    another dimension than the value, a range that excludes the declared value (1 for a scale)
    or is reversed, a range (or a normal's or lognormal's reach without one) that leaves what the
    value accepts (its sign and accepted range: an expansion coefficient stays positive), a sigma
    that is not positive, the paths of a ``value`` parameter holding
    different values, a lognormal on values that are not positive, a path that names no number
    (a typo, or a loss model swapped in the description that left the path behind).
    """
    if system.uncertainty is None:
        return []
    out = []
    for name, spec in system.uncertainty.parameters.items():
        try:
            _check(system, name, spec)
        except _Problem as problem:
            out.append((problem.path, problem.reason, problem.severity))
    return out


class _Problem(Exception):
    def __init__(self, path: str, reason: str, severity: str = "error"):
        super().__init__(f"{path}: {reason}")
        self.path, self.reason, self.severity = path, reason, severity


def _check(system: FeedSystem, name: str, spec: UncertaintyParameter) -> None:
    where = f"uncertainty.parameters.{name}"
    paths = []
    for path in spec.paths:
        why = unresolved(system, path)
        if why is not None:
            raise _Problem(f"{where}.paths", why)
        paths.extend(expand_path(system, path))
    values = [float(get_path(system, p)) for p in paths]
    if spec.kind == "value" and any(not math.isclose(v, values[0], rel_tol=1e-9, abs_tol=0.0) for v in values):
        raise _Problem(f"{where}.paths", f"a 'value' parameter sets one value at every path, but they hold "
                                         f"different values ({values[0]:g}, ...); use kind = \"scale\"")
    declared = values[0] if spec.kind == "value" else 1.0
    # a value's range and a normal's sigma are in the value's unit; factors and ln x have none
    unit = (si_unit_at(system, paths[0]) or "") if spec.kind == "value" else ""
    if spec.sigma is not None:
        sigma = _number(spec.sigma, f"{where}.sigma", "" if spec.distribution == "lognormal" else unit)
        if not sigma > 0:
            raise _Problem(f"{where}.sigma", f"must be positive, got {spec.sigma!r}")
    if spec.range is not None:
        low, high = (_number(b, f"{where}.range", unit) for b in spec.range)
        if not low < high:
            raise _Problem(f"{where}.range", "the lower bound must be below the upper")
        if not low <= declared <= high:
            what = "the declared factor 1" if spec.kind == "scale" else f"the declared value {declared:g} (SI)"
            raise _Problem(f"{where}.range", f"[{low:g}, {high:g}] (SI) excludes {what}; a prior that "
                                             f"excludes the description's own value contradicts it")
        if spec.distribution == "lognormal" and low <= 0:
            raise _Problem(f"{where}.range", "a lognormal distribution needs a positive range")
    if spec.distribution == "lognormal" and declared <= 0:
        raise _Problem(f"{where}.paths", "a lognormal distribution needs a positive declared value (its median)")
    if spec.range is not None:
        ends = (low, high)
    elif spec.distribution == "lognormal":
        ends = tuple(declared * math.exp(k * SAMPLED_SIGMAS * sigma) for k in (-1, 1))
    else:
        ends = tuple(declared + k * SAMPLED_SIGMAS * sigma for k in (-1, 1))
    _reach_accepted(system, where, spec, dict(zip(paths, values)), ends)


#: How far a normal or lognormal distribution without a range reaches [standard deviations]:
#: the sampler draws quantiles no closer than 1e-12 to 0 and 1 (analysis/uncertainty/sampling.py,
#: EDGE), 7.03 standard deviations from the centre.
SAMPLED_SIGMAS = 7.04


def _reach_accepted(system: FeedSystem, where: str, spec: UncertaintyParameter, values: dict[str, float],
                    ends: tuple[float, float]) -> None:
    """Every value the distribution reaches is one its paths accept: the same sign, Limit and
    bounds the declared value passed (an expansion coefficient stays positive, a tcr inside its
    range).  ``ends``: how far it reaches, a range's ends or, without a range, SAMPLED_SIGMAS
    standard deviations (a factor's, times each path's value)."""
    for path, value in values.items():
        for end in ends:
            reached = end if spec.kind == "value" else value * end
            reason = refusal_at(system, path, reached)
            if reason is None:
                continue
            if spec.range is not None:
                raise _Problem(f"{where}.range", f"reaches {reached:g} (SI) at {path}, which that value does not "
                                                 f"accept: {reason}")
            raise _Problem(f"{where}.sigma", f"a {spec.distribution} distribution without a range reaches "
                                               f"{reached:g} (SI) at {path} ({SAMPLED_SIGMAS:g} standard deviations, "
                                               f"as far as the samples go), which that value does not accept: "
                                               f"{reason}; give range = [low, high] inside what it accepts")
