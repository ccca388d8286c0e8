"""Duty cycles from CSV files: ``time_s,screw_rpm,nut_rpm,ambient_C``.

Each row holds from its time to the next row's; the last row holds to the end of the run.
Zero speeds are a standstill.  Errors name the file, the line and the reason.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

from pydantic import ValidationError

from ..errors import DescriptionError
from .files import MAX_DATA_BYTES, read_text_file
from .schema import DutyCycle
from .validation_errors import describe_error

HEADER = ["time_s", "screw_rpm", "nut_rpm", "ambient_C"]


def read_duty_cycle_csv(path: str | Path, duration: float) -> DutyCycle:
    """Read a duty cycle; ``duration`` [s] is where the run (and the last row) ends."""
    path = Path(path)
    if not path.exists():
        raise DescriptionError(f"{path}: no such file")
    text = read_text_file(path, str(path), MAX_DATA_BYTES, "duty-cycle")
    try:
        rows = list(csv.reader(text.splitlines()))
    except csv.Error as exc:
        raise DescriptionError(f"{path}: cannot be read ({exc})") from None
    rows = [row for row in rows if any(cell.strip() for cell in row)]
    if not rows:
        raise DescriptionError(f"{path}: the file is empty; expected the header {','.join(HEADER)}")
    header = [cell.strip() for cell in rows[0]]
    if header != HEADER:
        raise DescriptionError(f"{path}: line 1: header must be {','.join(HEADER)}, got {','.join(header)}")
    segments = []
    for number, row in enumerate(rows[1:], start=2):
        if len(row) != len(HEADER):
            raise DescriptionError(f"{path}: line {number}: expected {len(HEADER)} values, got {len(row)}")
        try:
            t, screw, nut, ambient = (float(cell) for cell in row)
        except ValueError:
            raise DescriptionError(f"{path}: line {number}: values must be numbers, got {','.join(row)}") from None
        if not all(math.isfinite(v) for v in (t, screw, nut, ambient)):
            raise DescriptionError(f"{path}: line {number}: values must be finite")
        segments.append({
            "start": f"{t} s", "screw_speed": f"{screw} rpm", "nut_speed": f"{nut} rpm", "ambient": f"{ambient} degC",
        })
    if not segments:
        raise DescriptionError(f"{path}: no rows after the header")
    try:
        return DutyCycle.model_validate({"segments": segments, "duration": f"{duration} s", "description": str(path)})
    except ValidationError as exc:
        raise DescriptionError(f"{path}: {describe_error(exc)}") from None
