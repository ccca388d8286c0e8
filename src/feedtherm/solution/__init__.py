"""The result of a simulation, the same for every model.

Analyses, outputs and the CLI read only this type; they never reach into a solver.
Temperatures are in kelvin and lengths in metres inside; converters below give the °C and
µm that files and plots show, properties named with their unit (``sensors_degC``,
``positioning_error_um``) say which one a value is in, and :meth:`Solution.to_dataframe` gives
the series as pandas tables.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ..constants import ELONGATION_PROBE, KELVIN_OFFSET
from .fields import FieldSeries

if TYPE_CHECKING:  # pandas is imported where a table is built (.tables)
    import pandas as pd

ENERGY_FLOOR_J = 1.0  # [J] smallest energy scale of the balance


@dataclass(frozen=True)
class EnergyBalance:
    """Heat in, lost and stored over a run [J], computed apart from the solver's matrices.

    Attributes
    ----------
    heat_in : float
        Heat the sources put in [J].
    heat_lost : float
        Heat lost to the surroundings [J].
    heat_stored : float
        Heat stored in the parts [J].
    """

    heat_in: float
    heat_lost: float
    heat_stored: float

    @property
    def residual(self) -> float:
        """In − lost − stored [J]."""
        return self.heat_in - self.heat_lost - self.heat_stored

    @property
    def relative_error(self) -> float:
        """``residual / max(in, |lost| + |stored|, 1 J)``.

        The 1 J floor keeps a run with (almost) no heat — a standstill at ambient — from
        dividing round-off by round-off.
        """
        scale = max(abs(self.heat_in), abs(self.heat_lost) + abs(self.heat_stored), ENERGY_FLOOR_J)
        return self.residual / scale


@dataclass(frozen=True)
class Ledger:
    """The energy account over time, by part and by source: what ``parts.csv`` and ``heat.csv`` hold.

    With :attr:`Solution.part_temperatures` (capacity-weighted part means) the heat stored from the
    start to a sample is ``Σ_p capacities[p] · (T̄_p(t) − T̄_p(0))``, the model's own stored heat
    (:meth:`~feedtherm.models.interface.ThermalModel.part_capacities`); the heats in and lost
    since the start are kept as the energy account sums them, step by step.

    Attributes
    ----------
    capacities : dict[str, float] or None
        Heat capacity ρcV [J/K] of every part (a projected model: its full model's); None if the
        model does not say.
    heat_in : dict[str, ndarray]
        Each source's heat since the start [J] at :attr:`Solution.times`, in the description's order;
        at the last sample their sum is ``energy.heat_in``.
    heat_lost : ndarray
        Heat lost to the air and the surfaces' sinks since the start [J] at the sample times.
    first_heat_in : dict[str, float]
        Each source's heat in the first time step [W].
    first_heat_lost : float
        The heat lost in the first time step [W].
    """

    capacities: dict[str, float] | None
    heat_in: dict[str, np.ndarray]
    heat_lost: np.ndarray
    first_heat_in: dict[str, float]
    first_heat_lost: float


@dataclass(frozen=True)
class Solution:
    """Sensor series, screw fields and summary values of one run.

    Every field is in SI units (s, K, m, J).  Beside each, a property whose name ends in its unit
    gives the same values in that unit: ``time_s``, ``sensors_K``, ``sensors_degC``,
    ``elongation_m``, ``elongation_um``, ``screw_x_m``, ``screw_temperature_K``,
    ``screw_temperature_degC``, ``screw_displacement_m``, ``screw_displacement_um``,
    ``table_x_m``, ``positioning_error_m``, ``positioning_error_um``, ``nut_offset_m``,
    ``part_temperatures_K``, ``part_temperatures_degC``, ``equilibrium_time_s``.
    :meth:`to_dataframe` tabulates the series with units in the column names.

    Attributes
    ----------
    times : ndarray, shape (n,)
        Sample times [s], from 0 to the end of the run.
    sensors : dict[str, ndarray]
        Sensor temperatures [K] at ``times``: the declared sensors and the ambient (:attr:`ambient_sensor`).
    elongation : ndarray, shape (n,)
        The elongation D [m]: what the declared displacement sensor reads
        (``mechanics.elongation``), zero at the reference temperature (the quantity compared
        with measurements).
    screw_x : ndarray, shape (m,)
        Axial positions [m] of the screw cells (centres).
    screw_temperature : ndarray, shape (n, m)
        Cross-section mean screw temperature [K] by time and position.
    screw_displacement : ndarray, shape (n, m)
        Axial thermal displacement [m] along the screw (its section mean at ``screw_x``),
        relative to the positioning reference point (``mechanics.positioning``).
    table_x : ndarray, shape (p,)
        Table positions [m]: the nut's centre along x at each position of the stroke.
    positioning_error : ndarray, shape (n, p)
        The thermal positioning error E(x, t) [m]: the screw's axial displacement under the
        nut at each table position, relative to the positioning reference.
    nut_offset : ndarray, shape (n,)
        Displacement [m] of the moving group from the middle of the stroke.
    part_temperatures : dict[str, ndarray]
        Mean temperature [K] of every part at ``times``, each node weighted by its heat capacity.
    cycle_times : ndarray
        Midpoints [s] of the full reciprocation cycles.
    cycle_sensors : dict[str, ndarray]
        Sensor temperatures [K] averaged over each full cycle.
    cycle_elongation : ndarray
        D [m] averaged over each full cycle.
    final : dict[str, float]
        Sensor temperatures [K] and ``D`` [m]: the mean over the last full cycle.
    steady : dict[str, float]
        The same quantities from the cycle-averaged steady state of the final operating point.
    equilibrium_time : float or None
        When the run reached thermal equilibrium [s] (definition: docs/fast-model.md), None if it did not.
    energy : EnergyBalance
        Heat in, lost and stored over the run [J].
    info : dict
        Model, mode, condition, time step, unknowns, wall time, provenance (JSON-able).
    fields : FieldSeries or None
        Full temperature fields every ``snapshot_interval`` on the model's mesh (FE runs).
    equilibrium_times : dict[str, float or None]
        The equilibrium time [s] of each sensor on its own and of ``D`` (its own bounds:
        :func:`feedtherm.solution.equilibrium.equilibrium_times`); None where the run ended first.
    ledger : Ledger or None
        Each part's capacity and each source's heat over time (every model's run has one).
    """

    times: np.ndarray
    sensors: dict[str, np.ndarray]
    elongation: np.ndarray
    screw_x: np.ndarray
    screw_temperature: np.ndarray
    screw_displacement: np.ndarray
    table_x: np.ndarray
    positioning_error: np.ndarray
    nut_offset: np.ndarray
    part_temperatures: dict[str, np.ndarray]
    cycle_times: np.ndarray
    cycle_sensors: dict[str, np.ndarray]
    cycle_elongation: np.ndarray
    final: dict[str, float]
    steady: dict[str, float]
    equilibrium_time: float | None
    energy: EnergyBalance
    info: dict = field(default_factory=dict)
    fields: FieldSeries | None = None
    equilibrium_times: dict[str, float | None] = field(default_factory=dict)
    ledger: Ledger | None = None

    @property
    def sensor_names(self) -> list[str]:
        return list(self.sensors)

    @property
    def ambient_sensor(self) -> str:
        """Which of :attr:`sensors` is the air's temperature (the description's ``room.ambient_sensor``)."""
        return self.info.get("ambient_sensor", "ambient")

    def sensors_celsius(self) -> dict[str, np.ndarray]:
        """:attr:`sensors` in °C (the same as :attr:`sensors_degC`)."""
        return {name: values - KELVIN_OFFSET for name, values in self.sensors.items()}

    # The fields under names that carry their unit (views, no copies where the unit is SI).

    @property
    def time_s(self) -> np.ndarray:
        """:attr:`times` [s]."""
        return self.times

    @property
    def sensors_K(self) -> dict[str, np.ndarray]:
        """:attr:`sensors` [K]."""
        return self.sensors

    @property
    def sensors_degC(self) -> dict[str, np.ndarray]:
        """:attr:`sensors` [°C]."""
        return self.sensors_celsius()

    @property
    def elongation_m(self) -> np.ndarray:
        """:attr:`elongation` D [m]."""
        return self.elongation

    @property
    def screw_x_m(self) -> np.ndarray:
        """:attr:`screw_x` [m]."""
        return self.screw_x

    @property
    def screw_temperature_K(self) -> np.ndarray:
        """:attr:`screw_temperature` [K], shape (times, screw_x)."""
        return self.screw_temperature

    @property
    def screw_temperature_degC(self) -> np.ndarray:
        """:attr:`screw_temperature` [°C], shape (times, screw_x)."""
        return self.screw_temperature - KELVIN_OFFSET

    @property
    def screw_displacement_m(self) -> np.ndarray:
        """:attr:`screw_displacement` [m], shape (times, screw_x)."""
        return self.screw_displacement

    @property
    def screw_displacement_um(self) -> np.ndarray:
        """:attr:`screw_displacement` [µm], shape (times, screw_x)."""
        return self.screw_displacement * 1e6

    @property
    def table_x_m(self) -> np.ndarray:
        """:attr:`table_x` [m]."""
        return self.table_x

    @property
    def positioning_error_m(self) -> np.ndarray:
        """:attr:`positioning_error` E(x, t) [m], shape (times, table_x)."""
        return self.positioning_error

    @property
    def positioning_error_um(self) -> np.ndarray:
        """:attr:`positioning_error` E(x, t) [µm], shape (times, table_x)."""
        return self.positioning_error * 1e6

    @property
    def nut_offset_m(self) -> np.ndarray:
        """:attr:`nut_offset` [m]."""
        return self.nut_offset

    @property
    def part_temperatures_K(self) -> dict[str, np.ndarray]:
        """:attr:`part_temperatures` [K]."""
        return self.part_temperatures

    @property
    def part_temperatures_degC(self) -> dict[str, np.ndarray]:
        """:attr:`part_temperatures` [°C]."""
        return {name: values - KELVIN_OFFSET for name, values in self.part_temperatures.items()}

    @property
    def equilibrium_time_s(self) -> float | None:
        """:attr:`equilibrium_time` [s], None if the run did not reach equilibrium."""
        return self.equilibrium_time

    def to_dataframe(self, kind: str = "sensors", form: str = "wide") -> "pd.DataFrame":
        """A series of the run as a pandas DataFrame, units in the column names.

        Parameters
        ----------
        kind : {"sensors", "parts", "screw_temperature", "screw_displacement", "positioning_error"}
            ``sensors``: every sensor's temperature [°C] (as declared, the ambient last) and D [µm];
            ``parts``: each part's capacity-weighted mean temperature [°C]; ``screw_temperature``
            [°C] and ``screw_displacement`` [µm] along the screw; ``positioning_error`` E(x, t) [µm]
            at the table positions.
        form : {"wide", "long"}
            ``wide``: one row per sample time, a column ``time [s]`` and one column per sensor
            (``<sensor> [degC]``, ``D [um]``), part (``screw [degC]``) or position (``E(x=12.5 mm) [um]``).
            ``long``: one row per value: ``time [s]``, ``sensor``, ``value``, ``unit`` for the
            sensors; ``time [s]``, ``part``, ``temperature [degC]`` for the parts; ``time [s]``,
            ``x [mm]`` and the quantity (``temperature [degC]``, ``displacement [um]``,
            ``positioning error [um]``) for a field along x.

        Returns
        -------
        pandas.DataFrame

        Raises
        ------
        feedtherm.errors.ArgumentError
            An unknown ``kind`` or ``form`` (a ``ValueError`` naming the argument).

        Examples
        --------
        >>> import feedtherm as ft
        >>> run = ft.simulate(ft.load("ballscrew_example"), condition="v10", duration=600.0)  # doctest: +SKIP
        >>> run.to_dataframe().iloc[-1]  # doctest: +SKIP
        """
        from .tables import to_dataframe

        return to_dataframe(self, kind, form)

    @property
    def elongation_um(self) -> np.ndarray:
        return self.elongation * 1e6

    @property
    def elongation_change_um(self) -> np.ndarray:
        """Change of D since the start of the run [µm]."""
        return (self.elongation - self.elongation[0]) * 1e6

    def summary_values(self, which: str = "final") -> dict[str, float]:
        """``final`` or ``steady`` values in °C and µm, keyed by sensor name, and D_um.

        Parameters
        ----------
        which : {"final", "steady"}
            The mean over the last full cycle, or the cycle-averaged steady state.

        Returns
        -------
        dict
            Sensor name -> temperature [°C], and ``"D_um"`` -> the elongation D [µm].
        """
        values = self.final if which == "final" else self.steady
        out = {name: value - KELVIN_OFFSET for name, value in values.items() if name != ELONGATION_PROBE}
        out["D_um"] = values[ELONGATION_PROBE] * 1e6
        return out
