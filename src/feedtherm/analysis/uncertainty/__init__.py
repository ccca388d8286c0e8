"""Uncertainty studies: prediction bands and Sobol indices from the description's declared uncertainties."""
