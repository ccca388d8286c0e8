"""Fixtures shared by the test layers."""

import os

import pytest

from feedtherm.system.load import LoadedSystem, load_system, parse_toml, read_text, validate_data

#: The paper bench's loss models before the catalogue ones replaced them (issue 12): the paper's
#: Eq. 14 (an efficiency) for the motors, Palmgren (Eqs. 15-22, corrected) for the bearings on a
#: fixed 100 mm²/s oil, a 500 N thread preload, coefficients frozen (the paper's assumption 3).
PAPER_EQUATION_MODELS = {
    "screw_motor": {"efficiency": 0.85},
    "nut_motor": {"efficiency": 0.85},
    "front_bearing": {"mean_diameter": "43.5 mm", "f0": 4.0, "lubricant_viscosity": "100 mm^2/s"},
    "rear_bearing": {"mean_diameter": "38.5 mm", "f0": 1.5, "lubricant_viscosity": "100 mm^2/s"},
    "nut_bearing": {"mean_diameter": "65 mm", "f0": 4.0, "lubricant_viscosity": "100 mm^2/s"},
    "screw_nut": {"preload": "500 N"},
}
# The paper's equations load the motors by a 500 N thread preload (1.75 N m at I, docs/paper-audit.md
# §5), more than the declared servos' continuous torque: the variant's motors are the paper's unnamed ones.
_REPLACED = ("losses", "friction_model", "bore_diameter", "outer_diameter", "series", "bearings_in_set", "lubricant",
             "continuous_torque")


#: The modules whose tests start Dask clusters (a local one of two worker processes, or a scheduler
#: and two workers): under pytest-xdist they run one after another on one worker, never two
#: clusters at once on this project's two cores.  A new module that starts a cluster goes here.
DASK_CLUSTER_MODULES = frozenset(f"tests/{m}.py" for m in (
    "integration/test_calibration", "integration/test_cli_calibrate_parallel", "integration/test_cli_compensate",
    "integration/test_cli_sweep_parallel", "integration/test_cli_sweep_resume",
    "integration/test_sweep_on_a_cluster", "integration/test_uncertainty_study",
    "integration/test_uncertainty_update", "unit/analysis/test_execution"))


#: The variables that set the thread count of OpenBLAS, MKL (PARDISO) and OpenMP in a child process.
THREAD_VARIABLES = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")


def pytest_configure(config):
    """Under pytest-xdist (``make test`` runs ``-n 2``) each worker process gets a cache of its own,
    ``$FEEDTHERM_CACHE/xdist-gwN``: two workers never write the same mesh, basis or pint file, and
    the commands the tests start in child processes inherit it; and each runs its numerical
    libraries on one thread.  A serial run keeps the user's cache and threads."""
    worker = os.environ.get("PYTEST_XDIST_WORKER")
    if worker:
        from threadpoolctl import threadpool_limits

        from feedtherm.constants import cache_root

        os.environ["FEEDTHERM_CACHE"] = str(cache_root() / f"xdist-{worker}")
        # One BLAS/LAPACK/PARDISO thread per worker (and in the commands it starts): two workers on
        # two cores, each with threads of its own that wait busily between calls, slowed the
        # heaviest tests twofold against the same test alone.
        for variable in THREAD_VARIABLES:
            os.environ[variable] = "1"
        threadpool_limits(1)


def _work_unit(nodeid: str) -> str:
    module = nodeid.split("::", 1)[0]
    return "dask_cluster" if module in DASK_CLUSTER_MODULES else module


def _rank(unit: str) -> int:
    """The longest units first, the many short unit tests last to fill the workers' ends: the Dask
    modules, then the FE verification cases and the validation, then the rest of the integration tests
    and the documentation site's (tests/docs: it builds the site)."""
    if unit == "dask_cluster":
        return 0
    if unit.startswith(("tests/verification/", "tests/validation/")):
        return 1
    return 2 if unit.startswith(("tests/integration/", "tests/docs/")) else 3


@pytest.hookimpl(optionalhook=True, tryfirst=True)  # before pytest-xdist's own
def pytest_xdist_make_scheduler(config, log):
    """pytest-xdist's work units (``make test``): each module whole on one worker (its module-scoped
    fixtures made once, its tests in their order), the :data:`DASK_CLUSTER_MODULES` together as one
    unit, handed out longest first (:func:`_rank`)."""
    from xdist.scheduler import LoadScopeScheduling

    class ModuleScheduling(LoadScopeScheduling):
        def _split_scope(self, nodeid: str) -> str:
            return _work_unit(nodeid)

        def _assign_work_unit(self, node) -> None:
            if not getattr(self, "_ranked", False):
                order = sorted(self.workqueue, key=_rank)  # stable: collection order within a rank
                for unit in order:
                    self.workqueue.move_to_end(unit)
                self._ranked = True
            super()._assign_work_unit(node)

    return ModuleScheduling(config, log)


def paper_with_equation_models() -> LoadedSystem:
    """The paper bench with :data:`PAPER_EQUATION_MODELS`: what hand calculations written for the
    paper's own equations are checked against."""
    text, origin = read_text("paper")
    data = parse_toml(text, origin)
    for name, values in PAPER_EQUATION_MODELS.items():
        source = data["sources"][name]
        for key in _REPLACED:
            source.pop(key, None)
        if source["model"] == "bearing":
            source.pop("friction_coefficient", None)  # a constant-friction bearing's; the thread keeps its own
        source.update(values)
    data["temperatures"]["coupling"] = "frozen"
    data["calibration"]["parameters"].pop("motor_copper")
    data["calibration"]["parameters"].pop("motor_no_load")
    data.get("uncertainty", {}).get("parameters", {}).pop("motor_copper", None)  # on the datasheet losses
    data["calibration"]["parameters"]["motor_efficiency"] = {
        "kind": "value", "paths": ["sources.screw_motor.efficiency", "sources.nut_motor.efficiency"],
        "bounds": [0.5, 0.98], "description": "efficiency of both servo motors at their operating point"}
    return validate_data(data, "bundled:paper (the paper's equation loss models)")


@pytest.fixture(scope="module", autouse=True)
def models_built_in_this_module():
    """The models the registry keeps (models/registry.py, ``build_options``) are the ones this module
    built: a module's runs of one description share an FE model, as a command's do, and no module
    gets one that another module, run before it on the same worker, left behind."""
    from feedtherm.models.registry import forget_built_models

    forget_built_models()
    yield
    forget_built_models()


@pytest.fixture(scope="session")
def paper():
    """The paper's bench, loaded once for the whole session (descriptions are frozen)."""
    return load_system("paper")


#: Run length [s] of :func:`paper_short`'s conditions.
SHORT_RUN_S = 1800.0


@pytest.fixture(scope="session")
def paper_short(paper):
    """The paper's bench with every condition run for half an hour instead of three.

    For tests that compare two executions of one study (serial against a Dask cluster): what
    they compare, every number to the last digit, does not depend on how long each run lasts,
    and the runs take a sixth of the time.
    """
    from feedtherm.system.variants import with_values

    return with_values(paper, {f"conditions.{name}.duration": SHORT_RUN_S for name in paper.system.conditions},
                       origin_suffix="half-hour runs")


@pytest.fixture(scope="session")
def paper_equations():
    """The paper's bench with the paper's own loss models (:func:`paper_with_equation_models`)."""
    return paper_with_equation_models()


@pytest.fixture(scope="session")
def ballscrew():
    """The bundled single-drive ball-screw axis."""
    return load_system("ballscrew_example")


@pytest.fixture
def surface_evaluations(monkeypatch):
    """The names of the surfaces whose transfer the boundary conditions compute, in order, from now on
    (``feedtherm.boundary.surface_transfer`` wrapped to record them)."""
    from feedtherm import boundary

    computed = []
    surface_transfer = boundary.surface_transfer

    def counted(*args, **kwargs):
        computed.append(args[1])
        return surface_transfer(*args, **kwargs)

    monkeypatch.setattr(boundary, "surface_transfer", counted)
    return computed
