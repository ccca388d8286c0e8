"""feedtherm: transient thermal model of machine-tool feed drives.

Data flows one way (see docs/architecture.md):
physics -> system -> boundary conditions -> models -> solution -> analyses/outputs/CLI.

The public API (docs/python-api.md)::

    import feedtherm as ft
    run = ft.simulate(ft.load("ballscrew_example"), condition="v10")
    run.to_dataframe("sensors")          # time [s], a column per sensor [degC], D [um]

``load``, ``simulate``, ``calibrate`` and ``compensate`` (:mod:`feedtherm.api`), the types they
return and the errors they raise.  They are imported when first used (PEP 562), so that
``import feedtherm`` (and every command of the CLI) stays as cheap as reading the version.
"""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("feedtherm")
except PackageNotFoundError:  # running from a source tree without installation
    __version__ = "0.0.0+unknown"

#: Public name -> the module that defines it, imported on first access.
_LAZY = {
    "load": "feedtherm.api",
    "simulate": "feedtherm.simulate",  # the module, callable (see there)
    "calibrate": "feedtherm.api",
    "compensate": "feedtherm.api",
    "LoadedSystem": "feedtherm.system.load",
    "Solution": "feedtherm.solution",
    "EnergyBalance": "feedtherm.solution",
    "CalibrationResult": "feedtherm.analysis.calibration",
    "StudyResult": "feedtherm.analysis.compensation.study",
    "FeedthermError": "feedtherm.errors",
    "ArgumentError": "feedtherm.errors",
    "DescriptionError": "feedtherm.errors",
    "ModelError": "feedtherm.errors",
}

__all__ = ["__version__", *_LAZY]


def __getattr__(name: str):
    # A name of the API is imported on first use and then kept in the module's namespace, so that
    # this runs once per name.  ``simulate`` is the submodule itself, which is callable: the import
    # system sets the package's attribute to a submodule when it is first imported, so a function
    # kept under that name would be replaced by whatever imports feedtherm.simulate first.
    if name not in _LAZY:
        raise AttributeError(f"module 'feedtherm' has no attribute {name!r}")
    from importlib import import_module

    # By name, not an import statement: the modules that read __version__ import this package, and
    # the import graph (import-linter's layers) must not see them reach the API above them.
    module = import_module(_LAZY[name])
    value = module if module.__name__ == f"{__name__}.{name}" else getattr(module, name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *_LAZY})
