"""Paper mode: the paper's Table 1 heats and Table 2 CHTCs, carried to other conditions.

At the paper's reference condition (I) a mapped value is the printed one.  At another
condition it is the printed value times the ratio that the physics correlations give
between that condition and the reference: the paper states values at one operating point
only, and this keeps its numbers while letting speed and ambient act as the physics says.
Sources and surfaces that the tables do not cover come from the physics unchanged.
"""

from __future__ import annotations


def scaled(printed: float, physics_here: float, physics_reference: float) -> float:
    """``printed * physics_here / physics_reference``; the printed value when the ratio is undefined."""
    if physics_reference == 0.0:
        return printed
    return printed * physics_here / physics_reference
