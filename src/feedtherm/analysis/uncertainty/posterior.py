"""The state of knowledge after a calibration: the calibrated description, the fitted
parameters' posterior, and the declared priors of the values the calibration did not fit.

A ``feedtherm calibrate`` folder holds ``calibrated.toml`` (the description with the fitted
values) and ``calibration.json`` (per parameter the fitted value, its standard error, bounds,
paths and kind, and the correlation of the fit).  The fitted parameters are taken as jointly
normal around the fit with those standard errors and that correlation (the Gauss-Newton
approximation the calibration's own prediction intervals use), clipped to the fit's bounds
(:func:`~.sampling.to_values`).  A declared uncertainty whose paths the calibration fitted is
replaced by the posterior; the others keep their prior.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...errors import FeedthermError
from ...system.load import LoadedSystem, load_system
from ...system.overlay import with_overlay
from ...system.paths import si_unit_at
from .declared import resolve_uncertainties
from .sampling import POSTERIOR, to_values
from .types import UncertainParameter


@dataclass
class Posterior:
    """What a calibration folder says, ready to sample."""

    loaded: LoadedSystem  # the calibrated description
    parameters: list[UncertainParameter]  # the fitted ones (POSTERIOR) first, then the priors kept
    correlation: np.ndarray  # over the fitted ones, in their order
    summary: dict  # for the study's record: fit conditions, fitted parameters, replaced priors

    @property
    def nominal(self) -> LoadedSystem:
        """The description of the set's nominal run: the calibrated one."""
        return self.loaded

    def values(self, u: np.ndarray) -> np.ndarray:
        """The parameter values (n, d) at the unit points ``u`` (n, d) (:func:`~.sampling.to_values`)."""
        return to_values(self.parameters, u, self.correlation)


def posterior_parameters(summary: dict, calibrated: LoadedSystem, where: str) -> tuple[list[UncertainParameter], np.ndarray]:
    """The fitted parameters of ``calibration.json`` as :data:`~.sampling.POSTERIOR` parameters
    of the calibrated description, and their correlation matrix.

    A ``value`` parameter is normal around the fitted value; a ``scale`` parameter is a factor
    on the calibrated values (which hold original × fitted already): normal around 1 with
    standard deviation se / fitted, bounds divided likewise.
    """
    conditions = ", ".join(summary.get("fit_conditions", []))
    out = []
    for name, entry in summary["parameters"].items():
        try:
            kind, fitted, se = entry["kind"], float(entry["fitted"]), float(entry["standard_error"])
            lower, upper = (float(b) for b in entry["bounds"])
            paths = tuple(entry["paths"])
        except (KeyError, TypeError, ValueError):
            raise FeedthermError(f"{where}: parameter {name!r} lacks kind, fitted, standard_error, bounds or paths") from None
        if kind not in ("value", "scale") or not all(map(math.isfinite, (fitted, se, lower, upper))) or se < 0 \
                or not paths or (kind == "scale" and fitted <= 0):
            raise FeedthermError(f"{where}: parameter {name!r} has no usable fit (kind {kind!r}, "
                                 f"fitted {fitted:g} +- {se:g})")
        f = fitted if kind == "scale" else 1.0  # a scale's posterior is relative to the calibrated values
        try:
            unit = (si_unit_at(calibrated.system, paths[0]) or "") if kind == "value" else ""
        except (KeyError, IndexError, AttributeError):
            raise FeedthermError(f"{where}: parameter {name!r}: {paths[0]!r} is not a value of the calibrated description") from None
        out.append(UncertainParameter(
            name=name, description=f"fitted by calibration on {conditions}", kind=kind, paths=paths,
            declared=fitted / f, distribution=POSTERIOR, low=lower / f, high=upper / f, sigma=se / f, unit=unit,
            reason=(f"fitted by calibration on {conditions}: {fitted:.4g} +- {se:.3g} (1 standard error), "
                    f"{'a factor on the declared values, ' if kind == 'scale' else ''}correlated with the other fitted "
                    f"parameters; normal around the fit, clipped to its bounds [{lower:g}, {upper:g}]"
                    + (f" (the calibration says: {entry['note']})" if entry.get("note") else "")),
            provenance=f"calibration: {where}"))
    names = [p.name for p in out]
    correlation = summary.get("correlation") or {}
    order = correlation.get("parameters", [])
    matrix = np.asarray(correlation.get("matrix", []), dtype=float)
    if sorted(order) != sorted(names) or matrix.shape != (len(order), len(order)):
        raise FeedthermError(f"{where}: the correlation matrix does not match the fitted parameters")
    index = [order.index(n) for n in names]
    return out, matrix[np.ix_(index, index)]


def read_posterior(folder: Path, original: LoadedSystem, summary: dict) -> Posterior:
    """The calibrated set of ``folder`` (``summary``: its calibration.json, already read)."""
    where = str(Path(folder) / "calibration.json")
    toml = Path(folder) / "calibrated.toml"
    if not toml.is_file():
        raise FeedthermError(f"--calibration: {toml} is missing (feedtherm calibrate writes it)")
    calibrated = with_overlay(load_system(str(toml)), original.overlay)  # runs as the original does
    fitted, correlation = posterior_parameters(summary, calibrated, where)
    fitted_paths = {p for parameter in fitted for p in parameter.paths}
    kept = []
    if calibrated.system.uncertainty is not None and calibrated.system.uncertainty.parameters:
        for prior in resolve_uncertainties(calibrated):
            rest = tuple(p for p in prior.paths if p not in fitted_paths)
            if rest:
                kept.append(prior if rest == prior.paths else _with_paths(prior, rest))
    declared = resolve_uncertainties(original) if original.system.uncertainty is not None else []
    replaced = [p.name for p in declared if fitted_paths & set(p.paths)]
    record = {
        "folder": str(folder),
        "fit_conditions": list(summary.get("fit_conditions", [])),
        "parameters": {p.name: {"kind": p.kind, "fitted": summary["parameters"][p.name]["fitted"],
                                "standard_error": summary["parameters"][p.name]["standard_error"],
                                "bounds": summary["parameters"][p.name]["bounds"], "paths": list(p.paths)}
                       for p in fitted},
        "correlation": {"parameters": [p.name for p in fitted], "matrix": correlation.tolist()},
        "replaced": replaced,
    }
    return Posterior(calibrated, fitted + kept, correlation, record)


def _with_paths(prior: UncertainParameter, paths: tuple[str, ...]) -> UncertainParameter:
    from dataclasses import replace

    return replace(prior, paths=paths, reason=f"{prior.reason} (the paths the calibration fitted left out)")
