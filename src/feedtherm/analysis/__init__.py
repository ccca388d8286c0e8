"""Analyses that read Solutions: elongation, equilibrium, validation, sweeps, calibration."""
