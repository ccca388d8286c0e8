"""Constants shared across the layers above physics: names and unit factors.

Physics functions keep their own constants (``physics/`` imports nothing of ours).
"""

import math
import os
from pathlib import Path

#: Name of the screw's elongation among a model's probes.
ELONGATION_PROBE = "D"
#: 0 °C in kelvin.
KELVIN_OFFSET = 273.15
#: rpm per rad/s, 60/(2π).
RPM_PER_RAD_S = 60.0 / (2.0 * math.pi)


def cache_root() -> Path:
    """Where feedtherm keeps what it can rebuild (meshes, parsed unit definitions):
    ``$FEEDTHERM_CACHE``, default ``~/.cache/feedtherm``."""
    root = os.environ.get("FEEDTHERM_CACHE")
    return Path(root).expanduser() if root else Path.home() / ".cache" / "feedtherm"
