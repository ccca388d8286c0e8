"""Printed values laid over the physics: how an overlay's values reach other conditions.

At the overlay's reference condition a mapped value is the printed one.  At another condition
it is the printed value times the ratio that the physics correlations give between that
condition and the reference: a source that prints values at one operating point only keeps its
numbers while speed and ambient act as the physics says.  Sources and surfaces that the overlay
does not cover come from the physics unchanged.
"""

from __future__ import annotations


def scaled(printed: float, physics_here: float, physics_reference: float) -> float:
    """``printed * physics_here / physics_reference``; the printed value when the ratio is undefined."""
    if physics_reference == 0.0:
        return printed
    return printed * physics_here / physics_reference
