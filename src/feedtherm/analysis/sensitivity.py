"""One-at-a-time sensitivity of the steady state to every declared numeric value.

Each numeric value of the description that can act on the temperatures — material
conductivities and expansion, joint resistances and areas, heat-source parameters, surface
lengths, areas and emissivities, the frozen CHTC rise, the lead — is multiplied by
``factor`` alone, and the cycle-averaged steady state of one condition is solved again.
Geometry (part shapes and positions), sensor positions, the stroke, the conditions and the
reference temperature are not perturbed: changing them changes the machine, not an
uncertain parameter.  Heat capacities do not act on a steady state and are left out.
"""

from __future__ import annotations

import re
from typing import Callable

from ..constants import ELONGATION_PROBE
from ..simulate import steady_state
from ..system.checks import covers, specificity
from ..system.load import LoadedSystem
from ..system.paths import get_path, leaf_paths
from ..system.variants import with_values
from .validation_types import ELONGATION_QUANTITY, Sensitivity

PERTURBED_SECTIONS = ("materials", "joints", "sources", "surfaces", "temperatures.convection_delta_t", "kinematics.lead")
SKIPPED_FIELDS = {"density", "specific_heat", "youngs_modulus", "poisson_ratio", "carriages", "origin", "position"}


def perturbable_paths(loaded: LoadedSystem) -> list[str]:
    """Dotted paths of the numeric values a sensitivity study perturbs."""
    data = loaded.system.model_dump(exclude_defaults=True)
    paths = []
    for path in leaf_paths(data):
        if not any(covers(section, path) for section in PERTURBED_SECTIONS):
            continue
        if path.rsplit(".", 1)[-1] in SKIPPED_FIELDS or ".into." in path:
            continue
        value = get_path(loaded.system, path)
        if isinstance(value, float) and not isinstance(value, bool) and value != 0.0:
            paths.append(path)
    return paths


def readable_name(loaded: LoadedSystem, path: str) -> str:
    """A joint's path by the parts it joins: ``joints[9].tcr`` -> ``joint nut–screw: tcr``.

    Other paths are already named (``sources.front_bearing.preload``) and give ``""``.
    """
    match = re.fullmatch(r"joints\[(\d+)\]\.(.+)", path)
    if match is None:
        return ""
    index, rest = int(match.group(1)), match.group(2)
    joints = loaded.system.joints
    if index >= len(joints):
        return ""
    a, b = joints[index].between
    return f"joint {a}–{b}: {rest}"


def source_of(loaded: LoadedSystem, path: str) -> str:
    """The provenance entry covering ``path`` (the longest matching prefix)."""
    best, text = (-1, -1), "undeclared"
    for entry in loaded.system.provenance:
        for prefix in entry.paths:
            if covers(prefix, path) and specificity(prefix) > best:
                best, text = specificity(prefix), f"{entry.origin}: {entry.source}"
    return text


def sensitivities(loaded: LoadedSystem, condition: str, *, factor: float = 1.1,
                  progress: Callable[[float], None] | None = None) -> list[Sensitivity]:
    """Effect of each perturbable value, scaled by ``factor``, on the steady sensor temperatures [K] and D [µm]."""
    base = steady_state(loaded, condition)
    paths = perturbable_paths(loaded)
    out = []
    for i, path in enumerate(paths):
        value = get_path(loaded.system, path)
        variant = with_values(loaded, {path: value * factor}, origin_suffix=f"{path} x {factor:g}")
        perturbed = steady_state(variant, condition)
        effect = {name: perturbed[name] - base[name] for name in base if name not in (ELONGATION_PROBE, loaded.system.room.ambient_sensor)}
        effect[ELONGATION_QUANTITY] = (perturbed["D"] - base["D"]) * 1e6
        out.append(Sensitivity(path, source_of(loaded, path), factor, effect, name=readable_name(loaded, path)))
        if progress is not None:
            progress((i + 1) / len(paths))
    return sorted(out, key=lambda s: (s.max_temperature_effect, abs(s.effect[ELONGATION_QUANTITY])), reverse=True)
