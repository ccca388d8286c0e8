"""Sobol' sensitivity indices by Saltelli's scheme (SALib), on the unit hypercube.

The points are drawn in [0, 1)^d (the problem's bounds are [0, 1] for every parameter) and
mapped to the parameters by the same :func:`~.sampling.to_values` as the bands' points, so the
indices belong to the declared distributions, not to uniform ones.  Without second-order
indices Saltelli's scheme takes N (d + 2) runs for a base of N points; the first-order index
S1 is estimated as in Saltelli et al. (2010), the total index ST by Jansen's formula, and their
95 % confidence intervals by bootstrap (SALib).

References
----------
.. [1] Saltelli, A., Annoni, P., Azzini, I., Campolongo, F., Ratto, M., Tarantola, S. (2010).
   Variance based sensitivity analysis of model output. Design and estimator for the total
   sensitivity index. Computer Physics Communications 181(2), 259-270.
.. [2] Sobol', I. M. (2001). Global sensitivity indices for nonlinear mathematical models and
   their Monte Carlo estimates. Mathematics and Computers in Simulation 55(1-3), 271-280.
"""

from __future__ import annotations

import warnings

import numpy as np

from ...errors import FeedthermError
from .sampling import is_power_of_two


def _problem(names: list[str]) -> dict:
    return {"num_vars": len(names), "names": list(names), "bounds": [[0.0, 1.0]] * len(names)}


def saltelli_points(names: list[str], base: int, seed: int) -> np.ndarray:
    """Saltelli's matrices in [0, 1)^d: ``base`` (d + 2) rows (A, the d mixed matrices, B)."""
    if not is_power_of_two(base):
        raise FeedthermError(f"--sobol-base: must be a power of 2 (Saltelli's scheme draws Sobol' points), got {base}")
    from SALib.sample import sobol as sobol_sample

    return sobol_sample.sample(_problem(names), base, calc_second_order=False, scramble=True, seed=seed)


def sobol_indices(names: list[str], outputs: np.ndarray, seed: int) -> dict[str, np.ndarray]:
    """First-order and total indices of one output at Saltelli's points.

    Returns ``{"S1", "S1_conf", "ST", "ST_conf"}``, one value per parameter (``*_conf``: half the
    95 % bootstrap interval).  An output that does not vary (the ambient sensor) has no indices:
    zeros.
    """
    y = np.asarray(outputs, dtype=float)
    if np.ptp(y) == 0.0:
        zero = np.zeros(len(names))
        return {"S1": zero, "S1_conf": zero, "ST": zero, "ST_conf": zero}
    from SALib.analyze import sobol as sobol_analyze

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # SALib's notes on sample sizes; the intervals say as much
        # A Generator, not the int: SALib seeds its bootstrap only `if seed:`, so seed 0 would
        # draw from numpy's global state and the intervals would differ from run to run.
        found = sobol_analyze.analyze(_problem(names), y, calc_second_order=False, conf_level=0.95,
                                      seed=np.random.default_rng(seed))
    return {key: np.asarray(found[key], dtype=float) for key in ("S1", "S1_conf", "ST", "ST_conf")}
