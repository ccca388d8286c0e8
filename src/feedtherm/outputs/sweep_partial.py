"""The rows of an unfinished sweep, kept on disk as each point finishes: what ``--resume`` reads.

A sweep keeps its finished points in ``<out>/.sweep-partial/``: one small JSON file per point,
named by the digest of the point's full inputs (:func:`feedtherm.analysis.sweep.point_key`), and
``sweep.json`` with what the points share (description digest, mode, duration, motion, feedtherm
version).  The final write of ``sweep.csv`` drops the folder in the same swap that brings the
CSV in (:func:`feedtherm.outputs.sweep_files.write_sweep`), so the folder exists only beside an
unfinished sweep, or one with failed points.

Why one file per point rather than one journal: a file is written to a temporary name and
renamed into place (``os.replace``, atomic on POSIX), so a record is either whole or absent, with
no torn last line to detect and truncate, and the main process never rewrites what is already
kept.  A record is still checked when it is read (valid JSON, its own key, the columns of the
sweep, numbers where numbers belong): anything else (a disk error, a hand edit) is ignored, and
the point runs again.  Temporary files of a killed process are never read and are removed with
the folder.
"""

from __future__ import annotations

import json
import math
import os
import re
import secrets
import shutil
from collections.abc import Iterable
from pathlib import Path

from ..errors import FeedthermError

#: The folder of an unfinished sweep's rows, inside the sweep's output directory.
PARTIAL_DIR = ".sweep-partial"
#: What every point of the kept sweep shares.
SETTINGS_JSON = "sweep.json"
#: The layout of the records; another layout is never read.
FORMAT = 1

_RECORD = re.compile(r"[0-9a-f]{64}\.json")
_TEMPORARY = ".tmp-"
#: The settings a user chose, with the option that sets each (for the one-line mismatch message).
_OPTIONS = {"description_sha256": "the description", "mode": "--mode", "duration_s": "--duration",
            "motion": "--motion", "feedtherm": "the feedtherm version"}


class PartialSweep:
    """The kept rows of one sweep in ``out_dir``.

    Parameters
    ----------
    out_dir : Path
        The sweep's output directory.
    settings : dict
        :func:`~feedtherm.analysis.sweep.sweep_settings` of this sweep.
    columns : list of str
        The row's keys (:func:`~feedtherm.analysis.sweep.columns`): a record without exactly
        these is ignored.
    """

    def __init__(self, out_dir: Path, settings: dict, columns: Iterable[str]):
        self.out_dir = Path(out_dir)
        self.folder = self.out_dir / PARTIAL_DIR
        self.settings = dict(settings)
        self.columns = list(columns)
        self._ready = False
        self._kept: set[str] = set()  # keys of this sweep's points known to be kept whole
        self._saving: str | None = None  # the key whose record is being written

    # ------------------------------------------------------------------ before the runs

    def open(self, *, resume: bool) -> None:
        """Check a kept sweep against this one, before anything runs.

        With ``resume``, a kept sweep of other settings is an error (its points could not be
        used, and a typo in ``--duration`` should not silently discard hours of runs); without,
        a kept sweep that holds any point is an error too (``--resume`` continues it; deleting
        the folder starts afresh).  A folder with no point in it is cleared.

        Raises
        ------
        FeedthermError
            One line naming the folder and what to do.
        """
        if not self.folder.is_dir():
            return
        kept = self._record_files()
        if not resume:
            if kept:
                raise FeedthermError(f"{self.out_dir}: holds {len(kept)} finished point{'s' if len(kept) != 1 else ''} "
                                     f"of an interrupted sweep ({self.folder}); add --resume to finish it, or delete "
                                     f"that folder to start afresh")
            shutil.rmtree(self.folder, ignore_errors=True)
            return
        stored = self._stored_settings()
        if stored is None:
            if kept:
                raise FeedthermError(f"--resume: {self.folder / SETTINGS_JSON} is missing or unreadable, so its "
                                     f"points cannot be checked; delete {self.folder} to start afresh")
            shutil.rmtree(self.folder, ignore_errors=True)
            return
        differ = [key for key in _OPTIONS if stored.get(key) != self.settings.get(key)]
        if differ:
            what = "; ".join(f"{_OPTIONS[key]}: kept {_shown(stored.get(key))}, now {_shown(self.settings.get(key))}"
                             for key in differ)
            raise FeedthermError(f"--resume: the interrupted sweep in {self.folder} was run with other settings "
                                 f"({what}); rerun it with its settings, or delete that folder to start afresh")
        self._ready = True

    def load(self, keys: list[str]) -> dict[int, dict]:
        """The kept rows among ``keys`` (one per grid point), by the point's index; records that
        are unreadable or not this sweep's are left out (those points run again)."""
        rows = {}
        for index, key in enumerate(keys):
            row = self._read(self.folder / f"{key}.json", key)
            if row is not None:
                rows[index] = row
                self._kept.add(key)
        return rows

    # ------------------------------------------------------------------ while the runs finish

    def save(self, key: str, row: dict) -> None:
        """Keep one finished point's row, atomically (a temporary file renamed into place)."""
        if not self._ready:
            self.folder.mkdir(parents=True, exist_ok=True)
            self._write(self.folder / SETTINGS_JSON, {"format": FORMAT, **self.settings})
            self._ready = True
        self._saving = key
        self._write(self.folder / f"{key}.json", {"format": FORMAT, "key": key, "row": row})
        self._kept.add(key)
        self._saving = None

    def count(self) -> int:
        """How many points of this sweep are kept whole: read back by :meth:`load`, or saved since.

        A Ctrl-C can land between a record's rename into place and its key's entry here: a record
        then on disk under its name is whole (written under a temporary name first), and counts.
        """
        kept = set(self._kept)
        if self._saving is not None and (self.folder / f"{self._saving}.json").is_file():
            kept.add(self._saving)
        return len(kept)

    # ------------------------------------------------------------------ files

    def _record_files(self) -> list[Path]:
        return [path for path in self.folder.iterdir() if _RECORD.fullmatch(path.name)]

    def _stored_settings(self) -> dict | None:
        try:
            document = json.loads((self.folder / SETTINGS_JSON).read_text(encoding="utf-8"))
        except (OSError, ValueError):
            return None
        if not isinstance(document, dict) or document.get("format") != FORMAT:
            return None
        return document

    def _read(self, path: Path, key: str) -> dict | None:
        try:
            document = json.loads(path.read_text(encoding="utf-8"))
        except (OSError, ValueError):  # missing, unreadable, cut short, not UTF-8, not JSON
            return None
        if not isinstance(document, dict) or document.get("format") != FORMAT or document.get("key") != key:
            return None
        row = document.get("row")
        if not isinstance(row, dict) or list(row) != self.columns:
            return None
        for name, value in row.items():
            if value is None and name == "equilibrium_time_s":
                continue
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
                return None
        return {name: (None if value is None else float(value)) for name, value in row.items()}

    def _write(self, path: Path, document: dict) -> None:
        temporary = path.with_name(f"{_TEMPORARY}{os.getpid()}-{secrets.token_hex(4)}-{path.name}")
        try:
            with open(temporary, "w", encoding="utf-8") as handle:
                handle.write(json.dumps(document, allow_nan=False) + "\n")
                handle.flush()
                os.fsync(handle.fileno())  # the bytes on disk before the name points at them
            os.replace(temporary, path)
        except BaseException:
            temporary.unlink(missing_ok=True)
            raise


def _shown(value) -> str:
    if isinstance(value, str) and len(value) == 64:  # a digest: its first characters say enough
        return value[:12]
    return "the default" if value is None else f"{value:g}" if isinstance(value, float) else str(value)
