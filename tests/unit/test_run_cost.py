"""What `check` says a run will cost: the integrator's steps by motion, each model's predicted size,
the wall time it would take, and when the cycle-averaged motion is advised."""

from dataclasses import replace

import pytest

from feedtherm.plan import AVERAGED_MOTION_MAX_CYCLE_S, model_sizes, plan_run, run_cost
from feedtherm.plan.cost import (FEM_NODES_PER_VOLUME, ModelSize, RunWork, fem_nodes, run_work, seconds_per_step,
                                 wall_time)
from feedtherm.simulate import simulate
from feedtherm.system.load import load_system

#: Nodes of the benches' actual meshes: ``mesh_system(load_system(bench).system, density).points.shape[1]``
#: with an empty FEEDTHERM_CACHE (gmsh 4.15.2, 2026-11-29).
MEASURED_NODES = {
    ("paper", "coarse"): 13_069, ("paper", "medium"): 44_443, ("paper", "fine"): 171_510,
    ("ballscrew_example", "coarse"): 15_605, ("ballscrew_example", "medium"): 53_346,
    ("ballscrew_example", "fine"): 219_250,
}


@pytest.fixture(scope="module")
def paper():
    return load_system("paper")


@pytest.fixture(scope="module")
def ballscrew():
    return load_system("ballscrew_example")


@pytest.mark.parametrize("bench, density", sorted(MEASURED_NODES))
def test_the_predicted_fe_nodes_are_within_a_quarter_of_the_benches_meshes(bench, density):
    predicted = fem_nodes(load_system(bench).system, density)
    assert predicted == pytest.approx(MEASURED_NODES[(bench, density)], rel=0.25)


def test_the_node_prediction_follows_the_element_size(paper):
    """Halving every target size multiplies a part's volume term by 8: the finer densities predict more."""
    nodes = [fem_nodes(paper.system, density) for density in ("coarse", "medium", "fine")]
    assert nodes[0] < nodes[1] < nodes[2]
    assert FEM_NODES_PER_VOLUME > 0.0


def test_the_fast_models_size_is_its_layouts(paper, ballscrew):
    assert model_sizes(paper.system)[("fast", None)].unknowns == 1474
    assert model_sizes(ballscrew.system)[("fast", None)].unknowns == 1752


@pytest.mark.parametrize("model, mesh", [("fast", None), ("fem", "coarse"), ("reduced", "coarse")])
def test_the_time_grows_with_the_unknowns_and_the_steps(model, mesh):
    size = ModelSize(model, mesh, 15_000, 41, 50_000.0, True)
    work = RunWork(5_000, 30, 4, False)
    base = wall_time(size, work)
    assert wall_time(replace(size, unknowns=30_000), work) > base
    assert wall_time(size, replace(work, steps=10_000)) > base
    assert seconds_per_step(replace(size, unknowns=30_000)) >= seconds_per_step(size)
    if model == "fem":
        assert wall_time(size, replace(work, factorisations=60)) > base
        assert wall_time(replace(size, contact_points=100_000.0), work) > base
        assert wall_time(replace(size, mesh_cached=False), work) > base  # the run meshes first


def test_steps_and_times_of_the_paper_benchs_condition_I(paper):
    cost = run_cost(plan_run(paper, condition="I"))
    # 10,800 s: resolved, 2 of the 40 grid cells of the 200 mm stroke a step at 6 mm/s, 1.667 s each
    # (docs/fem-model.md: 6,480 steps of 1.67 s); averaged, 10 s steps: 1,080
    assert cost.steps == {"resolved": 6480, "exact": 6480, "averaged": 1080}
    # the FE and reduced models' windows: 10 cells of 5 mm a step (the table passes 60 mm in 10 s, and
    # 10 is the largest divisor of 40 up to 12), 8.333 s each: 1,296 steps, a factorisation per window
    assert cost.window_steps == 1296
    assert run_work(plan_run(paper, condition="I"), "resolved", 41, windowed=True).factorisations == 4
    assert cost.seconds[("fem", "fine")]["resolved"] < cost.seconds[("fem", "fine")]["exact"]
    # the cycle: 2 x 200 mm / 6 mm/s = 66.7 s, over 30 s
    assert cost.cycle_s == pytest.approx(66.67, abs=0.01)
    assert not cost.suggest_averaged
    # the exact motion (the fast model's resolved one) visits every other of the 41 positions: 21 factorisations
    assert run_work(plan_run(paper, condition="I"), "resolved", 41).factorisations == 21
    times = cost.seconds
    assert times[("fem", "coarse")]["resolved"] < times[("fem", "medium")]["resolved"] < times[("fem", "fine")]["resolved"]
    assert times[("fast", None)]["averaged"] < times[("fast", None)]["resolved"]


def test_the_estimates_hold_against_runs_measured_alone():
    """Whole `feedtherm run` processes, CPU time with OpenBLAS and MKL on one thread, the FE meshes cached
    (the runs feedtherm.plan.cost's constants were checked on, 2026-11-29, benchmarks/README.md, *check's
    time estimates*): the estimate within a third.  The FE runs were made before the windowed motion,
    position by position: the exact motion's estimate is theirs."""
    measured = [
        ("paper", dict(condition="I"), ("fast", None), "resolved", 7.5),
        ("paper", dict(condition="I"), ("fem", "coarse"), "exact", 67.5),
        ("paper", dict(condition="I", duration=600.0), ("fem", "medium"), "exact", 77.7),
        ("ballscrew_example", dict(condition="v10", duration=180.0), ("fem", "coarse"), "exact", 57.9),
        ("ballscrew_example", dict(condition="v10", duration=3600.0), ("fast", None), "averaged", 6.0),
    ]
    for bench, run, key, motion, seconds in measured:
        loaded = load_system(bench)
        sizes = {k: replace(size, mesh_cached=True) for k, size in model_sizes(loaded.system).items()}
        estimate = run_cost(plan_run(loaded, **run), sizes).seconds[key][motion]
        assert estimate == pytest.approx(seconds, rel=1 / 3), (bench, run, key, motion)


def test_a_fast_table_is_advised_the_averaged_motion(ballscrew):
    cost = run_cost(plan_run(ballscrew, condition="v20"))
    # 2000 rpm x 10 mm = 20 m/min; 2 x 0.4 m / (1/3 m/s) = 2.4 s
    assert cost.cycle_s == pytest.approx(2.4)
    assert cost.cycle_s <= AVERAGED_MOTION_MAX_CYCLE_S and cost.suggest_averaged
    # resolved: 58 grid cells over the 400 mm stroke, 58 // 20 = 2 cells a step of 0.04138 s, over 28,800 s
    assert cost.steps["resolved"] == pytest.approx(28800 / (2 * 0.4 / 58 * 3), abs=2)


def test_the_planned_steps_are_the_integrators(ballscrew):
    plan = plan_run(ballscrew, condition="v10", duration=30.0)
    run = simulate(ballscrew, condition="v10", duration=30.0)
    assert run_cost(plan).steps["resolved"] == run.info["steps"]
