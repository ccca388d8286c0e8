"""The paper is one bench: no module outside benches/paper names its sensors, conditions or tables.

What the paper's bench is (its sensors T1-T6, its conditions I-V, its Tables 1-7, its findings)
lives in its folder (description, overlay, measurements, report notes); validation, the report,
calibration, inference, compensation and uncertainty read it from the loaded bench.

One layer is exempt: ``physics/``. Each correlation there cites its source with the equation,
table and a worked number, as the project's rules require, and for the paper's own equations the
source is the paper ("Paper, Eq. 14 and Table 1").  A citation names where a formula comes from;
it decides nothing about which bench runs.
"""

import re
from pathlib import Path

from feedtherm.benches import bench
from feedtherm.system.load import load_system

SRC = Path(__file__).parents[1] / "src" / "feedtherm"
EXEMPT = (SRC / "benches" / "paper", SRC / "physics")


def _patterns() -> dict[str, re.Pattern]:
    paper = load_system("paper").system
    sensors = sorted({*paper.sensors, paper.room.ambient_sensor})
    conditions = sorted(paper.conditions)
    tables = sorted({int(p.name[len("table"):].split("_")[0]) for p in (bench("paper").folder / "tables").glob("*.csv")})
    return {
        "a sensor of the paper": re.compile(r"\b(" + "|".join(map(re.escape, sensors)) + r")\b"),
        "a condition of the paper": re.compile(
            r"""["'](""" + "|".join(map(re.escape, conditions)) + r""")["']"""  # as a literal
            + r"|\bconditions? (" + "|".join(map(re.escape, conditions)) + r")\b"  # in prose
            + r"|\b(" + "|".join(c for c in conditions if len(c) > 1) + r")\b"),  # II, III, IV: no word else
        "a table of the paper": re.compile(r"\bTables? (" + "|".join(map(str, tables)) + r")\b"),
    }


def test_no_module_outside_the_paper_bench_names_what_is_the_papers():
    patterns = _patterns()
    found = []
    for path in sorted(SRC.rglob("*.py")):
        if any(path.is_relative_to(folder) for folder in EXEMPT):
            continue
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1):
            for what, pattern in patterns.items():
                if pattern.search(line):
                    found.append(f"{path.relative_to(SRC)}:{number}: {what}: {line.strip()}")
    assert not found, "\n".join(found)


def test_the_patterns_find_what_they_look_for():
    patterns = _patterns()
    assert patterns["a sensor of the paper"].search('AMBIENT_SENSOR = "T6"')
    assert patterns["a condition of the paper"].search('sobol_condition: str = "I"')
    assert patterns["a condition of the paper"].search("the times at IV, II and V")
    assert patterns["a condition of the paper"].search("at condition I by 2.3 min")
    assert patterns["a table of the paper"].search("the paper's Tables 6 and 7")
    assert not patterns["a condition of the paper"].search("I think V is a variable")
