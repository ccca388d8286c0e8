"""Reduced-order models: a full model projected onto a moment-matching basis (:mod:`.basis`, :mod:`.projection`)."""

from .basis import Basis, moment_basis
from .projection import ProjectedModel

__all__ = ["Basis", "ProjectedModel", "moment_basis"]
