"""``feedtherm export``: a law file as code a controller runs, with its guards and a summary.

The law is read as ``feedtherm correct`` reads it (:mod:`feedtherm.analysis.compensation.law_files`:
the same one-line refusals), then written as a set into the output folder (replaced whole,
nothing half-written):

- ``--to c``: ``<name>.h`` and ``<name>.c`` (:mod:`.c_code`);
- ``--to linuxcnc``: ``<name>_law.h``, ``<name>_law.c``, the component ``<name>.comp`` and
  ``<name>.hal`` (:mod:`.linuxcnc`);
- both: ``export.json``, what was exported: the law's kind and inputs in the code's order, the
  guards (:mod:`feedtherm.analysis.compensation.guards`), and for a stroke law its offset-and-slope
  form with the bound on that form's error over the stroke
  (:mod:`feedtherm.analysis.compensation.offset_slope`).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from ... import __version__
from ...analysis.compensation.guards import Guards, resolve_guards
from ...analysis.compensation.law_files import check_law, one_line, parse_law_file
from ...analysis.compensation.offset_slope import offset_slope
from ...errors import FeedthermError
from ..files import staged_directory, write_json
from .c_code import c_files
from .law_spec import LawSpec, c_identifier, default_name, law_spec, pin_names
from .linuxcnc import component_files, hal_name

TARGETS = ("c", "linuxcnc")
#: Machine units per metre by ``--units``.
UNITS_PER_M = {"mm": 1000.0, "inch": 1.0 / 0.0254}


@dataclass(frozen=True)
class ExportOptions:
    """What ``feedtherm export`` was asked for (CLI options, SI units)."""

    to: str
    name: str | None = None
    valid_range_K: tuple[float, float] | None = None
    margin_K: float | None = None
    max_rate: float | None = None
    start: str = "first-sample"
    x_ref: float | None = None
    axis: str = "x"
    units: str = "mm"
    scale: float = 1e-6


def read_exportable(path: str | Path) -> tuple[dict, LawSpec, list[str]]:
    """The law file ``path`` checked as ``correct`` checks it, its :class:`LawSpec` and its warnings."""
    document = parse_law_file(path)
    origin = one_line(str(path))
    if isinstance(document, dict) and document.get("kind") == "kalman":
        law_spec(document, origin)  # the one-line refusal, before the estimator is built
    warnings = check_law(document, str(path))
    return document, law_spec(document, origin), warnings


def _guards(document: dict, options: ExportOptions) -> Guards:
    kwargs = {k: v for k, v in (("margin_K", options.margin_K), ("max_rate", options.max_rate)) if v is not None}
    return resolve_guards(document, options.valid_range_K, start=options.start, **kwargs)


def export_law(path: str | Path, options: ExportOptions, out_dir: Path) -> dict:
    """Write the law of ``path`` as ``options.to`` asks into ``out_dir`` (module notes); the summary.

    Raises
    ------
    FeedthermError
        One line naming the file or the option and the reason, before anything is written.
    """
    if options.to not in TARGETS:
        raise FeedthermError(f"--to: {options.to!r} is not a target; allowed: {', '.join(TARGETS)}")
    document, spec, warnings = read_exportable(path)
    name = c_identifier(options.name) if options.name else default_name(Path(path).stem)
    guards = _guards(document, options)
    summary = _summary(path, document, spec, guards, name, options, warnings)
    source = Path(path).name
    if options.to == "c":
        files = c_files(spec, guards, name, source, __version__, options.x_ref)
    else:
        if len(options.axis) != 1 or options.axis not in "xyzabcuvw":
            raise FeedthermError(f"--axis: {options.axis!r} is not a LinuxCNC axis letter (x y z a b c u v w)")
        if options.units not in UNITS_PER_M:
            raise FeedthermError(f"--units: {options.units!r} is not a machine unit; allowed: {', '.join(UNITS_PER_M)}")
        files = {**c_files(spec, guards, name, source, __version__, options.x_ref, stem=f"{name}_law"),
                 **component_files(spec, name, source, __version__, options.axis, UNITS_PER_M[options.units],
                                   options.scale)}
        summary["linuxcnc"] = {"module": name, "component": hal_name(name), "axis": options.axis,
                               "units": options.units, "units_per_m": UNITS_PER_M[options.units],
                               "eoffset_scale": options.scale,
                               **({"x_at_zero_m": spec.x_min} if spec.stroke else {}),
                               "build": f"halcompile --install {name}.comp",
                               "wiring": f"{name}.hal: counts to axis.{options.axis}.eoffset-counts"}
    summary["files"] = sorted(files) + ["export.json"]
    with staged_directory(Path(out_dir), replaces=tuple(summary["files"])) as stage:
        for file_name, text in files.items():
            (stage / file_name).write_text(text, encoding="utf-8")
        write_json(stage / "export.json", summary)
    return summary


def _summary(path, document: dict, spec: LawSpec, guards: Guards, name: str, options: ExportOptions,
             warnings: list[str]) -> dict:
    pins = pin_names(spec.inputs)
    summary = {"law": str(path), "kind": document["kind"] + (" (adapted)" if spec.posterior else ""),
               "to": options.to, "name": name,
               "inputs": [{"index": i, "name": n, "unit": "K", "hal_pin": f"{hal_name(name)}.0.temp-{p.replace('_', '-')}"
                           + " [degC]"} for i, (n, p) in enumerate(zip(spec.inputs, pins))],
               "output": "E(x) [m] at a table position x [m]" if spec.stroke else "D [m]",
               "sign": "correct the axis by minus the output",
               "guards": guards.as_dict(list(spec.inputs)),
               "warnings": warnings}
    if spec.stroke:
        x_ref = 0.5 * (spec.x_min + spec.x_max) if options.x_ref is None else options.x_ref
        if not spec.x_min - 1e-9 <= x_ref <= spec.x_max + 1e-9:
            raise FeedthermError(f"--x-ref: {x_ref * 1e3:.6g} mm is outside the law's stroke, "
                                 f"[{spec.x_min * 1e3:.6g}, {spec.x_max * 1e3:.6g}] mm")
        envelope = document.get("envelope")
        ranges = ({n: (envelope["inputs"][n]["min_K"], envelope["inputs"][n]["max_K"]) for n in spec.inputs}
                  if envelope else dict(zip(spec.inputs, guards.valid_K)))
        summary["stroke_m"] = [spec.x_min, spec.x_max]
        summary["offset_slope"] = offset_slope(document, x_ref, ranges).as_dict()
        summary["offset_slope"]["ranges_from"] = "the law's training envelope" if envelope else "the valid ranges"
    elif options.x_ref is not None:
        raise FeedthermError("--x-ref: this law predicts D, the same at every table position; leave --x-ref out")
    return summary
