# Quick start (see README): `make validate` sets up and runs the main job,
# `make test` sets up and runs the whole test suite.  Both create .venv on first use.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed

.PHONY: setup setup-test validate uncertainty test docs bench fuzz clean

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install --quiet --upgrade pip
	$(BIN)/pip install --quiet -e ".[test,docs]"
	touch $(STAMP)

setup: $(STAMP)

# The calibration the report's headline judges on held-out conditions (README, docs/calibration.md).
CAL_PARAMS := screw_nut_preload,front_bearing_preload,foundation,chtc_screw
CAL_DIR    := out/paper_calibration_physics

validate: $(STAMP)
	$(BIN)/feedtherm calibrate paper --fit I,II,IV --params $(CAL_PARAMS) --cross-validate --out $(CAL_DIR)
	$(BIN)/feedtherm validate paper --mode physics --calibration $(CAL_DIR)

# The prediction bands (docs/uncertainty.md): the declared priors, updated with the measured
# finals of I, II, IV, and the predictive bands; then the report with them (and with the
# calibration of `make validate` where it has run).  25 minutes on 2 cores (2026-11-26).
UNC_DIR := out/paper_uncertainty
WORKERS ?= 2

uncertainty: $(STAMP)
	$(BIN)/feedtherm uncertainty paper --update-with I,II,IV --workers $(WORKERS) --out $(UNC_DIR)
	$(BIN)/feedtherm validate paper --mode physics --uncertainty $(UNC_DIR) \
		$(if $(wildcard $(CAL_DIR)/calibration.json),--calibration $(CAL_DIR))

# The report test renders report.html in headless Chromium (Debian package `chromium`); the
# FE tests need the X/GL libraries that gmsh's wheel links against (Debian packages), and the
# FE model's check against CalculiX needs its solver (Debian package `calculix-ccx`); the exported
# laws' LinuxCNC component is built and run by LinuxCNC's own tools (Debian packages
# `linuxcnc-uspace`, `linuxcnc-uspace-dev`; without them its tests are skipped, the C's still run).
GMSH_LIBS := libglu1-mesa libgl1 libopengl0 libxrender1 libxcursor1 libxfixes3 libxext6 libxft2 libxinerama1 libx11-6

setup-test: $(STAMP)
	command -v chromium >/dev/null || (apt-get update -qq && apt-get install -y -qq chromium >/dev/null)
	$(BIN)/python -c "import gmsh" 2>/dev/null || (apt-get update -qq && apt-get install -y -qq $(GMSH_LIBS) >/dev/null)
	command -v ccx >/dev/null || (apt-get update -qq && apt-get install -y -qq calculix-ccx >/dev/null)
	command -v halcompile >/dev/null || (apt-get update -qq && apt-get install -y -qq --no-install-recommends \
		linuxcnc-uspace linuxcnc-uspace-dev >/dev/null) || echo "LinuxCNC could not be installed: its tests are skipped"

# The suite on TEST_WORKERS pytest-xdist processes (2: this project's machines have two cores), each
# module whole on one of them and the modules that start Dask clusters one after another
# (tests/conftest.py); TEST_WORKERS=0 runs it in this process.  benchmarks/README.md, *Test suite time*.
TEST_WORKERS ?= 2

# The package is compiled first: where PYTHONDONTWRITEBYTECODE is set (as on this project's
# machines), the commands the tests start (about 150, and Dask's workers) would each compile every
# module they import again, 0.09 s a command (benchmarks/README.md, *Test suite time*).
test: $(STAMP) setup-test
	$(BIN)/python -m compileall -q src >/dev/null
	$(BIN)/python -m pytest -n $(TEST_WORKERS) --dist loadscope --durations=30

# The documentation site (docs/conf.py) into docs/_build/html, every warning an error; the tutorials
# (docs/tutorials/plot_*.py) run as it builds, their figures drawn by that run, with the venv's
# `feedtherm` first on the PATH for the commands they run.
docs: $(STAMP)
	PATH="$(CURDIR)/$(BIN):$$PATH" $(BIN)/sphinx-build -W --keep-going -b html docs docs/_build/html

clean:
	rm -rf $(VENV) build src/*.egg-info docs/_build docs/auto_tutorials

bench: $(STAMP)
	$(BIN)/python benchmarks/bench_fast.py

# The description fuzzing contract with a larger budget than the suite's (about 25 minutes),
# and the geometry fuzz (a box moved, resized or duplicated) with issue 35's 500 examples each;
# law files and measurement files (issue 57) with 1,000 examples each (about 1 minute each).
FUZZ_EXAMPLES ?= 2000
TOPOLOGY_EXAMPLES ?= 500
FILE_FUZZ_EXAMPLES ?= 1000
fuzz: $(STAMP)
	FEEDTHERM_FUZZ_EXAMPLES=$(FUZZ_EXAMPLES) $(BIN)/python -m pytest -q --hypothesis-show-statistics \
		tests/integration/test_fuzz_descriptions.py
	FEEDTHERM_TOPOLOGY_EXAMPLES=$(TOPOLOGY_EXAMPLES) $(BIN)/python -m pytest -q tests/unit/system/test_topology_property.py
	FEEDTHERM_FILE_FUZZ_EXAMPLES=$(FILE_FUZZ_EXAMPLES) $(BIN)/python -m pytest -q -n 0 --hypothesis-show-statistics \
		tests/integration/test_fuzz_laws.py tests/integration/test_fuzz_measurements.py
