"""Reduced-order models: a full model projected onto a moment-matching basis (:mod:`.basis`,
:mod:`.projection`, :mod:`.model`), kept on disk (:mod:`.store`)."""

from .basis import Basis, moment_basis
from .model import ProjectedModel
from .projection import Projection, project

__all__ = ["Basis", "ProjectedModel", "Projection", "moment_basis", "project"]
