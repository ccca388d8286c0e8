"""Property-based fuzzing of descriptions: the contract every command relies on.

Each example takes a bundled bench and mutates it: a value replaced (NaN, ±inf, 0, negative,
huge, tiny, a wrong unit, a wrong type), a key dropped, duplicated or misspelt, a reference
left dangling.  The contract: either the description is refused with one line (a
``FeedthermError``: schema, checks, heats, step count), or a short run of the fast model
completes with finite, healthy results (``execute`` checks them: finite, above absolute zero,
energy balance within 1e-4).  Any other exception is a defect.

The suite runs a fixed-seed budget (``FEEDTHERM_FUZZ_EXAMPLES``, default 40); ``make fuzz``
runs 2,000.
"""

from __future__ import annotations

import copy
import math
import os
import tomllib

import numpy as np
import pytest
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

from feedtherm.benches import bench
from feedtherm.errors import FeedthermError
from feedtherm.plan import plan_run
from feedtherm.simulate import execute
from feedtherm.system.load import validate_description

EXAMPLES = int(os.environ.get("FEEDTHERM_FUZZ_EXAMPLES", "40"))
BENCHES = {name: tomllib.loads(bench(name).description.read_text(encoding="utf-8"))
           for name in ("paper", "ballscrew_example")}


def _paths(data, prefix=()):
    """Every path into the parsed TOML: (keys..., ) for each dict entry and list item."""
    out = []
    items = data.items() if isinstance(data, dict) else enumerate(data) if isinstance(data, list) else ()
    for key, value in items:
        path = (*prefix, key)
        out.append(path)
        out.extend(_paths(value, path))
    return out


PATHS = {name: [p for p in _paths(data) if p[0] not in ("provenance", "meta")] for name, data in BENCHES.items()}

ODD_VALUES = [math.nan, math.inf, -math.inf, 0, 0.0, -1, -1.0, 1e300, 1e-300, True, "", "abc", [], {},
              "nan mm", "inf W", "1e400 mm", "3 kg", "20 K", "-300 degC", "1e30 rpm", "0 mm", "-5 mm",
              "ghost", ["ghost", "ghost"], {"ghost": 1.0}]


def _scaled(value, factor):
    """A quantity string or number with its number multiplied by ``factor``."""
    if isinstance(value, bool):
        return not value
    if isinstance(value, (int, float)):
        return value * factor
    if isinstance(value, str):
        number, _, unit = value.partition(" ")
        try:
            return f"{float(number) * factor!r} {unit}".strip()
        except ValueError:
            return value + "x"
    return value


@st.composite
def mutated(draw):
    name = draw(st.sampled_from(sorted(BENCHES)))
    data = copy.deepcopy(BENCHES[name])
    path = draw(st.sampled_from(PATHS[name]))
    parent = data
    for key in path[:-1]:
        parent = parent[key]
    key = path[-1]
    kind = draw(st.sampled_from(["odd", "scale", "drop", "duplicate", "rename"]))
    if kind == "odd":
        parent[key] = draw(st.sampled_from(ODD_VALUES))
    elif kind == "scale":
        parent[key] = _scaled(parent[key], draw(st.sampled_from([0.0, -1.0, 1e-9, 1e-3, 1e3, 1e9, math.nan])))
    elif kind == "drop":
        del parent[key]
    elif kind == "duplicate":
        if isinstance(parent, list):
            parent.append(copy.deepcopy(parent[key]))
        else:
            parent[f"{key}_copy"] = copy.deepcopy(parent[key])
    elif isinstance(parent, dict):
        parent[f"{key}x"] = parent.pop(key)
    else:
        parent[key] = "ghost"
    return name, f"{kind} {'.'.join(map(str, path))}", data


def _one_line(exc: BaseException) -> None:
    message = str(exc)
    assert message and "\n" not in message, repr(message)


@settings(max_examples=EXAMPLES, derandomize=True, deadline=None, database=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(mutated())
def test_a_mutated_description_is_refused_in_one_line_or_runs_healthy(example):
    name, mutation, data = example
    try:
        loaded = validate_description(data, f"{name} ({mutation})")
    except FeedthermError as exc:
        _one_line(exc)
        event("refused by the description's validation")
        return
    condition = next(iter(loaded.system.conditions))
    try:
        solution = execute(plan_run(loaded, condition=condition, duration=600.0))
    except FeedthermError as exc:
        _one_line(exc)
        event(f"refused by the run: {type(exc).__name__}")
        return
    event("ran healthy")
    for values in (*solution.sensors.values(), solution.elongation):
        assert np.all(np.isfinite(values)), mutation
    assert abs(solution.energy.relative_error) <= 1e-4, mutation


@pytest.mark.parametrize("name", sorted(BENCHES))
def test_the_unmutated_benches_run(name):
    """The fuzzer's starting points pass the contract's healthy branch."""
    loaded = validate_description(copy.deepcopy(BENCHES[name]), name)
    solution = execute(plan_run(loaded, condition=next(iter(loaded.system.conditions)), duration=600.0))
    assert abs(solution.energy.relative_error) <= 1e-4
