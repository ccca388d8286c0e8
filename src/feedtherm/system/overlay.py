"""Printed boundary conditions that a bench may lay over the physics: its overlay.

A source that prints heats and CHTCs at one operating point (the paper's first two tables)
supplies them to feedtherm as an overlay file beside the bench's description::

    name = "paper"                 # the --mode that applies it
    title = "..."
    reference_condition = "C1"     # the condition at which the values are printed

    [[heat]]                       # one per printed heat
    source = "guideways"           # a source of the description
    value = "0.39 W"
    table_label = "Guideways"      # as the source prints it
    ref = "table 1 of the source"

    [[chtc]]                       # one per printed CHTC
    surfaces = ["screw_pair"]      # the description's surfaces it covers
    value = "56.3 W/(m^2*K)"
    table_label = "Screw"
    ref = "table 2 of the source"

A bench folder's ``overlay.toml`` is its overlay; a description loaded from a file names one in
``meta.overlay`` (``bundled:<bench>`` or a path relative to the description). Only
:mod:`feedtherm.plan` applies it to a run; the rule that carries printed values to other
conditions is in :mod:`feedtherm.boundary.overlay`.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from pydantic import ValidationError

from ..benches import ORIGIN_PREFIX, bench, bench_name_of
from ..errors import DescriptionError
from .base import Strict
from .files import parse_bounded_toml, read_text_file
from .quantities import PosHeatTransferCoefficient, Power
from .references import closest
from .schema import FeedSystem

OVERLAY = "overlay.toml"
#: What runs without an overlay are called in outputs: every value from the physics.
PHYSICS = "physics"
#: How deep an overlay's tables and arrays nest: the file, [[chtc]], a row, its ``surfaces``.
OVERLAY_DEPTH = 4


class PrintedHeat(Strict):
    source: str
    value: Power
    table_label: str
    ref: str


class PrintedChtc(Strict):
    surfaces: list[str]
    value: PosHeatTransferCoefficient
    table_label: str
    ref: str


class Overlay(Strict):
    """Values a source prints at one condition, mapped onto a description's sources and surfaces."""

    name: str
    title: str = ""
    reference_condition: str
    heat: list[PrintedHeat] = []
    chtc: list[PrintedChtc] = []

    def printed_heats(self) -> dict[str, float]:
        """Source -> printed heat at the reference condition [W]."""
        return {row.source: row.value for row in self.heat}

    def printed_chtcs(self) -> dict[str, float]:
        """Surface -> printed CHTC at the reference condition [W/(m² K)]."""
        return {surface: row.value for row in self.chtc for surface in row.surfaces}


def overlay_spec(loaded) -> str | None:
    """Where the overlay of ``loaded`` (a LoadedSystem) is: its ``meta.overlay``, else its bench's
    ``overlay.toml``; None when there is none."""
    declared = loaded.system.meta.overlay
    if declared:
        return declared
    name = bench_name_of(loaded.origin)
    if name is not None and (bench(name).folder / OVERLAY).is_file():
        return f"{ORIGIN_PREFIX}{name}"
    return None


def available_overlay(loaded) -> Overlay | None:
    """The overlay ``loaded`` may apply, read and checked against its description; None without one."""
    spec = overlay_spec(loaded)
    if spec is None:
        return None
    if spec.startswith(ORIGIN_PREFIX):
        path = bench(spec[len(ORIGIN_PREFIX):]).folder / OVERLAY
    else:
        path = Path(spec)
        if not path.is_absolute():
            name = bench_name_of(loaded.origin)
            path = (bench(name).folder if name else Path(loaded.origin).parent) / path
    return read_overlay(path, loaded.system)


def read_overlay(path: Path, system: FeedSystem) -> Overlay:
    """Read and check an overlay file; one-line DescriptionError naming the file and the field."""
    if not path.exists():  # stat only: a FIFO does not block here
        raise DescriptionError(f"{path}: no such overlay file")
    # a regular file of at most MAX_DESCRIPTION_BYTES, UTF-8 with or without a BOM, nested at most
    # MAX_TOML_DEPTH levels: the rules of a description (system/files.py)
    data = parse_bounded_toml(read_text_file(path, str(path), what="overlay"), str(path), what="overlay",
                              deepest=OVERLAY_DEPTH)
    try:
        overlay = Overlay.model_validate(data)
    except ValidationError as exc:
        from .load import describe_error  # load imports the schema this module extends

        raise DescriptionError(f"{path}: {describe_error(exc)}") from None
    problem = _dangling(overlay, system)
    if problem:
        raise DescriptionError(f"{path}: {problem}")
    return overlay


def mode_of(loaded) -> str:
    """What outputs call the boundary conditions of ``loaded``: its overlay's name, or ``"physics"``."""
    return loaded.overlay.name if loaded.overlay is not None else PHYSICS


def with_overlay(loaded, overlay: Overlay | None):
    """A copy of ``loaded`` whose runs take ``overlay``'s printed values (None: the physics alone)."""
    return replace(loaded, overlay=overlay)


def _dangling(overlay: Overlay, system: FeedSystem) -> str:
    if overlay.reference_condition not in system.conditions:
        return (f"reference_condition: no condition named {overlay.reference_condition!r}"
                f"{closest(overlay.reference_condition, system.conditions)}")
    for i, row in enumerate(overlay.heat):
        if row.source not in system.sources:
            return f"heat[{i}].source: no heat source named {row.source!r}{closest(row.source, system.sources)}"
    for i, row in enumerate(overlay.chtc):
        for target in row.surfaces:
            if target not in system.surfaces:
                return f"chtc[{i}].surfaces: no surface named {target!r}{closest(target, system.surfaces)}"
    return ""
