"""The benches feedtherm knows by name, each one a folder with its description and its data.

A bench folder holds::

    description.toml        the system description (required; docs/system-description.md)
    measurements.csv        measured values to validate and calibrate against (optional; the
                            layout is in feedtherm.system.measurements)
    equilibrium_times.csv   the equilibrium time the source states per condition (optional)
    overlay.toml            values the source prints, laid over the physics by --mode (optional;
                            feedtherm.system.overlay)
    report.toml             what the validation report says of the bench beyond its runs (optional;
                            :class:`ReportNotes`)
    tables/tableN_*.csv     the source's printed tables, as printed (optional)
    SOURCES.md              where each file comes from

The benches shipped with feedtherm are the folders beside this file. Another package adds
its own through the entry-point group ``feedtherm.benches``: the entry point's name is the
bench's name, and it points to a folder path, a :class:`Bench`, or a function returning
either. In that package's pyproject.toml::

    [project.entry-points."feedtherm.benches"]
    my_mill = "my_package.benches:my_mill_folder"

An entry point is loaded only when its bench is asked for, so a broken one costs one error
line naming it, and only when that bench is used or all benches are listed.
"""

from __future__ import annotations

import csv
import difflib
import functools
import os
import tomllib
from dataclasses import dataclass, field
from importlib import metadata
from pathlib import Path

from ..errors import DescriptionError

#: The entry-point group through which other packages add benches.
GROUP = "feedtherm.benches"
#: A description loaded from a bench has the origin ``bundled:<name>``.
ORIGIN_PREFIX = "bundled:"

DESCRIPTION = "description.toml"
MEASUREMENTS = "measurements.csv"
EQUILIBRIUM_TIMES = "equilibrium_times.csv"
TABLES = "tables"
REPORT = "report.toml"

_SHIPPED = Path(__file__).parent
_PROVIDER = "feedtherm"


@dataclass(frozen=True)
class ReportNotes:
    """What the validation report says of a bench beyond its runs (the bench folder's report.toml).

    ``reference_model``: whose results the measurements' ``reference_simulated`` column holds;
    ``field_condition``: the condition whose screw field the report shows (default: the first
    run); ``findings``: what the source gets wrong or leaves open, one sentence or a few each;
    ``earlier_held_out_elongation_um``: held-out elongation errors of earlier versions of the
    bench's model [µm], by what they were, for the report to set today's beside.
    """

    reference_model: str = ""
    field_condition: str = ""
    findings: tuple[str, ...] = ()
    earlier_held_out_elongation_um: dict[str, float] = field(default_factory=dict)


@dataclass(frozen=True)
class Bench:
    """One bench: its name, its folder and the files in it that feedtherm reads."""

    name: str
    folder: Path
    title: str
    description: Path
    measurements: Path | None = None
    equilibrium_times: Path | None = None
    provider: str = _PROVIDER  # "feedtherm", or the entry point that registered it

    @classmethod
    def from_folder(cls, name: str, folder: str | os.PathLike, provider: str = _PROVIDER) -> "Bench":
        """The bench in ``folder``, laid out as this module's docstring says."""
        folder = Path(folder)
        description = folder / DESCRIPTION
        if not description.is_file():
            raise DescriptionError(f"bench {name!r} ({provider}): {description}: no such file; a bench folder needs {DESCRIPTION}")
        return cls(name=name, folder=folder, title=_title(description), description=description,
                   measurements=_optional(folder / MEASUREMENTS),
                   equilibrium_times=_optional(folder / EQUILIBRIUM_TIMES), provider=provider)

    def report_notes(self) -> ReportNotes:
        """The bench's :class:`ReportNotes` (none without a report.toml); one-line error naming the file."""
        path = self.folder / REPORT
        if not path.is_file():
            return ReportNotes()
        try:
            data = tomllib.loads(path.read_text(encoding="utf-8"))
        except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError) as exc:
            raise DescriptionError(f"{path}: cannot be read: {' '.join(str(exc).split())}") from None
        keys = ("reference_model", "field_condition", "findings", "earlier_held_out_elongation_um")
        unknown = sorted(set(data) - set(keys))
        if unknown:
            raise DescriptionError(f"{path}: {unknown[0]}: unknown key; expected one of {', '.join(keys)}")
        earlier = data.get("earlier_held_out_elongation_um", {})
        if not isinstance(earlier, dict) or not all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                                    for v in earlier.values()):
            raise DescriptionError(f"{path}: earlier_held_out_elongation_um: must be a table of numbers [µm]")
        findings = data.get("findings", [])
        texts = (data.get("reference_model", ""), data.get("field_condition", ""))
        if not all(isinstance(t, str) for t in texts) or not isinstance(findings, list) \
                or not all(isinstance(f, str) for f in findings):
            raise DescriptionError(f"{path}: reference_model and field_condition must be text, findings a list "
                                   f"of text")
        return ReportNotes(*texts, tuple(" ".join(f.split()) for f in findings),
                           {str(k): float(v) for k, v in earlier.items()})

    def table(self, number: int) -> list[dict[str, str]]:
        """Rows of the source's Table ``number`` (``tables/table<number>_*.csv``), strings as printed."""
        found = sorted((self.folder / TABLES).glob(f"table{number}_*.csv"))
        if len(found) != 1:
            count = "no" if not found else f"{len(found)} files for"
            raise DescriptionError(f"bench {self.name!r} has {count} table {number} ({TABLES}/table{number}_*.csv in {self.folder})")
        return list(csv.DictReader(found[0].read_text(encoding="utf-8").splitlines()))


def bench_names() -> list[str]:
    """Names of every bench: the shipped ones and those registered by entry points."""
    return sorted({*_shipped(), *(entry.name for entry in _entry_points())})


def bench(name: str) -> Bench:
    """The bench called ``name``; one-line DescriptionError if there is none or it is broken."""
    shipped = _shipped()
    registered = [entry for entry in _entry_points() if entry.name == name]
    if registered and (name in shipped or len(registered) > 1):
        others = (["feedtherm"] if name in shipped else []) + [_describe(entry) for entry in registered]
        raise DescriptionError(f"bench {name!r} is registered {len(others)} times ({'; '.join(others)}); "
                               f"rename the entry point")
    if name in shipped:
        return Bench.from_folder(name, shipped[name])
    if registered:
        return _from_entry_point(registered[0])
    raise DescriptionError(f"{name}: no bench of that name{suggestion(name)}")


def benches() -> list[Bench]:
    """Every bench, shipped ones and registered ones, by name."""
    return [bench(name) for name in bench_names()]


def suggestion(name: str) -> str:
    """``"; did you mean 'paper'? (benches: ...)"`` for a mistyped bench name."""
    names = bench_names()
    close = difflib.get_close_matches(name, names, n=1, cutoff=0.5)
    return (f"; did you mean {close[0]!r}?" if close else "") + f" (benches: {', '.join(names)})"


def bench_name_of(origin: str) -> str | None:
    """The bench a description came from, given its origin (``bundled:paper`` or a variant of it)."""
    if not origin.startswith(ORIGIN_PREFIX):
        return None
    return origin[len(ORIGIN_PREFIX):].split(" (", 1)[0]  # variants append " (<what changed>)"


def _shipped() -> dict[str, Path]:
    # "_template" is what `feedtherm new` copies, not a bench
    return {folder.name: folder for folder in sorted(_SHIPPED.iterdir())
            if not folder.name.startswith("_") and (folder / DESCRIPTION).is_file()}


def _entry_points() -> list[metadata.EntryPoint]:
    return list(metadata.entry_points(group=GROUP))


def _from_entry_point(entry: metadata.EntryPoint) -> Bench:
    where = _describe(entry)
    try:
        target = entry.load()
        found = target() if callable(target) and not isinstance(target, Bench) else target
    except Exception as exc:  # whatever another package raises, the user gets one line naming it
        reason = " ".join(str(exc).split())
        raise DescriptionError(f"bench {entry.name!r}: {where} failed: {type(exc).__name__}: {reason}") from None
    if isinstance(found, Bench):
        if found.name != entry.name:
            raise DescriptionError(f"bench {entry.name!r}: {where} returned a bench named {found.name!r}; "
                                   f"the two names must agree")
        return found
    if isinstance(found, (str, os.PathLike)):
        return Bench.from_folder(entry.name, found, provider=where)
    raise DescriptionError(f"bench {entry.name!r}: {where} returned an object of type {type(found).__name__}; "
                           f"expected a folder path or a feedtherm.benches.Bench")


def _describe(entry: metadata.EntryPoint) -> str:
    package = getattr(entry.dist, "name", None)
    return f"entry point {entry.name} = {entry.value}" + (f" of {package}" if package else "") + f" in {GROUP}"


def _optional(path: Path) -> Path | None:
    return path if path.is_file() else None


def _title(description: Path) -> str:
    # Only for listings: a description that cannot be read gets its one-line error from
    # load_system, which reads it in full.
    try:
        return _title_of(description.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError):
        return ""


@functools.lru_cache(maxsize=16)
def _title_of(text: str) -> str:
    """``meta.title`` of a description's text, parsed once per text: every :func:`bench` call names the
    title, and a batch's runs of measured tests call it for each file they read (30 ms a parse)."""
    try:
        meta = tomllib.loads(text).get("meta", {})
    except tomllib.TOMLDecodeError:
        return ""
    title = meta.get("title", "") if isinstance(meta, dict) else ""
    return title if isinstance(title, str) else ""
