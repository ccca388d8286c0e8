"""Reading a user's file as text, safely: a regular file only, of a bounded size, UTF-8 with or
without a byte-order mark; every refusal one line naming the file.

A FIFO or a device (``/dev/zero``) would block the reader or fill the memory, so only regular
files are read, and only up to a size no real input approaches.
"""

from __future__ import annotations

import stat
import tomllib
from pathlib import Path

from ..errors import DescriptionError

#: Largest description [bytes]: the bundled benches' are 40-60 kB, so 16 MB is hundreds of times
#: any real machine's and still reads in a moment; a larger file is the wrong file.
MAX_DESCRIPTION_BYTES = 16 * 2**20
#: Largest measurement or duty-cycle CSV [bytes]: a day of 20 sensors logged every second is
#: about 30 MB; 256 MB leaves room for longer logs and still fits in memory as text.
MAX_DATA_BYTES = 256 * 2**20
#: Deepest nesting of tables and arrays a description may have: the schema's deepest is 5
#: (``sources.X.losses``, ``mechanics.elongation.target.point``); Python's TOML reader recurses
#: once per level and would fail with a RecursionError far beyond.
MAX_TOML_DEPTH = 32


def read_text_file(path: str | Path, origin: str, limit: int = MAX_DESCRIPTION_BYTES, what: str = "description") -> str:
    """The text of the regular file ``path`` (at most ``limit`` bytes, UTF-8, a BOM dropped)."""
    path = Path(path)
    a = "an" if what[:1] in "aeiou" else "a"
    try:
        info = path.stat()  # does not open it: a FIFO does not block here
    except OSError as exc:
        raise DescriptionError(f"{origin}: cannot be read ({exc.strerror or exc})") from None
    if stat.S_ISDIR(info.st_mode):
        raise DescriptionError(f"{origin}: is a directory, not a file")
    if not stat.S_ISREG(info.st_mode):
        raise DescriptionError(f"{origin}: is not a regular file (a pipe, a device or a socket); give the path of "
                               f"{a} {what} file")
    too_big = (f"{origin}: is larger than the {limit // 2**20} MB {a} {what} may have (feedtherm.system.files); "
               "is it the right file?")
    if info.st_size > limit:
        raise DescriptionError(too_big)
    try:
        with open(path, "rb") as stream:
            data = stream.read(limit + 1)  # the file may have grown since
    except OSError as exc:
        raise DescriptionError(f"{origin}: cannot be read ({exc.strerror or exc})") from None
    if len(data) > limit:
        raise DescriptionError(too_big)
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise DescriptionError(f"{origin}: is not UTF-8 text (byte {exc.start} cannot be decoded: {exc.reason})") \
            from None


def nesting_depth(data) -> int:
    """How deep tables and arrays nest in parsed TOML (a scalar is 0), without recursion."""
    deepest, stack = 0, [(data, 0)]
    while stack:
        value, depth = stack.pop()
        if isinstance(value, dict):
            children = value.values()
        elif isinstance(value, list):
            children = value
        else:
            continue
        deepest = max(deepest, depth + 1)
        if deepest > MAX_TOML_DEPTH:
            return deepest
        stack.extend((child, depth + 1) for child in children)
    return deepest


def parse_bounded_toml(text: str, origin: str, what: str = "description", deepest: int = 5) -> dict:
    """TOML text parsed, its tables and arrays nested at most MAX_TOML_DEPTH levels; a one-line
    DescriptionError naming ``origin`` otherwise (``deepest``: how deep a valid ``what`` nests)."""
    try:
        data = tomllib.loads(text.removeprefix("\ufeff"))
    except tomllib.TOMLDecodeError as exc:
        raise DescriptionError(f"{origin}: invalid TOML: {exc}") from None
    except RecursionError:
        data = None
    if data is None or nesting_depth(data) > MAX_TOML_DEPTH:
        a = "an" if what[:1] in "aeiou" else "a"
        raise DescriptionError(f"{origin}: tables or arrays nest deeper than {MAX_TOML_DEPTH} levels; {a} {what} "
                               f"nests {deepest} at most") from None
    return data
