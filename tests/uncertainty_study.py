"""A synthetic uncertainty study with the shapes `feedtherm uncertainty` produces on the paper's bench.

Five conditions I–V over 0 … 10,800 s every 60 s, T1–T6 [°C] and D [µm], eight parameters, a prior
set with Sobol indices at condition I and a calibrated set with narrower bands.  Every number
follows from a formula here, so a test can compute what a file must hold.
"""

from __future__ import annotations

import numpy as np

from feedtherm.analysis.uncertainty.types import (
    Band,
    FinalBand,
    SobolIndex,
    UncertainParameter,
    UncertaintySet,
    UncertaintyStudy,
)

CONDITIONS = ("I", "II", "III", "IV", "V")
QUANTITIES = ("T1", "T2", "T3", "T4", "T5", "T6", "D_um")
MEASURED = ("T1", "T2", "T3", "T4", "T5", "D_um")  # Tables 6 and 7: 5 × 6 = 30 values
TIMES = np.arange(0.0, 10_800.0 + 1, 60.0)
PARAMETER_NAMES = ("screw_nut_preload", "front_bearing_preload", "rear_bearing_friction", "guideway_friction",
                   "chtc_scale", "tcr_scale", "motor_loss_scale", "ambient_drift")
#: The prior band's half-width at the end, per unit; the calibrated one is HALF_WIDTH_RATIO of it.
HALF_WIDTH = {"C": 2.0, "um": 8.0}
HALF_WIDTH_RATIO = 0.4


def unit(quantity: str) -> str:
    return "um" if quantity == "D_um" else "C"


def rise(condition: str, quantity: str) -> float:
    """The nominal run's final rise above 20 °C (or D in µm)."""
    c, q = CONDITIONS.index(condition), QUANTITIES.index(quantity)
    return 30.0 + 5.0 * c + 2.0 * q if quantity == "D_um" else 4.0 + c + 1.5 * q


def nominal(condition: str, quantity: str) -> np.ndarray:
    shape = 1.0 - np.exp(-TIMES / 2400.0)
    return (0.0 if quantity == "D_um" else 20.0) + rise(condition, quantity) * shape


def measured(condition: str, quantity: str) -> float:
    """Off the nominal by a pattern: some values fall inside the calibrated band, some only inside
    the prior one, some outside both."""
    c, q = CONDITIONS.index(condition), MEASURED.index(quantity)
    offset = (-1.5, -0.7, 0.0, 0.5, 1.2, 2.5)[(c + q) % 6]  # in half-widths of the prior band
    return round(float(nominal(condition, quantity)[-1] + offset * HALF_WIDTH[unit(quantity)]), 1)


def make_set(label: str, ratio: float, *, sobol: bool) -> UncertaintySet:
    bands, finals = {}, []
    shape = 1.0 - np.exp(-TIMES / 2400.0)
    for condition in CONDITIONS:
        quantiles, nominals = {}, {}
        for quantity in QUANTITIES:
            middle = nominal(condition, quantity)
            half = ratio * HALF_WIDTH[unit(quantity)] * shape
            quantiles[quantity] = np.stack([middle - half, middle + 0.1 * half, middle + half])
            nominals[quantity] = middle
            flag = "elongation off the trend of the others" if (condition, quantity) == ("V", "D_um") else ""
            finals.append(FinalBand(condition, quantity, unit(quantity), float(quantiles[quantity][0, -1]),
                                    float(quantiles[quantity][1, -1]), float(quantiles[quantity][2, -1]),
                                    float(middle[-1]),
                                    measured(condition, quantity) if quantity in MEASURED else None, flag))
        bands[condition] = Band(TIMES.copy(), quantiles, nominals)
    indices = []
    if sobol:
        for q_index, quantity in enumerate(QUANTITIES):
            for p_index, parameter in enumerate(PARAMETER_NAMES):
                s1 = round(0.5 / (1 + (p_index + q_index) % len(PARAMETER_NAMES)), 4)
                indices.append(SobolIndex(quantity, parameter, s1, 0.01, round(s1 + 0.05, 4), 0.02))
    return UncertaintySet(label, parameters(label), bands, finals, runs=512 if label == "prior" else 256,
                          sobol_condition="I" if sobol else None, sobol=indices,
                          calibration={"fit_conditions": ["I", "III"], "parameters": {"screw_nut_preload": 410.0}}
                          if label == "calibrated" else None)


def parameters(label: str) -> list[UncertainParameter]:
    out = []
    for index, name in enumerate(PARAMETER_NAMES):
        scale = index % 2 == 1
        if label == "calibrated" and name == "screw_nut_preload":
            out.append(UncertainParameter(name, "screw-nut preload", "value", ("joints.screw_nut.preload",), 410.0,
                                          "normal", 200.0, 800.0, 35.0, "N", "posterior of the calibration",
                                          "calibrated: feedtherm calibrate"))
            continue
        out.append(UncertainParameter(
            name, f"the {name.replace('_', ' ')}", "scale" if scale else "value", (f"path.to.{name}",),
            1.0 if scale else 300.0 + index, "uniform" if index % 3 else "triangular",
            0.8 if scale else 200.0, 1.25 if scale else 400.0 + index, None, "" if scale else "N",
            f"recalled <{name}> from a catalogue", f"assumption: catalogue {index}"))
    return out


def make_study(*, calibrated: bool = True, sobol: bool = True) -> UncertaintyStudy:
    sets = [make_set("prior", 1.0, sobol=sobol)]
    if calibrated:
        sets.append(make_set("calibrated", HALF_WIDTH_RATIO, sobol=False))
    settings = {"samples": 512, "seed": 7, "sampler": "sobol", "model": "fast", "mode": "physics", "ambient_sensor": "T6",
                "duration_s": 10800.0, "band": [0.05, 0.95], "execution": "serial", "wall_time_s": 12.5}
    return UncertaintyStudy("paper", settings, sets)


def expected_inside(ratio: float) -> int:
    """Measured values within ``ratio`` prior half-widths of the nominal (the band is symmetric)."""
    count = 0
    for condition in CONDITIONS:
        for quantity in MEASURED:
            final = nominal(condition, quantity)[-1]
            half = ratio * HALF_WIDTH[unit(quantity)] * (1.0 - np.exp(-TIMES[-1] / 2400.0))
            count += final - half <= measured(condition, quantity) <= final + half
    return count
