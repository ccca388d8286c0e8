"""A finding of ``feedtherm check``: a path in the description, what is wrong there, how bad."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Finding:
    path: str
    message: str
    severity: str = "warning"  # or "error": no model can run the description as meant

    def __str__(self) -> str:
        return f"{self.path}: {self.message}"
