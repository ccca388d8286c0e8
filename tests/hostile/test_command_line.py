"""Command-line values that would make a run allocate more than it may: refused in one line, before any
model is built or any array allocated, with the largest sample count and the smallest interval allowed.

The bound is memory: a run's samples and step records, every value 8 bytes held three times at the
peak, against :data:`feedtherm.plan.RECORD_MEMORY_BYTES`.
"""

from __future__ import annotations

import re

import pytest

from feedtherm import plan as planning
from feedtherm.errors import FeedthermError
from feedtherm.plan import plan_run, record_plan


@pytest.fixture
def nothing_allocated(monkeypatch):
    """Fails the test where a run gets as far as its sample times or its model."""

    def allocated(*args, **kwargs):
        raise AssertionError("the run got past planning: sample times or a model were made")

    import feedtherm.simulate

    monkeypatch.setattr(feedtherm.simulate, "sample_times", allocated)
    monkeypatch.setattr(feedtherm.simulate, "execute", allocated)


def smallest_interval(line: str) -> float:
    return float(re.search(r"give --sample-interval ([0-9.e+-]+) or more", line).group(1))


def test_a_sample_interval_of_a_microsecond_is_refused_before_allocating(refused, nothing_allocated):
    # 10,800,000,002 samples over condition I's 3 h: the audit's MemoryError (80.5 GiB of sample times alone)
    line = refused("run", "paper", "--condition", "I", "--sample-interval", "1e-6", "--out", "out",
                   says=("--sample-interval: 1e-06 s", "10,800,000,002 samples", "against the 1 GB",
                         "samples at most", "give --sample-interval"))
    assert 0.01 < smallest_interval(line) < 1.0


def test_the_smallest_interval_named_is_accepted_and_a_smaller_one_refused(refused, paper):
    line = refused("run", "paper", "--condition", "I", "--sample-interval", "0.01", "--out", "out")
    smallest = smallest_interval(line)
    most = int(re.search(r"([0-9,]+) samples at most", line).group(1).replace(",", ""))
    plan = plan_run(paper, condition="I", sample_interval=smallest)  # no refusal
    assert record_plan(paper, plan.segments, smallest, plan.options).samples <= most
    with pytest.raises(FeedthermError, match="--sample-interval"):
        plan_run(paper, condition="I", sample_interval=smallest * 0.8)


def test_a_long_duration_at_the_default_interval_is_refused_for_its_samples(refused, nothing_allocated):
    # 4e6 s (46 days) in 10 s steps is within the step limit, but its 400,000 samples are not within the memory
    refused("run", "paper", "--condition", "I", "--motion", "averaged", "--duration", "4e6", "--out", "out",
            says=("--sample-interval: 10 s over the run's 4e+06 s", "400,002 samples", "or a shorter --duration"))


def test_validate_and_every_other_planned_run_keep_the_bound(paper):
    # the bound lives in plan_run, which every command's runs go through
    with pytest.raises(FeedthermError, match="samples at most"):
        plan_run(paper, condition="II", sample_interval=1e-3)


def test_the_bound_is_the_memory_budget(paper, monkeypatch):
    plan = plan_run(paper, condition="I")
    records = record_plan(paper, plan.segments, 10.0, plan.options)
    # 0 to 10,800 s every 10 s and the end; each sample's values counted from the description
    assert records.samples == 1082 and records.values_per_sample == 277
    assert records.bytes == 3 * 8 * (records.samples * records.values_per_sample
                                     + records.steps * records.values_per_step)
    most = records.most_samples()
    monkeypatch.setattr(planning, "RECORD_MEMORY_BYTES", 2 * planning.RECORD_MEMORY_BYTES)
    assert records.most_samples() == pytest.approx(2 * most, abs=records.steps * records.values_per_step
                                                   / records.values_per_sample + 1)


def test_the_default_runs_of_the_benches_fit(paper, ballscrew):
    # a fifth of the budget at most (ballscrew_example's 8 h at 20 m/min: 480,001 steps, 124 MB)
    for loaded in (paper, ballscrew):
        for name in loaded.system.conditions:
            plan = plan_run(loaded, condition=name)
            assert record_plan(loaded, plan.segments, 10.0, plan.options).bytes < planning.RECORD_MEMORY_BYTES / 5


def test_the_step_limit_leaves_room_for_samples(paper):
    # the most steps a run may plan (MAX_STEPS, a wall-time bound) hold a ninth of the budget at most
    plan = plan_run(paper, condition="I")
    records = record_plan(paper, plan.segments, 10.0, plan.options)
    steps = 3 * 8 * planning.MAX_STEPS * records.values_per_step
    assert steps < planning.RECORD_MEMORY_BYTES / 9
