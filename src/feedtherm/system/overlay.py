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

import re
from dataclasses import replace
from pathlib import Path
from typing import Annotated

from pydantic import AfterValidator, ValidationError

from ..benches import ORIGIN_PREFIX, bench, bench_name_of
from ..errors import DescriptionError
from .base import Strict
from .files import parse_bounded_toml, read_text_file
from .quantities import PosHeatTransferCoefficient, Power
from .references import closest
from .schema import FeedSystem
from .validation_errors import describe_error

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


def _mode_name(name: str) -> str:
    """An overlay's name is the ``--mode`` that applies it and part of output folders' names."""
    if not re.fullmatch(r"[A-Za-z][A-Za-z0-9_-]{0,63}", name):
        raise ValueError(f"{name!r} is not a mode name: a letter, then up to 63 letters, digits, '_' or '-' (it "
                         "is the --mode that applies the overlay and part of output folders' names)")
    if name == PHYSICS:
        raise ValueError(f"{name!r} is the mode without an overlay; name the overlay after its source")
    return name


class Overlay(Strict):
    """Values a source prints at one condition, mapped onto a description's sources and surfaces."""

    name: Annotated[str, AfterValidator(_mode_name)]
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


def overlay_path(loaded) -> Path | None:
    """The file of the overlay of ``loaded`` (:func:`overlay_spec`), None when there is none."""
    spec = overlay_spec(loaded)
    if spec is None:
        return None
    if spec.startswith(ORIGIN_PREFIX):
        return bench(spec[len(ORIGIN_PREFIX):]).folder / OVERLAY
    path = Path(spec)
    if not path.is_absolute():
        name = bench_name_of(loaded.origin)
        path = (bench(name).folder if name else Path(loaded.origin).parent) / path
    return path


def available_overlay(loaded) -> Overlay | None:
    """The overlay ``loaded`` may apply, read and checked against its description; None without one."""
    path = overlay_path(loaded)
    return None if path is None else read_overlay(path, loaded.system)


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
    printed: dict[str, int] = {}
    for i, row in enumerate(overlay.heat):
        if row.source not in system.sources:
            return f"heat[{i}].source: no heat source named {row.source!r}{closest(row.source, system.sources)}"
        if row.source in printed:  # a second value would silently replace the first
            return f"heat[{i}].source: {row.source!r} is printed already, in heat[{printed[row.source]}]"
        printed[row.source] = i
    covered: dict[str, int] = {}
    for i, row in enumerate(overlay.chtc):
        for target in row.surfaces:
            if target not in system.surfaces:
                return f"chtc[{i}].surfaces: no surface named {target!r}{closest(target, system.surfaces)}"
            if target in covered:
                return f"chtc[{i}].surfaces: {target!r} is covered already, by chtc[{covered[target]}]"
            covered[target] = i
    return ""
