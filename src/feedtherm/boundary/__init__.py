"""Boundary conditions at an operating point: heat per source, CHTC per surface, TCR per joint.

``feedtherm heat`` prints them.  Every heat and every CHTC comes from the correlations and the
description, radiation on; unless an overlay is given (:class:`~feedtherm.system.overlay.Overlay`,
values a source prints at one reference condition): then its heats and CHTCs replace the
physics at that condition and are scaled to other conditions by the physics ratio (see
:mod:`.overlay`), uncovered values come from the physics, and radiation is off.  Only
:mod:`feedtherm.plan` decides which overlay a run takes.

By default CHTCs and lubricant viscosities are frozen for a run at the declared
surface-to-air temperature difference (the paper's assumption 3).  Given the surfaces' and
sources' own temperatures (:class:`~.temperatures.LocalTemperatures`, read from the state by
a model under ``temperatures.coupling = "nonlinear"``), every coefficient and every heat that
depends on temperature is evaluated there instead.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field, replace

from ..physics.contact import conductance_contact
from ..physics.validity import CorrelationRangeWarning
from ..system.overlay import PHYSICS, Overlay
from ..system.schema import FeedSystem
from .heat import SourceHeat, SourceMemo, named_failure, source_heats
from .operating import OperatingPoint, operating_point
from .overlay import scaled
from .physical import check_coefficient, check_heat, numeric_errors
from .surfaces import SurfaceTransfer, surface_transfer
from .temperatures import LocalTemperatures


@dataclass(frozen=True)
class JointConductance:
    parts: tuple[str, str]
    tcr: float  # [m^2 K / W]
    area: float  # [m^2]
    sliding: bool

    @property
    def conductance(self) -> float:
        """[W/K]"""
        return conductance_contact(self.tcr, self.area)


@dataclass(frozen=True)
class BoundaryConditions:
    condition: str
    overlay: str | None  # the overlay's name, None for the physics alone
    point: OperatingPoint
    heats: dict[str, SourceHeat]
    surfaces: dict[str, SurfaceTransfer]
    joints: list[JointConductance]
    warnings: list[str]
    temperatures: LocalTemperatures | None = None  # where they were evaluated (None: frozen)

    @property
    def mode(self) -> str:
        """The overlay's name, or ``"physics"``: what outputs call these boundary conditions."""
        return self.overlay or PHYSICS

    @property
    def total_heat(self) -> float:
        return sum(h.power for h in self.heats.values())


#: A surface's last evaluation: (operating point, surface temperature [K], radiation on) → its
#: transfer and its range warnings, by surface name (see :func:`boundary_conditions_at`).
SurfaceMemo = dict[str, tuple[tuple[OperatingPoint, float, bool], SurfaceTransfer, list[str]]]


@dataclass
class EvaluationMemo:
    """A coupled run's boundary conditions as last evaluated, surface by surface and source by source
    (``memo`` of :func:`boundary_conditions_at`; one per run, that is per description and overlay)."""

    surfaces: SurfaceMemo = field(default_factory=dict)
    sources: SourceMemo = field(default_factory=dict)
    #: an overlay's reference condition, by its operating point: its physics' heats and surfaces
    #: (taken at the frozen temperatures, so the same at every evaluation)
    reference: dict[OperatingPoint, tuple[dict[str, SourceHeat], dict[str, SurfaceTransfer]]] = field(
        default_factory=dict)


def boundary_conditions(system: FeedSystem, condition: str, overlay: Overlay | None = None) -> BoundaryConditions:
    """Boundary conditions of ``condition`` (a name in the description), with ``overlay`` if given."""
    return boundary_conditions_at(system, operating_point(system, system.conditions[condition]), overlay,
                                  label=condition)


def boundary_conditions_at(
    system: FeedSystem, point: OperatingPoint, overlay: Overlay | None = None, *, label: str = "",
    temperatures: LocalTemperatures | None = None, memo: EvaluationMemo | None = None,
) -> BoundaryConditions:
    """Boundary conditions at any operating point (a duty-cycle segment, a standstill, ...).

    ``overlay``: printed values to lay over the physics (None: the physics alone).
    ``temperatures``: the surfaces' and sources' own temperatures; None takes them all at the
    frozen temperature (:func:`frozen_surface_temperature`).
    ``memo``: the evaluations of earlier calls for the same ``system`` and overlay (a coupled
    run's): a surface at the operating point and temperature of its last evaluation takes that
    evaluation's coefficients and range warnings, and a source at the inputs of its last
    evaluation its heat (:func:`~.heat.source_heats`); an overlay's reference condition, whose
    physics is taken at the frozen temperatures, is evaluated once.  The result is that of an
    evaluation without the memo.
    """
    if overlay is not None and not isinstance(overlay, Overlay):
        raise TypeError(f"overlay must be a feedtherm.system.overlay.Overlay or None, got {overlay!r}; a mode "
                        f"becomes an overlay in feedtherm.plan.with_mode")
    caught: list[str] = []
    heats, surfaces = _physics(system, point, with_radiation=overlay is None, caught=caught,
                               temperatures=temperatures, memo=memo)
    if overlay is not None:
        heats, surfaces = _overlaid(system, overlay, heats, surfaces, memo)
    for name, heat in heats.items():  # the physics' and an overlay's alike
        check_heat(f"sources.{name}", heat.power, heat.details, system.sources[name].heat_factor)
    for name, transfer in surfaces.items():
        check_coefficient(f"surfaces.{name}", transfer.convection, transfer.radiation)
    joints = [JointConductance(tuple(j.between), j.tcr, j.area, j.sliding) for j in system.joints]
    return BoundaryConditions(label, overlay.name if overlay else None, point, heats, surfaces, joints, caught,
                              temperatures)


def frozen_surface_temperature(system: FeedSystem, point: OperatingPoint) -> float:
    """Surface temperature [K] at which frozen CHTCs are taken: ambient + declared rise."""
    return point.ambient + system.temperatures.convection_delta_t


def _physics(system: FeedSystem, point: OperatingPoint, *, with_radiation: bool, caught: list[str] | None = None,
             temperatures: LocalTemperatures | None = None, memo: EvaluationMemo | None = None):
    """Physics-mode heats and surface transfer; range warnings go to ``caught``, labelled."""
    sink = [] if caught is None else caught
    frozen = frozen_surface_temperature(system, point)
    local = temperatures or LocalTemperatures()
    others = []  # warnings not ours: raised again once the evaluation is done
    surfaces = {}
    # One record of the warnings for the whole evaluation, not one per surface and one for the
    # sources: each surface's share of it is labelled with the surface's name.
    with warnings.catch_warnings(record=True) as records:
        warnings.simplefilter("always", CorrelationRangeWarning)
        heats = source_heats(system, point, local.sources, memo=None if memo is None else memo.sources,
                             records=None if memo is None else records)
        sink.extend(message for message in _labelled("sources", records, others) if message not in sink)
        del records[:]
        with numeric_errors():  # an overflow raises, for named_failure to name
            for name in system.surfaces:
                inputs = (point, local.surfaces.get(name, frozen), with_radiation)
                kept = None if memo is None else memo.surfaces.get(name)
                if kept is not None and kept[0] == inputs:
                    surfaces[name], messages = kept[1], kept[2]
                else:
                    start = len(records)
                    with named_failure(f"surfaces.{name}"):
                        surfaces[name] = surface_transfer(system, name, point, inputs[1], with_radiation=with_radiation)
                    messages = _labelled(f"surfaces.{name}", records[start:], others)
                    if memo is not None:
                        memo.surfaces[name] = (inputs, surfaces[name], messages)
                sink.extend(message for message in messages if message not in sink)
    for record in others:  # not ours to swallow
        warnings.warn_explicit(record.message, record.category, record.filename, record.lineno)
    return heats, surfaces


def _labelled(label: str, records: list, others: list) -> list[str]:
    """The correlation-range warnings among ``records`` as ``"<label>: <message>"``, each once; any
    other warning goes to ``others``."""
    messages = []
    for record in records:
        if issubclass(record.category, CorrelationRangeWarning):
            message = f"{label}: {record.message}"
            if message not in messages:
                messages.append(message)
        else:
            others.append(record)
    return messages


def _overlaid(system: FeedSystem, overlay: Overlay, heats, surfaces, memo: EvaluationMemo | None = None):
    reference = operating_point(system, system.conditions[overlay.reference_condition])
    kept = None if memo is None else memo.reference.get(reference)
    if kept is None:
        kept = _physics(system, reference, with_radiation=False)
        if memo is not None:
            memo.reference[reference] = kept
    ref_heats, ref_surfaces = kept
    printed_heat, printed_chtc = overlay.printed_heats(), overlay.printed_chtcs()
    heats = {
        # the physics ratio cancels a heat_factor, so it multiplies the printed value
        name: replace(h, power=scaled(printed_heat[name], h.power, ref_heats[name].power)
                      * system.sources[name].heat_factor)
        if name in printed_heat else h
        for name, h in heats.items()
    }
    surfaces = {
        name: replace(
            s,
            # the physics ratio cancels a calibrated chtc_factor, so it multiplies the printed value
            convection=scaled(printed_chtc[name], s.convection, ref_surfaces[name].convection)
            * system.surfaces[name].chtc_factor,
            correlation=f"{overlay.name} value x ratio of: {s.correlation}",
        ) if name in printed_chtc else s
        for name, s in surfaces.items()
    }
    return heats, surfaces


__all__ = [
    "BoundaryConditions",
    "EvaluationMemo",
    "JointConductance",
    "LocalTemperatures",
    "PHYSICS",
    "OperatingPoint",
    "SourceHeat",
    "SurfaceMemo",
    "SurfaceTransfer",
    "boundary_conditions",
    "boundary_conditions_at",
    "operating_point",
    "surface_transfer",
]
