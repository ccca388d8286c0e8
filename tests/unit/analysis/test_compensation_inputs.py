"""The inputs of compensation studies: random cycles, machine variants, candidate sensors (issue 16)."""

import math
import re

import numpy as np
import pytest

from feedtherm.analysis.candidates import candidate_sensors, with_candidates
from feedtherm.analysis.machine_variants import DEFAULT_SPREAD, draw_variant
from feedtherm.analysis.random_cycles import CycleRanges, SpeedEnvelope, cycle_seed, random_cycle
from feedtherm.errors import FeedthermError
from feedtherm.system.geometry import contains
from feedtherm.system.load import load_system

RPM = 60 / (2 * math.pi)


@pytest.fixture(scope="module")
def paper():
    return load_system("paper")


def _rows(cycle):
    return [(s.start, s.screw_speed, s.nut_speed, s.ambient) for s in cycle.segments]


def test_a_seed_gives_the_same_cycle_and_another_index_another(paper):
    a = random_cycle(paper.system, cycle_seed(7, 0, 3))
    b = random_cycle(paper.system, cycle_seed(7, 0, 3))
    c = random_cycle(paper.system, cycle_seed(7, 0, 4))
    d = random_cycle(paper.system, cycle_seed(7, 1, 3))
    assert _rows(a) == _rows(b)
    assert _rows(a) != _rows(c) and _rows(a) != _rows(d)


def test_cycles_stay_in_the_declared_ranges(paper):
    ranges = CycleRanges()
    envelope = SpeedEnvelope.of(paper.system)
    assert envelope.screw == pytest.approx((396, 2214)) and envelope.relative == pytest.approx((36, 54))
    stops = 0.0
    for index in range(20):
        cycle = random_cycle(paper.system, cycle_seed(1, 0, index), ranges)
        assert cycle.duration == ranges.duration
        ends = [s.start for s in cycle.segments[1:]] + [cycle.duration]
        for segment, end in zip(cycle.segments, ends):
            screw, relative = segment.screw_speed * RPM, (segment.screw_speed - segment.nut_speed) * RPM
            if screw == 0:
                assert segment.nut_speed == 0
                stops += end - segment.start
            else:
                assert envelope.screw[0] - 1e-9 <= screw <= envelope.screw[1] + 1e-9
                assert envelope.relative[0] - 1e-9 <= relative <= envelope.relative[1] + 1e-9
            ambient_c = segment.ambient - 273.15
            assert ranges.ambient_mean[0] - ranges.ambient_amplitude[1] - 1e-9 <= ambient_c
            assert ambient_c <= ranges.ambient_mean[1] + ranges.ambient_amplitude[1] + 1e-9
        steps = np.diff([s.start for s in cycle.segments])
        assert steps.max() <= ranges.ambient_step + 1e-9  # the ambient is updated every step
    assert stops > 0.1 * 20 * ranges.duration  # standstills and dwells occur


@pytest.mark.parametrize("seed", [1.5, "3", None, True])
def test_a_seed_must_be_an_integer(seed):
    with pytest.raises(FeedthermError, match="not an integer"):
        cycle_seed(seed, 0, 0)


def test_a_machine_variant_scales_every_heat_and_chtc_within_its_spread(paper):
    a = draw_variant(paper, np.random.default_rng(3))
    b = draw_variant(paper, np.random.default_rng(3))
    assert a == b
    assert set(a.heat) == set(paper.system.sources) and set(a.chtc) == set(paper.system.surfaces)
    factors = np.array([*a.heat.values(), *a.chtc.values()])
    assert np.all(np.abs(factors - 1) <= DEFAULT_SPREAD) and factors.std() > 0.05
    variant = a.apply(paper)
    assert variant.system.sources["front_bearing"].heat_factor == a.heat["front_bearing"]
    # the declared "chtc_moving" scale on the moving group's CHTCs, times the variant's own factor
    assert variant.system.surfaces["worktable"].chtc_factor == pytest.approx(
        a.declared["chtc_moving"] * a.chtc["worktable"], rel=1e-12)
    assert variant.system.surfaces["guideways"].chtc_factor == pytest.approx(
        a.declared["chtc_fixed"] * a.chtc["guideways"], rel=1e-12)
    assert variant.sha256 != paper.sha256


def test_a_machine_variant_draws_every_declared_uncertainty_within_its_range(paper):
    from feedtherm.analysis.uncertainty.declared import resolve_uncertainties

    declared = {p.name: p for p in resolve_uncertainties(paper)}
    assert {"screw_expansion", "loop_expansion", "screw_nut_preload", "tcr_bolted"} <= set(declared)
    draws = [draw_variant(paper, np.random.default_rng(seed)) for seed in range(40)]
    for name, parameter in declared.items():
        values = np.array([d.declared[name] for d in draws])
        assert np.all((parameter.low <= values) & (values <= parameter.high)), name
        assert values.std() > 0.0, name
    variant = draws[0].apply(paper)
    assert variant.system.materials["gcr15"].expansion == draws[0].declared["screw_expansion"]
    assert variant.system.materials["q345b"].expansion == draws[0].declared["loop_expansion"]
    assert variant.system.sources["screw_nut"].preload == draws[0].declared["screw_nut_preload"]
    # a bolted joint's resistance: the declared scale times its nominal value
    assert variant.system.joints[9].tcr == pytest.approx(draws[0].declared["tcr_bolted"] * paper.system.joints[9].tcr)


def test_the_heat_and_chtc_factors_of_a_seed_do_not_depend_on_the_declared_draws(paper):
    full = draw_variant(paper, np.random.default_rng(5))
    alone = draw_variant(paper, np.random.default_rng(5), declared=False)
    assert alone.declared == {} and full.declared
    assert (full.heat, full.chtc) == (alone.heat, alone.chtc)


def test_each_out_of_range_case_changes_one_thing_of_its_cycle(paper):
    from feedtherm.analysis.compensation.data import OUT_OF_RANGE, out_of_range_cycle

    assert OUT_OF_RANGE == ("ambient_ramp", "ambient_step", "fast", "warm_start")
    cycle = random_cycle(paper.system, cycle_seed(0, 3, 0))
    first = cycle.segments[0].ambient
    ramp = out_of_range_cycle("ambient_ramp", cycle)
    # 8 K over the 8 h cycle: a segment starting at t has first + 8 * t / 28800
    assert [s.ambient for s in ramp.segments] == pytest.approx([first + 8.0 * s.start / 28800.0 for s in ramp.segments])
    assert [(s.screw_speed, s.nut_speed) for s in ramp.segments] == [(s.screw_speed, s.nut_speed) for s in cycle.segments]
    step = out_of_range_cycle("ambient_step", cycle)
    assert 7200.0 in [s.start for s in step.segments]
    assert all(s.ambient == pytest.approx(first + (5.0 if s.start >= 7200.0 else 0.0)) for s in step.segments)
    fast = out_of_range_cycle("fast", cycle)
    assert [s.screw_speed for s in fast.segments] == pytest.approx([1.5 * s.screw_speed for s in cycle.segments])
    assert max(abs(s.screw_speed) for s in fast.segments) > SpeedEnvelope.of(paper.system).screw[1] / RPM
    assert _rows(out_of_range_cycle("warm_start", cycle)) == _rows(cycle)  # the machine starts warm, not the cycle


def test_candidates_are_named_exposed_points_of_the_parts(paper):
    candidates = candidate_sensors(paper.system)
    assert list(candidates)[:6] == ["T1", "T2", "T3", "T4", "T5", "T6"]
    for name, candidate in candidates.items():
        assert re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", name), name
        if candidate.where not in ("ambient", "declared"):
            assert contains(paper.system.parts[candidate.part], candidate.position, tol=0.0)
    assert {c.part for c in candidates.values()} >= {"screw", "front_housing", "rear_housing", "worktable", "nut"}
    # the rails cover the risers' tops, the bearings the screw where they sit
    assert not any(name.startswith("base_b1_top") for name in candidates)
    assert "screw_top_x0" not in candidates and "screw_top_x400" not in candidates
    assert "screw_top_x200" in candidates
    with_them = with_candidates(paper, candidates)
    assert set(with_them.system.sensors) == set(candidates) - {"T6"}  # the ambient is no point of a part
