"""feedtherm: transient thermal model of machine-tool feed drives.

Data flows one way (see docs/architecture.md):
physics -> system -> boundary conditions -> models -> solution -> analyses/outputs/CLI.
"""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("feedtherm")
except PackageNotFoundError:  # running from a source tree without installation
    __version__ = "0.0.0+unknown"

__all__ = ["__version__"]
