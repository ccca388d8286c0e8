"""Pure physical correlations in SI units.

Nothing in this sub-package imports any other part of feedtherm: every function takes
floats (or numpy arrays) in SI units and returns SI values.  Each function documents
its equation, units, validity range and source.
"""
