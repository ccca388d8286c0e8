"""Every number the boundary-condition step evaluates is finite and physical, or one line names it.

The description's values each lie in their declared range (:mod:`feedtherm.system.quantities`),
but a heat, a coefficient or a viscosity combines several of them at an operating point, and a
combination can still leave what a machine can be: a motor's copper loss from a tiny torque
constant, an oil's viscosity far below its pour point.  Here each evaluated value is checked
against the range its quantity has in a description, and numpy's overflow, division by zero
and invalid operations raise instead of warning (:func:`numeric_errors`): a ``RuntimeWarning``
never reaches the user, a :class:`~feedtherm.errors.ModelError` naming the value does.
"""

from __future__ import annotations

import math
import warnings
from contextlib import contextmanager

import numpy as np

from ..errors import ModelError
from ..system.quantities import HTC_LIMIT, KINEMATIC_VISCOSITY_LIMIT, POWER_LIMIT, Limit

_KELVIN_AT_0C = 273.15


@contextmanager
def numeric_errors():
    """Floating-point overflow, division by zero and invalid operations raise inside.

    numpy raises ``FloatingPointError`` (underflow to zero stays silent: a vanishing term is
    a value), and any other ``RuntimeWarning`` becomes an exception, for the caller to name.
    """
    with np.errstate(over="raise", divide="raise", invalid="raise"), warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        yield


def _outside(value: float, limit: Limit) -> bool:
    return not (math.isfinite(value) and limit.low <= value <= limit.high)


def check_heat(path: str, power: float, details: dict, heat_factor: float = 1.0) -> None:
    """A source's heat [W] and the values that made it: finite, the heat within 0 to 1 MW."""
    bad = [key for key, value in details.items()
           if isinstance(value, float) and not isinstance(value, bool) and not math.isfinite(value)]
    if not _outside(power, POWER_LIMIT) and not bad:
        return
    if heat_factor != 1.0 and math.isfinite(power) and not _outside(power / heat_factor, POWER_LIMIT):
        path = f"{path}.heat_factor"
    shown = ", ".join(f"{key} = {details[key]:g}" for key in bad)
    raise ModelError(f"{path}: its heat here is {power:.4g} W{f' ({shown})' if shown else ''}, outside "
                     f"{POWER_LIMIT.describe()}: a value of the source is beyond what a feed drive has")


def check_coefficient(path: str, convection: float, radiation: float) -> None:
    """A surface's convective and radiative coefficients [W/(m^2 K)]: finite, within the HTC range."""
    for what, value in (("convective", convection), ("radiative", radiation)):
        if _outside(value, HTC_LIMIT):
            raise ModelError(f"{path}: its {what} coefficient here is {value:.4g} W/(m^2*K), outside "
                             f"{HTC_LIMIT.describe()}")


def check_viscosity(path: str, nu: float, temperature: float, where: str) -> None:
    """A lubricant's kinematic viscosity [m^2/s] at ``temperature`` [K]: finite, within the range
    a description may state.  ``where`` says why the lubricant is at that temperature."""
    if not _outside(nu, KINEMATIC_VISCOSITY_LIMIT) and nu > 0.0:
        return
    celsius = temperature - _KELVIN_AT_0C
    cold = not nu <= KINEMATIC_VISCOSITY_LIMIT.high  # and not finite
    raise ModelError(f"{path}: the oil's viscosity at {celsius:.4g} degC ({where}) is {nu * 1e6:.4g} mm^2/s by "
                     f"Walther's equation, outside {KINEMATIC_VISCOSITY_LIMIT.describe()}"
                     + (": the oil is too cold there; state a warmer ambient, or an oil for this cold" if cold else ""))
