"""Thermal equilibrium time, following the paper's criterion made precise.

The paper (§4.2): equilibrium when "the temperature rise reached 95 % of the maximum
temperature rise and the stable fluctuation of the value of the multiple temperature
measurement points was less than 0.5 °C".  feedtherm's definition, on the cycle-averaged
sensor series (each value the mean over the preceding full reciprocation cycle):

``t_eq`` is the first time t at which, for every sensor,

1. the rise since the start has reached 95 % of the steady-state rise
   (sensors whose steady rise is below 0.1 K are exempt), and
2. the cycle-averaged value varied by less than 0.5 K over the 600 s ending at t.

``None`` when the run ends first.

The same two criteria per quantity (:func:`equilibrium_times`) say which sensor settles last,
and when the elongation D settles: for D the fluctuation bound is ``D_FLUCTUATION_M`` (1 µm)
and rises below ``D_MIN_RISE_M`` (0.2 µm) are exempt.  1 µm is the paper's 0.5 K carried over
to a length: 0.5 K on the 170 mm of steel screw (12e-6 1/K) between the paper bench's fixed
bearing and its laser is 0.5 × 12e-6 × 0.17 m = 1.0 µm; 0.2 µm likewise stands for its 0.1 K.
"""

from __future__ import annotations

import numpy as np

RISE_FRACTION = 0.95
FLUCTUATION_K = 0.5
WINDOW_S = 600.0
MIN_RISE_K = 0.1
D_FLUCTUATION_M = 1e-6  # [m] D's counterpart of FLUCTUATION_K (module docstring)
D_MIN_RISE_M = 0.2e-6  # [m] D's counterpart of MIN_RISE_K


def equilibrium_time(times: np.ndarray, series: dict[str, np.ndarray], initial: dict[str, float],
                     steady: dict[str, float], *, fluctuation: float = FLUCTUATION_K,
                     min_rise: float = MIN_RISE_K) -> float | None:
    """First time [s] at which every series meets both criteria (see module docstring).

    ``fluctuation`` and ``min_rise`` are in the series' unit (K for temperatures, m for D).
    """
    times = np.asarray(times, dtype=float)
    if times.size == 0:
        return None
    ok = np.ones(times.size, dtype=bool)
    for name, values in series.items():
        values = np.asarray(values, dtype=float)
        rise_steady = steady[name] - initial[name]
        if abs(rise_steady) >= min_rise:
            ok &= (values - initial[name]) / rise_steady >= RISE_FRACTION
        ok &= _trailing_range(times, values) < fluctuation
    ok &= times >= times[0] + WINDOW_S
    hits = np.nonzero(ok)[0]
    return float(times[hits[0]]) if hits.size else None


def equilibrium_times(times: np.ndarray, sensors: dict[str, np.ndarray], elongation: np.ndarray,
                      initial: dict[str, float], steady: dict[str, float],
                      elongation_key: str) -> dict[str, float | None]:
    """The equilibrium time [s] of each sensor on its own, and of D (under ``elongation_key``).

    ``sensors`` are cycle-averaged temperatures [K], ``elongation`` the cycle-averaged D [m];
    ``initial`` and ``steady`` hold both, D under ``elongation_key``.  None where the run ends first.
    """
    out: dict[str, float | None] = {name: equilibrium_time(times, {name: values}, initial, steady)
                                    for name, values in sensors.items()}
    out[elongation_key] = equilibrium_time(times, {elongation_key: elongation}, initial, steady,
                                           fluctuation=D_FLUCTUATION_M, min_rise=D_MIN_RISE_M)
    return out


def _trailing_range(times: np.ndarray, values: np.ndarray) -> np.ndarray:
    """max - min of ``values`` over [t - WINDOW_S, t] at every t (``times`` ascending).

    Every window's extremes from two overlapping power-of-two spans of a sparse table (the
    spans' max and min, doubled level by level): exact, and without a Python loop over samples.
    """
    values = np.asarray(values, dtype=float)
    n = values.size
    if n == 0:
        return values.copy()
    end = np.arange(n)
    start = np.searchsorted(times, np.asarray(times, dtype=float) - WINDOW_S, side="left")
    start = np.minimum(start, end)
    highs, lows = [values], [values]
    while 2 ** len(highs) <= n:
        half = 2 ** (len(highs) - 1)
        highs.append(np.maximum(highs[-1][:-half], highs[-1][half:]))
        lows.append(np.minimum(lows[-1][:-half], lows[-1][half:]))
    level = np.log2(end - start + 1).astype(int)  # the largest 2^level <= the window's length
    out = np.empty(n)
    for k in np.unique(level):
        rows = np.nonzero(level == k)[0]
        left, right = start[rows], end[rows] - 2 ** k + 1
        out[rows] = (np.maximum(highs[k][left], highs[k][right]) - np.minimum(lows[k][left], lows[k][right]))
    return out


def rise_time(times: np.ndarray, series: dict[str, np.ndarray], initial: dict[str, float],
              steady: dict[str, float], fraction: float = RISE_FRACTION) -> float:
    """Time [s] at which the slowest sensor has risen by ``fraction`` of its steady rise.

    The first criterion of :func:`equilibrium_time` as a continuous quantity, for fitting: the
    crossing is interpolated linearly between samples, and a sensor that has not crossed by
    the end of the run is extrapolated with the exponential decay of its remaining rise over
    the last two samples, ``1 - r(t) ∝ exp(-t/τ)``.  ``inf`` if a sensor's remaining rise does
    not decay.  Sensors whose steady rise is below ``MIN_RISE_K`` are exempt (0 if all are).

    >>> t = np.arange(0.0, 3001.0, 100.0)
    >>> round(rise_time(t, {"a": 1 - np.exp(-t / 1000)}, {"a": 0.0}, {"a": 1.0}), 1)  # 1000 ln 20 = 2995.7
    2995.9
    >>> round(rise_time(t[:11], {"a": 1 - np.exp(-t[:11] / 1000)}, {"a": 0.0}, {"a": 1.0}), 1)  # extrapolated
    2995.7
    """
    times = np.asarray(times, dtype=float)
    slowest = 0.0
    for name, values in series.items():
        rise_steady = steady[name] - initial[name]
        if abs(rise_steady) < MIN_RISE_K:
            continue
        r = (np.asarray(values, dtype=float) - initial[name]) / rise_steady
        hits = np.nonzero(r >= fraction)[0]
        if hits.size:
            i = hits[0]
            if i == 0:
                t = times[0]
            else:
                t = times[i - 1] + (fraction - r[i - 1]) / (r[i] - r[i - 1]) * (times[i] - times[i - 1])
        else:
            g_a, g_b = 1.0 - r[-2], 1.0 - r[-1]
            if not 0.0 < g_b < g_a:
                return float("inf")
            tau = (times[-1] - times[-2]) / np.log(g_a / g_b)
            t = times[-1] + tau * np.log(g_b / (1.0 - fraction))
        slowest = max(slowest, float(t))
    return slowest
