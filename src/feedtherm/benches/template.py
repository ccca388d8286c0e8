"""A new bench folder from the template beside this file (``feedtherm new``).

The template (``_template/``: a commented single-drive ball-screw description, a README saying
what to replace, a SOURCES.md) is copied with the bench's name filled in. Every argument is
checked before anything is written: the name (a description's name, short enough for the file
system) and the target (an existing, writable folder ``--out``; no file, device or non-empty
folder where the bench goes). The folder is then written whole or not at all: into a temporary
sibling first, renamed into place when complete.
"""

from __future__ import annotations

import errno
import os
import re
import shutil
import stat
import uuid
from pathlib import Path

from ..errors import FeedthermError

TEMPLATE = Path(__file__).parent / "_template"
#: Replaced by the bench's name in every file of the template.
PLACEHOLDER = "__BENCH_NAME__"
_NAME = re.compile(r"[A-Za-z][A-Za-z0-9_]*")  # the description's names (system/schema.py), matched whole
#: Longest bench name [characters]: a name is typed on command lines and becomes part of output
#: folder names (``out/<name>_<condition>_<mode>``) and of an entry point's; 64 leaves those well
#: inside the file system's 255 bytes a path component.
MAX_NAME_LENGTH = 64
#: A path component's and a path's longest length [bytes] where the file system does not say
#: (POSIX NAME_MAX and Linux PATH_MAX).
NAME_MAX = 255
PATH_MAX = 4096
_FILES = ("description.toml", "README.md", "SOURCES.md")


def new_bench(name: str, parent: str | Path = ".") -> Path:
    """Write the folder ``parent/name`` from the template and return it.

    Raises FeedthermError (one line naming ``NAME`` or ``--out`` and the reason) for a name that is
    not a valid bench name or too long for the file system, a ``parent`` that is not an existing
    writable folder, and a target that exists and is not an empty folder; nothing is written then.
    Writing that fails half-way (a full disk) leaves nothing behind either.
    """
    _check_name(name)
    parent = Path(parent)
    _check_parent(parent)
    target = parent / name
    staging = parent / f".{name}-{uuid.uuid4().hex[:8]}.partial"
    _check_lengths(parent, target, staging)
    _check_target(target)
    try:
        staging.mkdir()  # as any folder the user makes (mkdtemp's would be private to the user)
    except OSError as exc:
        raise FeedthermError(f"--out: cannot write in {parent} ({exc.strerror or exc})") from None
    try:
        for file in _FILES:
            text = (TEMPLATE / file).read_text(encoding="utf-8")
            (staging / file).write_text(text.replace(PLACEHOLDER, name), encoding="utf-8")
        _move_into_place(staging, target)
    except BaseException as exc:
        shutil.rmtree(staging, ignore_errors=True)
        if isinstance(exc, OSError):
            raise FeedthermError(f"{target}: could not write the bench ({exc.strerror or exc}); nothing was "
                                 "written") from None
        raise
    return target


def _check_name(name: str) -> None:
    if not _NAME.fullmatch(name):
        raise FeedthermError(f"NAME: {name!r} is not a valid bench name (a letter, then letters, digits "
                             "or underscores, as a Python identifier without a leading underscore)")
    if len(name) > MAX_NAME_LENGTH:
        raise FeedthermError(f"NAME: {len(name)} characters long ({name[:20]}...); a bench name has at most "
                             f"{MAX_NAME_LENGTH} (it becomes part of output folders' names)")


def _check_parent(parent: Path) -> None:
    """``--out`` must be an existing folder this process may create entries in."""
    try:
        file_mode = parent.stat().st_mode
    except FileNotFoundError:
        raise FeedthermError(f"--out: {parent} does not exist; create the folder first or choose another") from None
    except OSError as exc:
        raise FeedthermError(f"--out: cannot read {parent} ({exc.strerror or exc})") from None
    if not stat.S_ISDIR(file_mode):
        raise FeedthermError(f"--out: {parent} is {_kind(file_mode)}, not a folder")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise FeedthermError(f"--out: {parent} is not writable (no permission to create a folder in it, or a "
                             "read-only file system)")


def _check_lengths(parent: Path, target: Path, staging: Path) -> None:
    """The staging folder's name (the longest component written) and the longest file's path must fit
    the file system's limits, or the write would fail half-way."""
    name_max = _pathconf(parent, "PC_NAME_MAX", NAME_MAX)
    if len(os.fsencode(staging.name)) > name_max:
        longest = name_max - (len(os.fsencode(staging.name)) - len(os.fsencode(target.name)))
        raise FeedthermError(f"NAME: too long for the file system of {parent} ({name_max} bytes a name, "
                             f"{longest} for a bench's)")
    path_max = _pathconf(parent, "PC_PATH_MAX", PATH_MAX)
    longest_file = max(_FILES, key=len)
    if len(os.fsencode(str((staging / longest_file).absolute()))) >= path_max:
        raise FeedthermError(f"--out: {parent} is nested too deep for the file system: the bench's files would "
                             f"have paths longer than its {path_max} bytes")


def _check_target(target: Path) -> None:
    try:
        file_mode = target.lstat().st_mode  # a symbolic link is in the way as a file is, wherever it points
    except FileNotFoundError:
        return
    except OSError as exc:
        raise FeedthermError(f"{target}: cannot read it ({exc.strerror or exc}); choose another NAME or --out") from None
    if stat.S_ISDIR(file_mode):
        try:
            empty = not any(target.iterdir())
        except OSError as exc:
            raise FeedthermError(f"{target}: exists and cannot be read ({exc.strerror or exc}); choose another NAME "
                                 "or --out") from None
        if empty:
            return
        raise FeedthermError(f"{target}: exists and is a folder that is not empty; choose another NAME or --out")
    raise FeedthermError(f"{target}: exists and is {_kind(file_mode)}; choose another NAME or --out")


def _move_into_place(staging: Path, target: Path) -> None:
    """Rename the complete folder to ``target``; an empty folder there is replaced."""
    try:
        staging.rename(target)  # POSIX replaces an empty folder in one step
    except OSError as exc:
        # Windows does not replace; a target that appeared meanwhile and is not empty stays untouched
        if exc.errno not in (errno.EEXIST, errno.ENOTEMPTY, errno.EACCES) or not target.is_dir() \
                or any(target.iterdir()):
            raise
        target.rmdir()
        staging.rename(target)


def _kind(file_mode: int) -> str:
    """What a path that is not a folder is, for a message."""
    if stat.S_ISREG(file_mode):
        return "a file"
    if stat.S_ISLNK(file_mode):
        return "a symbolic link"
    if stat.S_ISCHR(file_mode) or stat.S_ISBLK(file_mode):
        return "a device"
    if stat.S_ISFIFO(file_mode):
        return "a named pipe"
    if stat.S_ISSOCK(file_mode):
        return "a socket"
    return "not a folder"


def _pathconf(path: Path, name: str, default: int) -> int:
    """The file system's limit ``name`` at ``path`` (os.pathconf), or ``default`` where it does not say."""
    try:
        value = os.pathconf(path, name)
    except (AttributeError, ValueError, OSError):  # no pathconf (Windows), or not for this file system
        return default
    return value if value and value > 0 else default
