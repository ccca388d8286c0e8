"""Data shipped with feedtherm: the paper's Tables 1-7 (see data/paper/SOURCE.md)."""

from __future__ import annotations

import csv
from importlib import resources

PAPER_TABLES = {
    1: "table1_heat_condition_I.csv",
    2: "table2_chtc_condition_I.csv",
    3: "table3_tcr.csv",
    4: "table4_materials.csv",
    5: "table5_operating_conditions.csv",
    6: "table6_temperatures.csv",
    7: "table7_elongation.csv",
}


def paper_table(number: int) -> list[dict[str, str]]:
    """Rows of the paper's Table ``number`` (1-7) as dicts of strings, as printed."""
    name = PAPER_TABLES[number]
    text = resources.files("feedtherm.data").joinpath("paper").joinpath(name).read_text(encoding="utf-8")
    return list(csv.DictReader(text.splitlines()))
