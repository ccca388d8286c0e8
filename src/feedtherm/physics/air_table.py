"""The table of dry air at one standard atmosphere that :func:`~feedtherm.physics.air.properties_air` reads.

The table holds CoolProp's values for the pseudo-pure fluid ``"Air"`` (Lemmon et al. 2000
equation of state, Lemmon & Jacobsen 2004 transport) at 101325 Pa, every kelvin from
:data:`T_FIRST` to :data:`T_LAST`.  Reading it takes milliseconds where importing CoolProp
takes seconds, and a linear interpolation between whole kelvins stays within a few parts
in 10⁶ of CoolProp (tests/unit/physics/test_air.py measures it).

Regenerate it after a CoolProp upgrade with::

    .venv/bin/python -m feedtherm.physics.air_table

A test regenerates a few rows and compares, so a CoolProp that disagrees with the table is
noticed.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

#: Where the table lives (package data).
TABLE_PATH = Path(__file__).with_name("data") / "air_1atm.csv"
#: First and last temperature of the table [K]; the description accepts −150…1000 °C.
T_FIRST, T_LAST = 110, 1400
#: The columns after the temperature, in the order of :func:`coolprop_row`.
COLUMNS = ("density_kg_m3", "specific_heat_J_kgK", "viscosity_Pa_s", "conductivity_W_mK")
P_TABLE = 101325.0  #: [Pa]


def coolprop_row(T: float, p: float = P_TABLE) -> tuple[float, float, float, float]:
    """Density [kg/m³], c_p [J/(kg·K)], μ [Pa·s] and k [W/(m·K)] of air from CoolProp.

    Examples
    --------
    Air at 300 K and one atmosphere; Incropera Table A.4 (its density at 1 bar, times 1.01325:
    1.1768 kg/m³; 1007 J/(kg·K), 184.6e-7 Pa·s, 26.3e-3 W/(m·K)) agrees within 0.5 %:

    >>> rho, cp, mu, k = coolprop_row(300.0)
    >>> round(rho, 4), round(cp, 1), round(mu * 1e7, 1), round(k * 1e3, 2)
    (1.177, 1006.4, 185.4, 26.38)
    """
    import CoolProp.CoolProp as CP  # seconds to import: only here, for the table and other pressures

    state = CP.AbstractState("HEOS", "Air")
    state.update(CP.PT_INPUTS, float(p), float(T))
    return float(state.rhomass()), float(state.cpmass()), float(state.viscosity()), float(state.conductivity())


def table_rows(temperatures) -> np.ndarray:
    """Rows ``(T, ρ, c_p, μ, k)`` of the table at ``temperatures`` [K], from CoolProp.

    Examples
    --------
    >>> table_rows([300.0]).shape
    (1, 5)
    """
    return np.array([(T, *coolprop_row(T)) for T in temperatures])


def _write_table(path: Path = TABLE_PATH) -> Path:
    """Write the table (10 significant digits) with a header naming its source."""
    import CoolProp

    rows = table_rows(np.arange(T_FIRST, T_LAST + 1, dtype=float))
    header = (f"Dry air at {P_TABLE:.0f} Pa from CoolProp {CoolProp.__version__} (HEOS 'Air': Lemmon et al. 2000 EOS, "
              "Lemmon & Jacobsen 2004 transport); regenerate: python -m feedtherm.physics.air_table\n"
              + ",".join(("T_K", *COLUMNS)))
    path.parent.mkdir(parents=True, exist_ok=True)
    np.savetxt(path, rows, fmt="%.10g", delimiter=",", header=header)
    return path


def read_table(path: Path = TABLE_PATH) -> np.ndarray:
    """The table as an array of rows ``(T, ρ, c_p, μ, k)``.

    Examples
    --------
    >>> table = read_table()
    >>> float(table[0, 0]), float(table[-1, 0]), table.shape
    (110.0, 1400.0, (1291, 5))
    """
    return np.loadtxt(path, delimiter=",", comments="#")


if __name__ == "__main__":
    print(_write_table())
