"""The Python API's reference: an autodoc directive per name of ``feedtherm.__all__``."""

from __future__ import annotations

import types
from dataclasses import dataclass

from .rst import heading


@dataclass(frozen=True)
class ApiEntry:
    """A public name of ``feedtherm`` and the autodoc directive that documents it."""

    name: str
    directive: str
    target: str


def api_entries() -> list[ApiEntry]:
    """Every name of ``feedtherm.__all__`` but the version, as autodoc documents it."""
    import feedtherm

    entries = []
    for name in feedtherm.__all__:
        if name == "__version__":
            continue
        value = getattr(feedtherm, name)
        if isinstance(value, types.ModuleType):  # ``simulate``: the callable module runs its function
            entries.append(ApiEntry(name, "autofunction", f"{value.__name__}.{name}"))
        elif isinstance(value, type) and issubclass(value, BaseException):
            entries.append(ApiEntry(name, "autoexception", f"feedtherm.{name}"))
        elif isinstance(value, type):
            entries.append(ApiEntry(name, "autoclass", f"feedtherm.{name}"))
        else:
            entries.append(ApiEntry(name, "autofunction", f"feedtherm.{name}"))
    return entries


def api_rst(entries: list[ApiEntry] | None = None) -> str:
    entries = api_entries() if entries is None else entries
    lines: list[str] = []
    for kind, title in (("autofunction", "Functions"), ("autoclass", "Types"), ("autoexception", "Errors")):
        chosen = [e for e in entries if e.directive == kind]
        if not chosen:
            continue
        lines += heading(title, "-")
        for entry in chosen:
            lines += [f".. {entry.directive}:: {entry.target}"]
            if kind != "autofunction":
                lines += ["   :members:", "   :show-inheritance:"]
            lines += [""]
    return "\n".join(lines)
