"""How every result file is written: a set of files swapped in whole, and JSON from results.

A writer stages its whole set of files in a hidden directory beside the output directory
(:func:`staged_directory`).  Only when every file is complete does the staged directory take
the output directory's place, in two renames: the old directory is renamed aside, the new one
renamed in, and the old one deleted.  A reader therefore sees the old set or the new one,
never a mixture; if the second rename fails, the first is undone.  Files of the old directory
that the new set does not replace (a user's notes, another command's files) are hard-linked
into the new directory before the swap, so they are kept without being copied or moved.

Staging directories are named ``.<name>.partial-<host>-<pid>-<token>`` and the old directory,
while it is aside, ``.<name>.replaced-<host>-<pid>-<token>``.  A run killed before it could
clean up (SIGKILL, a power cut) leaves them behind; the next write into the same directory
removes those whose process no longer runs on this host, and puts a set that was aside back
in place if the swap never finished.  Folders of any other name are never touched.

:func:`to_json_ready` turns results (numpy scalars and arrays, paths, dataclasses, NaN) into
plain JSON types; :func:`write_json` writes them.
"""

from __future__ import annotations

import dataclasses
import fnmatch
import json
import math
import os
import re
import secrets
import shutil
import socket
from collections.abc import Iterable, Iterator, Mapping
from contextlib import contextmanager
from pathlib import Path

import numpy as np

from ..errors import FeedthermError

__all__ = ["check_output_dir", "json_text", "remove_stale_staging", "staged_directory", "to_json_ready",
           "write_json"]

_STAGING = "partial"  # a set being written
_REPLACED = "replaced"  # the previous set, renamed aside during the swap


# --------------------------------------------------------------------------- JSON


def to_json_ready(value):
    """``value`` as plain JSON types, ready for :func:`json.dumps` with ``allow_nan=False``.

    Mappings become dicts with string keys; lists, tuples and numpy arrays become lists;
    numpy scalars become Python numbers; NaN and ±inf become ``None`` (JSON has no NaN, and
    ``null`` is what every reader parses); paths become strings; dataclass instances become
    dicts of their fields.  Strings, ints, floats, bools and ``None`` pass unchanged.

    Raises
    ------
    TypeError
        For any other type, naming it (rather than writing its ``repr``).
    """
    if isinstance(value, np.ndarray):
        value = value.tolist()  # nested lists of Python scalars; a 0-d array gives a scalar
    elif isinstance(value, np.generic):
        value = value.item()
    if value is None or isinstance(value, (str, bool, int)):
        return value
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, Mapping):
        return {str(key): to_json_ready(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [to_json_ready(item) for item in value]
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return {f.name: to_json_ready(getattr(value, f.name)) for f in dataclasses.fields(value)}
    raise TypeError(f"cannot write a {type(value).__name__} as JSON")


def json_text(value) -> str:
    """``value`` as indented JSON text (via :func:`to_json_ready`; UTF-8 characters kept)."""
    return json.dumps(to_json_ready(value), indent=2, ensure_ascii=False, allow_nan=False)


def write_json(path: Path, value) -> None:
    """Write ``value`` as indented UTF-8 JSON (see :func:`json_text`) with a final newline."""
    Path(path).write_text(json_text(value) + "\n", encoding="utf-8")


# --------------------------------------------------------------------------- the output directory


def check_output_dir(out_dir: Path) -> None:
    """Fail now, before a long run, if ``out_dir`` cannot become a directory we write into.

    Raises
    ------
    FeedthermError
        ``out_dir`` is a file or lies below one, holds the current directory (the swap would
        leave this process, and the shell it was started from, in a deleted directory), or
        it or its parent cannot be written.
    """
    out_dir = Path(out_dir)
    target = _resolved(out_dir)
    if target.exists() and not target.is_dir():
        raise FeedthermError(f"{out_dir}: exists and is not a directory")
    existing = _nearest_existing(target)
    if not existing.is_dir():
        raise FeedthermError(f"{out_dir}: {existing} is a file, not a directory")
    if _holds_current_directory(target):
        raise FeedthermError(f"{out_dir}: is or holds the current directory; outputs replace their directory "
                             "as a whole, so give a directory below it")
    # The set is staged beside out_dir and swapped with it: both places must be writable.
    must_write = [target.parent, target] if existing == target else [existing]
    for directory in must_write:
        if not os.access(directory, os.W_OK | os.X_OK):
            raise FeedthermError(f"{out_dir}: no permission to write in {directory}")


@contextmanager
def staged_directory(out_dir: Path, *, replaces: Iterable[str] = ()) -> Iterator[Path]:
    """Yield an empty staging directory; on success it becomes ``out_dir`` in one swap.

    Parameters
    ----------
    out_dir : Path
        The output directory; created with its parents if missing.
    replaces : iterable of str
        Glob patterns of every file this kind of set may hold (``"fields_*.vtu"``).  Files of
        the old directory that match them belong to the old set and are dropped even when the
        new set has no file of that name; other files that the new set does not write are
        kept.

    Raises
    ------
    FeedthermError
        ``out_dir`` cannot be written (see :func:`check_output_dir`), or an operating-system
        error while writing or swapping; the old directory is then left as it was.

    Notes
    -----
    On any error, in the caller's block or in the swap, the staging directory and any parent
    directories made for it are removed and the old directory stays in place, unchanged.
    """
    out_dir = Path(out_dir)
    check_output_dir(out_dir)
    target = _resolved(out_dir)
    patterns = tuple(replaces)
    made = []
    stage = target.parent / _folder_name(target.name, _STAGING)
    try:
        made = _make_parents(target.parent)
        remove_stale_staging(target)
        stage.mkdir()
        yield stage
        _swap_in(stage, target, patterns)
    except BaseException as exc:
        shutil.rmtree(stage, ignore_errors=True)
        _remove_if_empty(made)
        if isinstance(exc, OSError):
            raise FeedthermError(f"{out_dir}: cannot write the outputs ({exc.strerror or exc})") from None
        raise


def remove_stale_staging(out_dir: Path) -> None:
    """Clean up after writes into ``out_dir`` that were killed before they could.

    A ``.<name>.replaced-…`` folder of a process that is gone, while ``out_dir`` is missing,
    is a set whose swap was cut between its two renames: it is renamed back into place.
    Every other ``.<name>.partial-…`` and ``.<name>.replaced-…`` folder of a process that is
    gone is deleted.  Folders of a running process, of another host, or of any other name are
    left alone.
    """
    target = _resolved(Path(out_dir))
    if not target.parent.is_dir():
        return
    stale = {_STAGING: [], _REPLACED: []}
    for path in sorted(target.parent.iterdir()):
        owner = _folder_owner(target.name, path.name)
        if owner is not None and owner[1] == _host() and not _process_running(owner[2]):
            stale[owner[0]].append(path)
    if stale[_REPLACED] and not os.path.lexists(target):
        os.rename(stale[_REPLACED].pop(), target)  # the old set, as it was before the cut swap
    for path in stale[_STAGING] + stale[_REPLACED]:
        shutil.rmtree(path, ignore_errors=True)


# --------------------------------------------------------------------------- the swap


def _swap_in(stage: Path, target: Path, replaces: tuple[str, ...]) -> None:
    if not os.path.lexists(target):
        try:
            os.rename(stage, target)
            return
        except OSError:
            if not target.is_dir():
                raise  # not a directory made meanwhile by someone else: a real failure
    _keep_other_files(target, stage, replaces)
    shutil.copymode(target, stage)  # the directory keeps its permissions
    aside = target.parent / _folder_name(target.name, _REPLACED)
    os.rename(target, aside)
    try:
        os.rename(stage, target)
    except BaseException:
        os.rename(aside, target)
        raise
    shutil.rmtree(aside, ignore_errors=True)


def _keep_other_files(old: Path, stage: Path, replaces: tuple[str, ...]) -> None:
    """Hard-link (or copy, where links fail) the old directory's other entries into ``stage``.

    Links leave the old directory untouched: a run killed now loses nothing, and the links
    in the staging directory are all that its clean-up deletes.
    """
    for entry in old.iterdir():
        destination = stage / entry.name
        if os.path.lexists(destination) or any(fnmatch.fnmatchcase(entry.name, p) for p in replaces):
            continue
        if entry.is_symlink():
            os.symlink(os.readlink(entry), destination)
        elif entry.is_dir():
            shutil.copytree(entry, destination, symlinks=True, copy_function=_link_or_copy)
        else:
            _link_or_copy(entry, destination)


def _link_or_copy(source, destination) -> None:
    try:
        os.link(source, destination, follow_symlinks=False)
    except OSError:  # no hard links on this file system, or not allowed for this file
        shutil.copy2(source, destination, follow_symlinks=False)


# --------------------------------------------------------------------------- names and owners


def _folder_name(name: str, kind: str) -> str:
    return f".{name}.{kind}-{_host()}-{os.getpid()}-{secrets.token_hex(6)}"


def _folder_owner(name: str, folder: str) -> tuple[str, str, int] | None:
    """(kind, host, pid) of one of our folders for the directory ``name``; None for any other."""
    match = re.fullmatch(rf"\.{re.escape(name)}\.({_STAGING}|{_REPLACED})-([A-Za-z0-9]+)-(\d+)-[0-9a-f]{{12}}",
                         folder)
    return None if match is None else (match[1], match[2], int(match[3]))


def _host() -> str:
    # Letters and digits only, so that the name parses back; short, so that it fits in a name.
    return re.sub(r"[^A-Za-z0-9]", "", socket.gethostname())[:24] or "host"


def _process_running(pid: int) -> bool:
    if os.name != "posix":
        return True  # no safe probe (os.kill would end the process): never remove
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:
        return True  # e.g. another user's process
    return True


# --------------------------------------------------------------------------- paths


def _resolved(path: Path) -> Path:
    # Through symbolic links: a link to a directory has its directory replaced, not the link.
    return Path(os.path.realpath(path))


def _holds_current_directory(target: Path) -> bool:
    try:
        cwd = Path(os.path.realpath(os.getcwd()))
    except OSError:
        return False
    return cwd == target or target in cwd.parents


def _nearest_existing(path: Path) -> Path:
    while not path.exists():
        path = path.parent
    return path


def _make_parents(directory: Path) -> list[Path]:
    """Create ``directory`` and its missing parents; return the ones made, deepest first."""
    missing = []
    current = Path(directory)
    while not current.exists():
        missing.append(current)
        current = current.parent
    for path in reversed(missing):
        path.mkdir()
    return missing


def _remove_if_empty(directories: list[Path]) -> None:
    for path in directories:  # deepest first
        try:
            path.rmdir()
        except OSError:
            return


def read_study_summary(folder: Path, name: str, option: str, command: str, keys: tuple[str, ...]) -> dict:
    """The JSON summary ``name`` another command wrote into ``folder``, for ``option``.

    One-line errors name what is wrong: the file missing (and which command writes it), not
    JSON, or without the ``keys`` such a summary has.
    """
    path = Path(folder) / name
    if not path.is_file():
        raise FeedthermError(f"{option}: {path} not found (give the output folder of `feedtherm {command}`)")
    try:
        document = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError) as exc:
        raise FeedthermError(f"{option}: {path} is not readable JSON ({exc})") from None
    missing = [key for key in keys if key not in (document if isinstance(document, dict) else {})]
    if missing:
        raise FeedthermError(f"{option}: {path} lacks {', '.join(missing)}; is it a {name}?")
    return document

