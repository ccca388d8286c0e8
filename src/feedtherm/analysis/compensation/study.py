"""A compensation study: cycles, sensor selection for K = 1 … 6, laws judged on held-out machines.

:func:`parse_sensors` checks ``--sensors`` (a count K, or names of candidates) before anything
runs; :func:`run_study` simulates the three sets of cycles (:mod:`.data`), chooses sensors
greedily for the static and the lagged regression (:mod:`.selection`), fits the law asked for,
the law on the description's own sensors (T1-T5 on the paper bench) for comparison, and
judges each on the test cycles (:mod:`.metrics`).
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass

from ...constants import AMBIENT_SENSOR
from ...errors import FeedthermError
from ...system.load import LoadedSystem
from ..candidates import Candidate, candidate_sensors
from .data import CycleSet, StudySettings, simulate_set
from .metrics import Residuals, residuals
from .regression import DEFAULT_LAGS, RegressionLaw
from .selection import fit_on, greedy_selection, predictor

#: The error against K is shown for K = 1 … this (issue 16), or up to the K asked for.
CURVE_SENSORS = 6
#: The laws of a study: name -> lag time constants [s] (:mod:`.regression`).
LAWS = {"regression": (), "regression_lags": DEFAULT_LAGS}

_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


@dataclass(frozen=True)
class LawResult:
    """One law: its kind, its sensors, the fitted law and its errors on the held-out cycles."""

    kind: str  # a key of LAWS
    sensors: tuple[str, ...]
    law: RegressionLaw
    validation: Residuals
    test: Residuals

    @property
    def k(self) -> int:
        return len(self.sensors)


@dataclass(frozen=True)
class StudyResult:
    settings: StudySettings
    candidates: dict[str, Candidate]
    sets: dict[str, CycleSet]
    curves: dict[str, list[LawResult]]  # law kind -> the greedy sets for K = 1 … n
    chosen: dict[str, LawResult]  # law kind -> the law asked for (K greedy sensors, or the named ones)
    declared: dict[str, LawResult]  # law kind -> the law on the description's own sensors
    request: int | tuple[str, ...]

    def best(self, max_sensors: int = 3) -> LawResult:
        """The law with the smallest validation RMS among the curves' laws of at most ``max_sensors`` sensors."""
        pool = [r for curve in self.curves.values() for r in curve if r.k <= max_sensors]
        return min(pool, key=lambda r: r.validation.rms)


def parse_sensors(text: str, candidates: dict[str, Candidate]) -> int | tuple[str, ...]:
    """``--sensors``: a count K (1 … the number of candidates) or comma-separated candidate names.

    Raises
    ------
    FeedthermError
        One line: K not a positive whole number or larger than the candidates, an unknown name
        (with the closest ones), a name listed twice.
    """
    text = text.strip()
    if re.fullmatch(r"[+-]?\d+", text):
        k = int(text)
        if k < 1:
            raise FeedthermError(f"--sensors: K must be at least 1, got {k}")
        if k > len(candidates):
            raise FeedthermError(f"--sensors: K = {k} but there are {len(candidates)} candidate positions")
        return k
    names = tuple(item.strip() for item in text.split(","))
    for name in names:
        if not name or not _NAME.fullmatch(name):
            raise FeedthermError(f"--sensors: {text!r} is neither a count nor a list of sensor names")
        if name not in candidates:
            raise FeedthermError(f"--sensors: no candidate sensor {name!r}{_closest(name, candidates)}")
    if len(set(names)) != len(names):
        raise FeedthermError(f"--sensors: a sensor is listed twice in {text!r}")
    return names


def _closest(name: str, candidates: dict[str, Candidate]) -> str:
    import difflib

    close = difflib.get_close_matches(name, list(candidates), n=3)
    return f"; did you mean {', '.join(close)}?" if close else ""


def run_study(loaded: LoadedSystem, settings: StudySettings, request: int | tuple[str, ...],
              progress: Callable[[float], None] | None = None) -> StudyResult:
    """Simulate the cycles, choose sensors, fit and judge the laws (see the module's notes)."""
    candidates = candidate_sensors(loaded.system)
    if isinstance(request, int) and request > len(candidates):
        raise FeedthermError(f"--sensors: K = {request} but there are {len(candidates)} candidate positions")
    sets = {}
    names = ("train", "validation", "test")
    for i, name in enumerate(names):
        inner = None if progress is None else (lambda f, i=i: progress((i + f) / len(names)))
        sets[name] = simulate_set(loaded, candidates, settings, name, inner)
    n_curve = max(CURVE_SENSORS, request if isinstance(request, int) else 0)
    n_curve = min(n_curve, len(candidates))
    curves, chosen, declared = {}, {}, {}
    own = tuple(n for n in loaded.system.sensors if n != AMBIENT_SENSOR)
    for kind, lags in LAWS.items():
        steps = greedy_selection(sets["train"], sets["validation"], n_curve, lags)
        curves[kind] = [_judge(kind, step.law, sets) for step in steps]
        if isinstance(request, int):
            chosen[kind] = curves[kind][request - 1]
        else:
            chosen[kind] = _judge(kind, fit_on(sets["train"], request, lags), sets)
        if own:
            declared[kind] = _judge(kind, fit_on(sets["train"], own, lags), sets)
    return StudyResult(settings, candidates, sets, curves, chosen, declared, request)


def _judge(kind: str, law: RegressionLaw, sets: dict[str, CycleSet]) -> LawResult:
    names = sets["test"].names
    return LawResult(kind, law.sensors, law, residuals(predictor(law, names), sets["validation"]),
                     residuals(predictor(law, names), sets["test"]))
