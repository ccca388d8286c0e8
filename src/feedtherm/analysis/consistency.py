"""Measurement consistency: which measured points cannot all hold, from the measurements alone.

No thermal model is run.  The checks use only the measured values and the operating points
the description states (motor speeds, ambient temperature), and three properties any feed
drive near its thermal equilibrium has:

1. **Elongation follows the temperatures.**  In linear thermoelasticity with a fixed reference
   temperature the screw's elongation is a linear functional of its temperature field; across
   conditions whose fields have a similar shape it is an affine function of the mean measured
   temperature, ``D = a + s·T̄`` with one sensitivity ``s`` [µm/K] for the whole set (the same
   screw, the same length, the same material).  Each condition is left out in turn: the others
   give ``a`` and ``s``; a condition whose elongation lies far from that line while the others
   lie on it is flagged.  Only the one condition whose removal makes the rest consistent is
   flagged, so a set that is scattered everywhere is reported as such, not pruned.
2. **A faster drive is not cooler.**  At the same ambient temperature, a condition in which
   both motors turn at least as fast as in another has no lower temperature rise or
   elongation at any point.
3. **An ambient shift moves the rises little.**  At the same motor speeds, the rise of each
   sensor above the ambient temperature changes only through the weak temperature dependence
   of convection and radiation.

Tolerances are ``k`` times the standard uncertainty of the compared quantity, from the stated
uncertainties of one measured temperature ``sigma_t`` [K] and one elongation ``sigma_d`` [µm]
(the description's calibration weights).  A flagged point is never dropped silently: callers
show it with its reason, and calibration leaves it out of the fit visibly.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

from ..constants import KELVIN_OFFSET, RPM_PER_RAD_S
from ..system.measurements import ELONGATION_QUANTITY, MeasurementSet

#: Coverage factor of the tolerances (about 99.7 % for a normal error).
COVERAGE = 3.0
#: Conditions closer than this in ambient temperature [K] are "at the same ambient".
SAME_AMBIENT_K = 0.5
#: Speeds closer than this [rpm] are "the same speed".
SAME_SPEED_RPM = 1.0
#: A measured temperature that, read as kelvin, lies this close to its ambient [K] is suspected of
#: being in kelvin: a feed drive's sensors rise tens of kelvin above the air, never hundreds.
KELVIN_HINT_RISE_K = 100.0


@dataclass(frozen=True)
class OperatingPoint:
    """What the description states about a condition: motor speeds [rpm], ambient [°C]."""

    screw_rpm: float
    nut_rpm: float
    ambient_c: float


@dataclass(frozen=True)
class Flag:
    """A measured value that cannot hold together with the others, and why."""

    condition: str
    quantity: str
    check: str  # "elongation_law", "speed_monotone" or "ambient_shift"
    reason: str
    excess: float  # how far the value lies outside the tolerance, [K] or [µm]


@dataclass(frozen=True)
class ElongationLaw:
    """``D = intercept + slope·T̄`` fitted to the conditions that agree with one another."""

    slope_um_per_k: float
    intercept_um: float
    conditions: list[str]
    max_residual_um: float
    proxy: list[str]  # the temperature sensors whose mean is T̄


@dataclass(frozen=True)
class ConsistencyReport:
    flags: list[Flag]
    law: ElongationLaw | None
    notes: list[str]

    def flag_for(self, condition: str, quantity: str) -> Flag | None:
        return next((f for f in self.flags if f.condition == condition and f.quantity == quantity), None)

    def excluded(self) -> set[tuple[str, str]]:
        return {(f.condition, f.quantity) for f in self.flags}


def check_consistency(data: MeasurementSet, points: dict[str, OperatingPoint], *, sigma_t: float = 0.5,
                      sigma_d: float = 2.0, coverage: float = COVERAGE) -> ConsistencyReport:
    """Run the three checks on ``data`` (conditions missing from ``points`` are skipped)."""
    values = {c: {r.quantity: r.measured for r in data.for_condition(c)} for c in data.conditions() if c in points}
    notes: list[str] = []
    flags, law = _elongation_law(values, sigma_t, sigma_d, coverage, notes)
    flags += _speed_monotone(values, points, sigma_t, sigma_d, coverage)
    flags += _ambient_shift(values, points, sigma_t, coverage)
    return ConsistencyReport(flags, law, notes)


def _temperature_sensors(values: dict[str, dict[str, float]]) -> list[str]:
    """The temperatures measured in every condition, in the order of the first."""
    first = next(iter(values.values()), {})
    return [q for q in first if q != ELONGATION_QUANTITY and all(q in v for v in values.values())]


def _affine_fit(x: np.ndarray, y: np.ndarray) -> tuple[float, float, np.ndarray]:
    """Least-squares ``y = a + s x``: (a, s, residuals)."""
    A = np.column_stack([np.ones_like(x), x])
    (a, s), *_ = np.linalg.lstsq(A, y, rcond=None)
    return float(a), float(s), y - (a + s * x)


def _left_out(x: np.ndarray, y: np.ndarray, i: int, sigma_d: float, sigma_mean_t: float):
    """Fit the others, predict point ``i``: (intercept, slope, predicted, its standard uncertainty).

    The uncertainty combines the point's own measurement, the fitted line's standard error at
    ``x[i]`` (from ``sigma_d``) and the temperature uncertainty carried through the slope.
    """
    keep = np.arange(len(x)) != i
    a, s, _ = _affine_fit(x[keep], y[keep])
    xk = x[keep]
    leverage = 1 / len(xk) + (x[i] - xk.mean()) ** 2 / np.sum((xk - xk.mean()) ** 2)
    sigma = np.sqrt((sigma_d**2 + (s * sigma_mean_t) ** 2) * (1 + leverage))
    return a, s, a + s * x[i], float(sigma)


def _all_on_one_line(x, y, sigma_d, sigma_mean_t, coverage) -> bool:
    """Every point within ``coverage`` uncertainties of the line through the others.

    Left-out (deleted) residuals, not in-sample ones: a point far out at the end of the
    range pulls an in-sample line towards itself and would hide.
    """
    for i in range(len(x)):
        _, _, predicted, sigma = _left_out(x, y, i, sigma_d, sigma_mean_t)
        if abs(y[i] - predicted) > coverage * sigma:
            return False
    return True


def _elongation_law(values, sigma_t, sigma_d, coverage, notes):
    with_d = [c for c, v in values.items() if ELONGATION_QUANTITY in v]
    sensors = _temperature_sensors({c: values[c] for c in with_d})
    if len(with_d) < 4 or not sensors:
        notes.append("elongation law: needs the elongation and the same temperatures at four or more conditions; "
                     f"{len(with_d)} given, not checked")
        return [], None
    x = np.array([np.mean([values[c][q] for q in sensors]) for c in with_d])
    y = np.array([values[c][ELONGATION_QUANTITY] for c in with_d])
    sigma_mean_t = sigma_t / np.sqrt(len(sensors))
    if _all_on_one_line(x, y, sigma_d, sigma_mean_t, coverage):
        a, s, r = _affine_fit(x, y)
        return [], ElongationLaw(s, a, with_d, float(np.max(np.abs(r))), sensors)
    candidates = []
    for i, condition in enumerate(with_d):
        keep = np.arange(len(with_d)) != i
        a, s, predicted, sigma = _left_out(x, y, i, sigma_d, sigma_mean_t)
        deviation = y[i] - predicted
        if s > 0 and abs(deviation) > coverage * sigma and _all_on_one_line(x[keep], y[keep], sigma_d, sigma_mean_t, coverage):
            candidates.append((i, condition, a, s, predicted, deviation, sigma))
    if len(candidates) != 1:
        _, _, r_all = _affine_fit(x, y)
        notes.append(f"elongation law: the measured elongations do not lie on one line in the mean temperature "
                     f"(largest residual {np.max(np.abs(r_all)):.1f} µm) and no single condition explains it; "
                     "nothing flagged")
        return [], None
    i, condition, a, s, predicted, deviation, sigma = candidates[0]
    others = [c for c in with_d if c != condition]
    residuals = np.delete(y, i) - (a + s * np.delete(x, i))
    reason = (f"elongation {y[i]:.1f} µm at a mean measured temperature of {x[i]:.2f} °C; "
              f"the other conditions ({', '.join(others)}) lie within {np.max(np.abs(residuals)):.1f} µm of "
              f"D = {a:.1f} µm + {s:.2f} µm/K · T̄, which gives {predicted:.1f} µm here "
              f"({deviation:+.1f} µm, {abs(deviation) / sigma:.1f} standard uncertainties)")
    law = ElongationLaw(s, a, others, float(np.max(np.abs(residuals))), sensors)
    return [Flag(condition, ELONGATION_QUANTITY, "elongation_law", reason, float(abs(deviation) - coverage * sigma))], law


def _speed_monotone(values, points, sigma_t, sigma_d, coverage):
    """Property 2 for every pair of conditions at the same ambient.  A value that breaks it with
    several conditions, where every pair it breaks involves that one condition, is that condition's
    (the slowest condition's temperatures written in kelvin are hotter than two faster conditions,
    which agree with each other):
    flagged there once.  Otherwise each faster condition that is cooler is flagged, as seen."""
    found = []  # (slow, fast, quantity, drop, tolerance) in the order of the pairs
    for slow, fast in itertools.permutations(values, 2):
        p, q = points[slow], points[fast]
        if abs(p.ambient_c - q.ambient_c) > SAME_AMBIENT_K:
            continue
        faster = abs(q.screw_rpm) >= abs(p.screw_rpm) and abs(q.nut_rpm) >= abs(p.nut_rpm)
        same = abs(q.screw_rpm - p.screw_rpm) < SAME_SPEED_RPM and abs(q.nut_rpm - p.nut_rpm) < SAME_SPEED_RPM
        if not faster or same:
            continue
        for quantity, measured in values[fast].items():
            if quantity not in values[slow]:
                continue
            sigma = sigma_d if quantity == ELONGATION_QUANTITY else sigma_t
            drop = values[slow][quantity] - measured
            tolerance = coverage * np.sqrt(2.0) * sigma
            if drop > tolerance:
                found.append((slow, fast, quantity, drop, tolerance))
    flags = []
    for quantity in dict.fromkeys(v[2] for v in found):
        pairs = [v for v in found if v[2] == quantity]
        odd = _odd_one_out(pairs)
        if odd is not None:
            flags.append(_odd_flag(odd, quantity, pairs, values, points))
            continue
        for slow, fast, _, drop, tolerance in pairs:
            p, q = points[slow], points[fast]
            reason = (f"{drop:.1f} {_unit(quantity)} below condition {slow}, although both motors turn at least as "
                      f"fast ({_speeds(q)} against {_speeds(p)}) at the same ambient temperature")
            flags.append(Flag(fast, quantity, "speed_monotone", reason, float(drop - tolerance)))
    return flags


def _odd_one_out(pairs) -> str | None:
    """The one condition in every pair of ``pairs`` (slow, fast, ...) where there are two pairs or more:
    without it the others agree.  None where one pair cannot tell which side is off."""
    if len(pairs) < 2:
        return None
    common = set.intersection(*({slow, fast} for slow, fast, *_ in pairs))
    return next(iter(common)) if len(common) == 1 else None


def _odd_flag(condition, quantity, pairs, values, points) -> Flag:
    """The flag of ``condition``, off against every condition of ``pairs``: above the faster ones,
    below the slower ones."""
    unit = _unit(quantity)
    hotter = [(fast, drop) for slow, fast, _, drop, _ in pairs if slow == condition]
    cooler = [(slow, drop) for slow, fast, _, drop, _ in pairs if fast == condition]
    parts = []
    if hotter:
        names = ", ".join(c for c, _ in hotter)
        parts.append(f"{max(d for _, d in hotter):.1f} {unit} above condition{'s' * (len(hotter) > 1)} {names}, "
                     f"although {'their' if len(hotter) > 1 else 'its'} motors turn at least as fast "
                     f"({', '.join(_speeds(points[c]) for c, _ in hotter)} against {_speeds(points[condition])})")
    if cooler:
        names = ", ".join(c for c, _ in cooler)
        parts.append(f"{max(d for _, d in cooler):.1f} {unit} below condition{'s' * (len(cooler) > 1)} {names}, "
                     f"although both motors turn at least as fast ({_speeds(points[condition])} against "
                     f"{', '.join(_speeds(points[c]) for c, _ in cooler)})")
    reason = (f"{' and '.join(parts)} at the same ambient temperature; those conditions agree with one another"
              f"{_kelvin_hint(values[condition][quantity], quantity, points[condition])}")
    excess = max(drop - tolerance for *_, drop, tolerance in pairs)
    return Flag(condition, quantity, "speed_monotone", reason, float(excess))


def _kelvin_hint(value: float, quantity: str, point: OperatingPoint) -> str:
    """Where a temperature read as kelvin would lie near its ambient, as a feed drive's do: say so."""
    if quantity == ELONGATION_QUANTITY or not abs(value - KELVIN_OFFSET - point.ambient_c) < KELVIN_HINT_RISE_K:
        return ""
    return (f"; {value:g} °C is {value - KELVIN_OFFSET:.1f} °C if read as kelvin: is the file's value in K "
            "where °C are expected?")


def _unit(quantity: str) -> str:
    return "µm" if quantity == ELONGATION_QUANTITY else "K"


def _speeds(point: OperatingPoint) -> str:
    return f"{point.screw_rpm:g}/{point.nut_rpm:g} rpm"


def _ambient_shift(values, points, sigma_t, coverage):
    flags = []
    for a, b in itertools.combinations(values, 2):
        p, q = points[a], points[b]
        if abs(p.screw_rpm - q.screw_rpm) >= SAME_SPEED_RPM or abs(p.nut_rpm - q.nut_rpm) >= SAME_SPEED_RPM:
            continue
        if abs(p.ambient_c - q.ambient_c) <= SAME_AMBIENT_K:
            continue
        for quantity in values[a]:
            if quantity == ELONGATION_QUANTITY or quantity not in values[b]:
                continue
            rise_a = values[a][quantity] - p.ambient_c
            rise_b = values[b][quantity] - q.ambient_c
            tolerance = coverage * np.sqrt(2.0) * sigma_t
            if abs(rise_a - rise_b) > tolerance:
                reason = (f"rise above the ambient {rise_b:.1f} K, against {rise_a:.1f} K at condition {a} "
                          f"with the same motor speeds and a {q.ambient_c - p.ambient_c:+.1f} K different ambient")
                flags.append(Flag(b, quantity, "ambient_shift", reason, float(abs(rise_a - rise_b) - tolerance)))
    return flags


def check_description_measurements(system, data: MeasurementSet) -> ConsistencyReport:
    """:func:`check_consistency` at a description's operating points, with the uncertainties its
    ``[calibration]`` declares (0.5 K and 2 µm when it declares none)."""
    weights = system.calibration
    return check_consistency(data, operating_points(system),
                             sigma_t=weights.temperature_sigma if weights else 0.5,
                             sigma_d=(weights.elongation_sigma if weights else 2e-6) * 1e6)


def operating_points(system) -> dict[str, OperatingPoint]:
    """The stated operating point of every condition of a description."""
    return {name: OperatingPoint(c.screw_speed * RPM_PER_RAD_S, c.nut_speed * RPM_PER_RAD_S, c.ambient - KELVIN_OFFSET)
            for name, c in system.conditions.items()}


__all__ = ["check_consistency", "check_description_measurements", "operating_points", "ConsistencyReport", "ElongationLaw", "Flag", "OperatingPoint"]
