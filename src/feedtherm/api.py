"""The public API's verbs over the modules that do the work: load, calibrate, compensate.

``import feedtherm as ft`` exposes them with ``ft.simulate`` (docs/python-api.md), which is
:mod:`feedtherm.simulate` itself: that module is callable, a call runs
:func:`feedtherm.simulate.simulate` (the package's attribute ``simulate`` is always the module, see
there).  Each verb here is a thin wrapper: it takes a description loaded once (or a bench name or
a path, loaded here), checks what its caller passed and calls the functions the matching command
of the CLI calls.  The work stays where it is done (:func:`feedtherm.analysis.calibration.calibrate`,
:func:`feedtherm.analysis.compensation.study.run_study`).

An argument with a value the verbs cannot use raises :class:`~feedtherm.errors.ArgumentError`,
a ``ValueError`` whose message begins with the argument's name (``condition: no condition or
test 'nope' …``); the CLI says the same with the option's name (``--condition: …``).

The modules below are imported inside each verb, not at the top: ``ft.load`` then costs what
loading a description costs, and the studies' modules are read only when a study runs.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING

from .errors import ArgumentError

if TYPE_CHECKING:
    from .analysis.calibration import CalibrationResult
    from .analysis.compensation.study import StudyResult
    from .system.load import LoadedSystem

def load(system: str | os.PathLike, *, mode: str = "physics") -> LoadedSystem:
    """Load and validate a feed system's description.

    Parameters
    ----------
    system : str or path-like
        A bundled bench by name (``"paper"``, ``"ballscrew_example"``; ``feedtherm benches``
        lists them) or the path of a description's TOML file.
    mode : str
        ``"physics"`` (default): every heat and coefficient from the correlations; or the name of
        the overlay of printed values the bench supplies (``"paper"`` for the paper's bench: its
        printed heats and coefficients laid over the physics).

    Returns
    -------
    feedtherm.system.load.LoadedSystem
        The validated description (``.system``), where it came from (``.origin``) and its hash
        (``.sha256``), set to run in ``mode``.

    Raises
    ------
    feedtherm.errors.DescriptionError
        The file is missing, unreadable or invalid (the message names the file and the key).
    feedtherm.errors.FeedthermError
        ``mode`` names no overlay of the description.
    """
    from .plan import with_mode
    from .system.load import load_system

    if not isinstance(system, (str, os.PathLike)):
        raise ArgumentError("system", f"a bench name or a description's path, got {type(system).__name__}")
    return with_mode(load_system(os.fspath(system)), mode)


def calibrate(system: LoadedSystem | str | os.PathLike, *, fit: str | Sequence[str], params: str | Sequence[str],
              measured: str | os.PathLike | None = None, model: str = "fast", mesh: str | None = None,
              equilibrium: bool = True, workers: int = 1,
              progress: Callable[[float], None] | None = None) -> CalibrationResult:
    """Fit declared parameters of ``system`` to measured conditions and predict the others.

    What ``feedtherm calibrate`` does without writing files: the measurements are read and checked
    for consistency (flagged values are left out of the fit), the parameters are fitted by bounded
    least squares and every measured condition not fitted is predicted by the calibrated model.

    Parameters
    ----------
    system : LoadedSystem, str or path-like
        A description from :func:`load` (its mode is the runs'), or a bench name or path.
    fit : str or sequence of str
        The measured conditions or tests to fit (``["v5", "v20"]`` or ``"v5,v20"``).
    params : str or sequence of str
        Parameters declared under ``[calibration.parameters]`` with their bounds.
    measured : str or path-like, optional
        A measurement file; default the description's own (``meta.measurements``, else its bench's).
    model, mesh : str
        The model every run takes (default ``"fast"``) and its FE mesh, if it takes one.
    equilibrium : bool
        Also fit the stated equilibrium times of the fitted conditions.
    workers : int
        Runs side by side on a local cluster of this many processes (1: one after another; the
        numbers are the same either way).
    progress : callable, optional
        Called with the fraction done, from 0 to 1.

    Returns
    -------
    feedtherm.analysis.calibration.CalibrationResult
        The fitted values (``fitted``, in SI units) with standard errors and correlations, the
        residuals at the fitted conditions, the predictions of the held-out ones, and the
        calibrated description (``calibrated``, a LoadedSystem to simulate).

    Raises
    ------
    feedtherm.errors.ArgumentError
        ``params``: an undeclared parameter (with the closest declared name) or one without bounds;
        ``fit``: a condition without measurements, or fewer measured values than parameters;
        ``model``: an unknown model.
    """
    from .analysis.calibration import calibrate as fit_parameters
    from .analysis.calibration import resolve_parameters
    from .analysis.consistency import check_description_measurements
    from .analysis.validation import measurements_of

    loaded = _loaded(system)
    fit, params = _names("fit", fit), _names("params", params)
    data = measurements_of(loaded, None if measured is None else os.fspath(measured))
    resolve_parameters(loaded, params)  # unknown names and missing bounds fail before any run
    consistency = check_description_measurements(loaded.system, data)
    return fit_parameters(loaded, data, fit, params, progress=progress, consistency=consistency,
                          equilibrium=equilibrium, workers=workers, model=model, mesh=mesh)


def compensate(system: LoadedSystem | str | os.PathLike, *, sensors: int | str | Sequence[str] = 3, cycles: int = 8, seed: int = 0,
               duration: float | None = None, model: str = "fast", mesh: str | None = None,
               workers: int | None = None, progress: Callable[[float], None] | None = None) -> StudyResult:
    """Derive and judge thermal-error compensation laws for ``system`` on random duty cycles.

    What ``feedtherm compensate`` does without writing files: random cycles are simulated for
    training, validation and test, read through noisy sensors; sensors are chosen greedily, the
    regression laws and the model-based estimator fitted, and each judged on the held-out cycles
    (docs/compensation.md).

    Parameters
    ----------
    system : LoadedSystem, str or path-like
        A description with a feed drive, from :func:`load`, or a bench name or path.
    sensors : int, str or sequence of str
        How many sensors the laws read, chosen greedily among the candidates (K, default 3);
        ``"declared"``: the description's own sensors; or the candidates' names.
    cycles : int
        Random cycles in the training set (the validation and test sets follow from it).
    seed : int
        Seed of every random draw: the same seed gives the same study.
    duration : float, optional
        Length of each random cycle [s] (default 8 h: one shift).
    model, mesh : str
        The model that simulates the cycles (default ``"fast"``) and its FE mesh, if it takes one.
    workers : int, optional
        Cycles side by side on a local cluster of this many processes (None or 1: one after another).
    progress : callable, optional
        Called with the fraction done, from 0 to 1.

    Returns
    -------
    feedtherm.analysis.compensation.study.StudyResult
        The laws asked for (``chosen``, by kind), those on the declared sensors (``declared``), the
        error against the number of sensors (``curves``) and the laws along the stroke (``stroke``).

    Raises
    ------
    feedtherm.errors.ArgumentError
        ``sensors``: an unknown candidate (with the closest names), a K out of range;
        ``cycles``, ``seed``, ``model``: values a study cannot take.
    feedtherm.errors.FeedthermError
        The description has no feed drive.
    """
    from .analysis.candidates import candidate_sensors
    from .analysis.compensation.data import StudySettings
    from .analysis.compensation.study import parse_sensors, run_study
    from .analysis.execution import resolve_execution
    from .analysis.random_cycles import CycleRanges
    from .models.registry import model_entry
    from .system.schema import feed_drive

    loaded = _loaded(system)
    feed_drive(loaded.system, "compensate()")
    entry = model_entry(model)
    request = parse_sensors(_sensor_text(sensors), candidate_sensors(loaded.system))
    if duration is not None and not duration > 0:
        raise ArgumentError("duration", f"must be positive, got {duration!r} s")
    ranges = CycleRanges() if duration is None else CycleRanges(duration=float(duration))
    settings = StudySettings(cycles=cycles, seed=seed, ranges=ranges, model=entry.name,
                             mesh=mesh if entry.uses_mesh else None)
    return run_study(loaded, settings, request, progress, resolve_execution(workers))


def _loaded(system) -> LoadedSystem:
    from .system.load import as_loaded

    return as_loaded(system)


def _names(argument: str, value: str | Sequence[str]) -> list[str]:
    """A list of names, given as a list or as one comma-separated string (as the CLI takes them)."""
    items = value.split(",") if isinstance(value, str) else list(value)
    if not all(isinstance(item, str) for item in items):
        raise ArgumentError(argument, f"names (strings), got {value!r}")
    return [item.strip() for item in items if item.strip()]


def _sensor_text(sensors: int | str | Sequence[str]) -> str:
    """``sensors`` as the text :func:`~feedtherm.analysis.compensation.study.parse_sensors` reads."""
    if isinstance(sensors, bool):
        raise ArgumentError("sensors", f"a count, 'declared' or sensor names, got {sensors!r}")
    if isinstance(sensors, int):
        return str(sensors)
    return sensors if isinstance(sensors, str) else ",".join(_names("sensors", sensors))


__all__ = ["load", "calibrate", "compensate"]
