"""Models by name: the ones feedtherm ships and any another package registers.

A model is a factory ``(system, options) -> ThermalModel``.  Built-in models are listed
here; another package adds one through the entry-point group ``feedtherm.models`` (the
entry point names a :class:`ModelEntry`), or a program calls :func:`register_model`.
``feedtherm models`` lists the registry.
"""

from __future__ import annotations

import difflib
from dataclasses import dataclass
from functools import cache
from importlib import import_module, metadata
from typing import Callable

from ..errors import ArgumentError, FeedthermError
from ..system.schema import FeedSystem
from .interface import ThermalModel
from .options import ModelOptions

ENTRY_POINT_GROUP = "feedtherm.models"

Factory = Callable[[FeedSystem, ModelOptions], ThermalModel]


@dataclass(frozen=True)
class ModelEntry:
    """A named model: what it is, and how to build it (``factory`` as ``"module:function"`` loads lazily)."""

    name: str
    summary: str
    factory: Factory | str
    uses_mesh: bool = False  # does it take ``--mesh``?
    #: built once before a batch's runs (:func:`feedtherm.simulate.prepare`): it keeps on disk what a
    #: build makes for the runs that follow (the reduced model's projection)
    prepares: bool = False
    #: what of the options a build depends on, for a model whose build is worth keeping: the last
    #: model built is then given again to a build of the same description (the same object) with
    #: the same of these (:func:`forget_built_models`)
    build_options: Callable[[ModelOptions], object] | None = None

    def build(self, system: FeedSystem, options: ModelOptions) -> ThermalModel:
        if self.build_options is not None:
            key = self.build_options(options)
            kept = _kept.pop(self.name, None)  # dropped before another build: one kept model alive at a time
            if kept is not None and kept[0] is system and kept[1] == key:
                _kept[self.name] = kept
                return kept[2]
        factory = self.factory
        if isinstance(factory, str):  # heavy libraries (gmsh, scikit-fem) load only when used
            module, _, attribute = factory.partition(":")
            factory = getattr(import_module(module), attribute)
        model = factory(system, options)
        if not isinstance(model, ThermalModel):
            raise FeedthermError(f"model {self.name!r}: its factory returned {type(model).__name__}, not a ThermalModel")
        if self.build_options is not None:
            _kept[self.name] = (system, key, model)
        return model


#: The last model built of each entry with ``build_options``: (description, key, model).
_kept: dict[str, tuple[FeedSystem, object, ThermalModel]] = {}


def forget_built_models() -> None:
    """Drop the kept models (:attr:`ModelEntry.build_options`), and the memory they hold."""
    _kept.clear()


def _fast(system: FeedSystem, options: ModelOptions) -> ThermalModel:
    from .fast.discretization import FastDiscretization

    return FastDiscretization(system, options)


def _fem_arguments(options: ModelOptions) -> dict:
    """The options the FE model is built from (and all of them: the reduced model's cache key names these)."""
    return {"density": options.mesh, "axial_cells": options.axial_cells, "min_positions": options.steps_per_stroke}


def _fem(system: FeedSystem, options: ModelOptions) -> ThermalModel:
    from .fem.bench import FemDiscretization

    return FemDiscretization(system, **_fem_arguments(options))


def _reduced(system: FeedSystem, options: ModelOptions) -> ThermalModel:
    from .reduced.store import cached_projected_model

    return cached_projected_model(system, options.reduction_tolerance, lambda: _fem(system, options),
                                  lambda: _reduced_inputs(system, options), training=options.reduced_training)


def _reduced_inputs(system: FeedSystem, options: ModelOptions) -> dict | None:
    """What the reduced model's full FE model is built from (models/reduced/store.py): the description's
    structure (models/reduced/training.py), the mesh file's digest (None while it does not exist)
    and the FE model's arguments."""
    from .fem.geometry import mesh_cache_path
    from .reduced.store import file_digest
    from .reduced.training import structure

    mesh = file_digest(mesh_cache_path(system, options.mesh))
    if mesh is None:
        return None
    return {"system": structure(system), "mesh_file": mesh, "full_model": {"name": "fem", **_fem_arguments(options)}}


_BUILT_IN = (
    ModelEntry("fast", "thermal network: the screw in axial cells × rings, the other parts in sub-volumes "
                       "(docs/fast-model.md)", _fast),
    # An FE model's build (mesh, matrices), its contacts at every position and its elastic factor take
    # 5 s on the coarse mesh and 15 s on the medium one: the runs of one description (a validation's
    # conditions, a calibration point's) share them, as they share the model's caches
    ModelEntry("fem", "3D finite elements (gmsh + scikit-fem), every part meshed, joints as interface "
                      "conductances (docs/fem-model.md)", _fem, uses_mesh=True,
               build_options=lambda options: tuple(_fem_arguments(options).items())),
    ModelEntry("reduced", "the FE model projected onto a moment-matching basis: the same mesh and moving nut, "
                          "a few hundred unknowns (docs/reduced-model.md)", _reduced, uses_mesh=True,
               prepares=True),
)
_registered: dict[str, ModelEntry] = {}


def register_model(entry: ModelEntry) -> None:
    """Add (or replace) a model under ``entry.name``."""
    _registered[entry.name] = entry


def unregister_model(name: str) -> None:
    _registered.pop(name, None)


def available_models() -> dict[str, ModelEntry]:
    """Every model by name: built-in, then entry points, then registered at run time."""
    models = {entry.name: entry for entry in _BUILT_IN}
    models.update((entry.name, entry) for entry in _plugged_in())
    models.update(_registered)
    return models


@cache
def _plugged_in() -> tuple[ModelEntry, ...]:
    """The models of the entry points, read once per process: every run's plan looks its model up,
    and reading the installed packages' metadata took a twentieth of a cycle-averaged fast run."""
    entries = []
    for point in metadata.entry_points(group=ENTRY_POINT_GROUP):
        try:
            entry = point.load()
        except Exception as exc:  # a broken plug-in must not break the built-in models
            raise FeedthermError(f"entry point {point.name!r} ({point.value}) in {ENTRY_POINT_GROUP} "
                                 f"cannot be loaded: {exc}") from None
        if not isinstance(entry, ModelEntry):
            raise FeedthermError(f"entry point {point.name!r} in {ENTRY_POINT_GROUP} is not a ModelEntry")
        entries.append(entry)
    return tuple(entries)


def model_entry(name: str) -> ModelEntry:
    """The model called ``name``; an unknown name is one line with the closest ones."""
    models = available_models()
    if name not in models:
        close = difflib.get_close_matches(name, models, n=1)
        hint = f"; did you mean {close[0]!r}?" if close else ""
        raise ArgumentError("model", f"no model {name!r}; models: {', '.join(models)}{hint}")
    return models[name]


def build_model(name: str, system: FeedSystem, options: ModelOptions) -> ThermalModel:
    """Discretise ``system`` with the model called ``name``."""
    return model_entry(name).build(system, options)
