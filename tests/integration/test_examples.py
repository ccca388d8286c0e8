"""Every script in docs/examples runs, and its numbers agree with the paper, with physical
relations and with hand calculations written out here — never with what a script printed once.

Each example is imported by path (as scikit-fem's tests/test_examples.py imports its
docs/examples) and its ``main()`` returns the numbers it prints; each runs once per session.
The printing block of each script is run on those numbers, so a reader's
``python docs/examples/NAME.py`` is covered too.
"""

import ast
import importlib.util
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from feedtherm.boundary import boundary_conditions, boundary_conditions_at
from feedtherm.boundary.temperatures import LocalTemperatures
from feedtherm.models.coupling import STEADY_TOLERANCE
from feedtherm.models.registry import unregister_model
from feedtherm.simulate import simulate
from feedtherm.system.variants import with_values

EXAMPLES = Path(__file__).resolve().parents[2] / "docs" / "examples"
SENSORS = ["T1", "T2", "T3", "T4", "T5"]
NAMES = ["load_and_inspect", "run_fast_model", "compare_models", "sweep_speeds", "calibrate", "custom_model"]

# The paper's Table 4: GCr15 (screw, bearings) and Q345B (base, housings) expand alike.
ALPHA_SCREW = 1.2e-5  # [1/K]
ALPHA_HOUSING = 1.2e-5  # [1/K] the front housing
ALPHA_BASE = 1.2e-5  # [1/K]
AMBIENT_I = 20.0  # [°C], Table 5, condition I; also the bench's reference temperature (ISO 1)
# The elongation D by hand, from the bench's description (mechanics, joints, parts; mm):
# the laser (mechanics.elongation) reads the screw's rear end face, x = 450, relative to the
# base at x = 480, along +x.  The base (x from -300 to 700) is held along x at its front foot,
# x = -250; the chain of joints that hold x from it to the screw is base -> front_housing
# (bolted along its foot: they meet over x from -220 to 30) -> front_bearing (in the housing's
# bore, -15 to 15) -> screw (in the bearing, -15 to 15; the rear bearing floats, release x).
# A part fastened to its parent over a range is held at the middle of it and expands freely
# from there (models/fast/bars.py), so the anchors are
#     base at its support -250;  front_housing (-220 + 30)/2 = -95;
#     front_bearing (-15 + 15)/2 = 0;  screw (-15 + 15)/2 = 0,
# and a part's point x moves by its anchor's displacement on the parent plus α ∫ ΔT̄ dx from
# the anchor to x (rises ΔT̄ over T_ref, section means):
#     u_base(x)    = α_b ∫_-250^x ΔT̄_base dx
#     u_housing(x) = u_base(-95) + α_h ∫_-95^x ΔT̄_housing dx
#     u_bearing(x) = u_housing(0) + α_r ∫_0^x ΔT̄_bearing dx       (u_bearing(0) = u_housing(0))
#     u_screw(x)   = u_bearing(0) + α_s ∫_0^x ΔT̄_screw dx
# so the bearing, held at 0 and holding the screw at 0, stretches nothing D reads, and
#     D = u_screw(450) − u_base(480)
#       = α_s ∫_0^450 ΔT̄_screw dx + α_h ∫_-95^0 ΔT̄_housing dx − α_b ∫_-95^480 ΔT̄_base dx;
# against the positioning reference, the base at x = 0,
#     u_screw(x) − u_base(0)
#       = α_s ∫_0^x ΔT̄_screw dx + α_h ∫_-95^0 ΔT̄_housing dx − α_b ∫_-95^0 ΔT̄_base dx.
BASE_SUPPORT = -0.250  # [m] the base's front foot, held along x
HOUSING_ANCHOR = -0.095  # [m] the middle of the front housing's foot on the base, (-220 + 30)/2
SCREW_ANCHOR = 0.0  # [m] the middle of the front bearing, (-15 + 15)/2: the screw expands from there
LASER_TARGET = 0.450  # [m] the screw's rear end face
LASER_MOUNT = 0.480  # [m] the laser's stand on the base
# The base over all of -95..480 mm: slab 400 x 40 mm plus two risers 40 x 90 mm (x from -200 to
# 600) in section, A = 23200 mm²; in all, V = 1000·400·40 + 2·800·40·90 = 21.76e6 mm³.
BASE_SECTION = 23200e-6  # [m²]
BASE_VOLUME = 21.76e6 * 1e-9  # [m³]
# The front housing: the bearing housing 60 x 110 x 95 mm (x from -30 to 30) with a 62 mm bore
# through it, 110·95 − π·31² = 7430.9 mm² in section, and the motor's bracket plate (x from
# -220 to -30), 80 x 30 = 2400 mm²: over -95..0 mm its section is at least A = 2400 mm²; in all,
# V = 60·110·95 − π·31²·60 + 190·80·30 = 901855.8 mm³.
HOUSING_MIN_SECTION = 2400e-6  # [m²]
HOUSING_VOLUME = (60 * 110 * 95 - math.pi * 31**2 * 60 + 190 * 80 * 30) * 1e-9  # [m³]


def load(name):
    spec = importlib.util.spec_from_file_location(f"docs_example_{name}", EXAMPLES / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def printed(name, result, capsys) -> list[str]:
    """The lines the script's ``if __name__ == "__main__":`` block prints for ``result``."""
    module = load(name)
    tree = ast.parse((EXAMPLES / f"{name}.py").read_text(encoding="utf-8"))
    block = next(node for node in tree.body if isinstance(node, ast.If) and "__main__" in ast.unparse(node.test))
    capsys.readouterr()
    exec(compile(ast.Module(block.body, []), module.__file__, "exec"), {**vars(module), "main": lambda: result})
    return capsys.readouterr().out.splitlines()


def test_every_example_is_tested_and_listed():
    assert sorted(p.stem for p in EXAMPLES.glob("*.py")) == sorted(NAMES)
    listing = (EXAMPLES / "README.md").read_text(encoding="utf-8")
    for name in NAMES:
        assert f".venv/bin/python docs/examples/{name}.py" in listing, name
        assert ast.get_docstring(ast.parse((EXAMPLES / f"{name}.py").read_text(encoding="utf-8"))), name


def test_an_example_runs_as_a_script_from_anywhere(tmp_path):
    result = subprocess.run([sys.executable, str(EXAMPLES / "load_and_inspect.py")], cwd=tmp_path,
                            capture_output=True, check=False, text=True, timeout=300)
    assert result.returncode == 0, result.stderr
    assert "total heat:" in result.stdout and "Traceback" not in result.stderr


# --------------------------------------------------------------------------- load_and_inspect


@pytest.fixture(scope="module")
def inspect_result():
    return load("load_and_inspect").main()


def test_load_and_inspect_heats_against_table_1_and_hand_calculations(inspect_result, paper, capsys):
    r = inspect_result
    assert (r["screw_rpm"], r["nut_rpm"]) == (396.0, 360.0)  # Table 5, condition I
    # Table 1 as printed in the paper, carried by the description for comparison
    assert r["table1_heat_W"] == pytest.approx({"guideways": 0.39, "screw_motor": 1.87, "nut_motor": 1.70,
                                                "front_bearing": 4.95, "nut_bearing": 5.31, "rear_bearing": 4.36})
    assert set(r["table1_heat_W"]) <= set(r["sources"]) and len(r["parts"]) == len(paper.system.parts)
    assert r["total_heat_W"] == pytest.approx(sum(r["heat_W"].values()), rel=1e-12)
    # The bench's losses are catalogue models (data-sheet motor losses, SKF bearing friction), not
    # the paper's equations behind Table 1: Table 1 is printed beside them for comparison only.
    d = r["details"]
    omega = 2 * math.pi * 396 / 60  # screw speed [rad/s]
    # Guideways: Coulomb friction force times table speed, v = (396 − 360) rpm · 10 mm / 60 = 0.006 m/s.
    g = paper.system.sources["guideways"]
    normal = g.moving_mass * 9.80665 + g.external_load  # [N]
    force = g.friction_coefficient * normal + g.seal_drag_per_carriage * g.carriages
    assert r["heat_W"]["guideways"] == pytest.approx(force * 0.006, rel=1e-9)
    # A bearing's heat is its friction torque times its shaft's speed.
    assert r["heat_W"]["front_bearing"] == pytest.approx(d["front_bearing"]["friction_torque_Nm"] * omega, rel=1e-9)
    # The screw motor by hand, with the data sheet's values as the description declares them.
    losses = paper.system.sources["screw_motor"].losses
    k_t, r_20, t_f, damping = 0.39, 5.70, 0.02, 2e-5  # [N·m/A], [Ω] at 20 °C, [N·m], [N·m·s/rad]
    assert (losses.torque_constant, losses.terminal_resistance, losses.friction_torque, losses.viscous_damping) \
        == pytest.approx((k_t, r_20, t_f, damping), rel=1e-12)
    # Its torque: the friction torques on the screw shaft (both bearings, the thread) plus the
    # torque F·lead/(2π) with which the screw pushes the table against the guideways' friction.
    torque = (d["front_bearing"]["friction_torque_Nm"] + d["rear_bearing"]["friction_torque_Nm"]
              + d["screw_nut"]["friction_torque_Nm"] + force * 0.010 / (2 * math.pi))
    # The winding at the declared surface temperature, 20 °C + 10 K, copper as (235 + θ) (IEC 60034-1).
    theta = AMBIENT_I + paper.system.temperatures.convection_delta_t
    resistance = r_20 * (235 + theta) / (235 + 20)
    current = torque / k_t
    copper = 1.5 * current**2 * resistance  # 3 I² R_phase = 3/2 I² R_terminal
    no_load = t_f * omega + damping * omega**2
    m = d["screw_motor"]
    assert (m["torque_Nm"], m["current_A"], m["terminal_resistance_ohm"]) == pytest.approx((torque, current, resistance),
                                                                                       rel=1e-9)
    assert (m["copper_loss_W"], m["no_load_loss_W"]) == pytest.approx((copper, no_load), rel=1e-9)
    assert r["heat_W"]["screw_motor"] == pytest.approx(copper + no_load, rel=1e-9)
    lines = printed("load_and_inspect", r, capsys)
    assert any(line.startswith("total heat:") for line in lines) and len(lines) == 4 + len(r["heat_W"]) + 3
    assert any(line.startswith("screw motor:") and f"{copper:.2f} W" in line for line in lines)


def test_load_and_inspect_screw_shaft_chtc_by_hand(inspect_result):
    """Eq. 27 mixed with natural convection (Morgan), by hand with Incropera Table A.4 air at 300 K
    (ν = 15.89e-6 m²/s, k = 26.3e-3 W/(m·K), α = 22.5e-6 m²/s, Pr^(1/3) = 0.89085); 3 % for the
    property table against CoolProp at the 298.15 K film.

    forced:  ω = 2π·396/60 = 41.469 rad/s, Re = ω d²/ν = 41.469 · 0.032² / 15.89e-6 = 2672.4,
             Nu = 0.133 Re^(2/3) Pr^(1/3) = 0.133 · 192.6 · 0.89085 = 22.82, h = Nu k/d = 18.76
    natural: Ra = g/T ΔT d³/(να) = 9.80665/300 · 10 · 0.032³ / (15.89e-6 · 22.5e-6) = 2.996e4,
             Nu = 0.48 Ra^0.25 = 6.315, h = 5.19   (ΔT = the declared 10 K rise)
    mixed:   (18.76³ + 5.19³)^(1/3) = 18.89 W/(m²·K); Table 2 prints 56.3.
    """
    re = 2 * math.pi * 396 / 60 * 0.032**2 / 15.89e-6
    h_forced = 0.133 * re ** (2 / 3) * 0.89085 * 26.3e-3 / 0.032
    ra = 9.80665 / 300 * 10 * 0.032**3 / (15.89e-6 * 22.5e-6)
    h_natural = 0.48 * ra**0.25 * 26.3e-3 / 0.032
    assert h_forced == pytest.approx(18.76, rel=1e-3) and h_natural == pytest.approx(5.19, rel=1e-3)
    assert inspect_result["screw_shaft_chtc"] == pytest.approx((h_forced**3 + h_natural**3) ** (1 / 3), rel=0.03)
    assert inspect_result["table2_screw_shaft_chtc"] == 56.3


# --------------------------------------------------------------------------- run_fast_model


@pytest.fixture(scope="module")
def fast_result():
    return load("run_fast_model").main()


def test_run_fast_model_conserves_energy_and_heats_towards_steady(fast_result, paper, capsys):
    r = fast_result
    assert abs(r["energy_relative_error"]) < 1e-6
    # The bench is coupled (temperatures.coupling = "nonlinear"): the sources' heat follows the
    # temperatures, so the heat in is its time integral, not one boundary condition's total
    # times 3600 s.  The run starts with every surface and source at the ambient (its first
    # boundary conditions) and ends with those of info["heat_W"]; the bench warms steadily over
    # the hour, so the heat moves steadily from one to the other and its mean over the run,
    # heat in / duration, lies between them.
    system = paper.system
    point = boundary_conditions(system, "I").point
    ambient = point.ambient
    at_start = boundary_conditions_at(system, point, temperatures=LocalTemperatures(
        {name: ambient for name in system.surfaces}, {name: ambient for name in system.sources})).total_heat
    mean = r["energy_in_J"] / r["duration_s"]
    assert r["duration_s"] == pytest.approx(3600.0)
    assert min(at_start, r["heat_end_W"]) < mean < max(at_start, r["heat_end_W"]), (at_start, mean, r["heat_end_W"])
    assert r["ambient_C"] == pytest.approx(AMBIENT_I)
    for n in SENSORS:  # starting at ambient, one hour in: warmer than the air, not yet at steady state
        assert AMBIENT_I < r["final_C"][n] < r["steady_C"][n], n
    lines = printed("run_fast_model", r, capsys)
    assert len(lines) == 5 and f"D = {r['D_um']:.1f} µm" in lines[2] and f"{r['screw_stretch_um']:.1f} µm" in lines[2]
    assert all(f"{at}" in lines[2] for at in ("(x = 0 mm)", "(450 mm)", "(-95 mm)", "(480 mm;", "-250 mm"))
    assert f"adds {r['D_end_um'] - r['screw_stretch_um']:+.2f} µm" in lines[2]
    e = r["positioning_error_um"]
    assert f"E = {e[0]:.1f} µm at x = 113.5 mm" in lines[3] and f"{e[-1]:.1f} µm at 313.5 mm" in lines[3]


def test_run_fast_model_elongation_and_positioning_error_by_hand(fast_result):
    """D and E(x) at the last sample from the screw's, the front housing's and the base's
    temperatures (the chain above LASER_TARGET)."""
    r = fast_result
    # The screw's cells: 510 mm (x from -60 to 450) in 102 cells of 5 mm, 0 and 450 mm among their edges.
    x, T, u = r["screw_x_m"], r["screw_C"], r["screw_displacement_um"]
    np.testing.assert_allclose(np.diff(x), 0.005, rtol=1e-9)
    assert (len(x), x[0], x[-1]) == (102, pytest.approx(-0.0575), pytest.approx(0.4475))
    free = x > SCREW_ANCHOR  # the 90 cells from 0 to 450 mm
    assert free.sum() == 90 and r["screw_stretch_m"] == pytest.approx((SCREW_ANCHOR, LASER_TARGET))
    assert (r["housing_anchor_m"], r["base_support_m"], r["laser_mount_m"]) == pytest.approx(
        (HOUSING_ANCHOR, BASE_SUPPORT, LASER_MOUNT))
    # The screw is one bar held at x = 0: along all of it, on either side of its anchor, it
    # stretches by its section-mean strain, cell by cell: between two cell centres by
    # α · 5 mm · (half of each cell's rise), exactly (whatever the housing and the base do).
    between = ALPHA_SCREW * 0.005 * ((T[:-1] + T[1:]) / 2 - AMBIENT_I) * 1e6
    np.testing.assert_allclose(np.diff(u), between, rtol=1e-9, atol=1e-12)
    # so from 0 to 450 mm: α · 5 mm · Σ ΔT̄ over the 90 cells
    stretch = ALPHA_SCREW * 0.005 * np.sum(T[free] - AMBIENT_I) * 1e6  # [µm]
    assert r["screw_stretch_um"] == pytest.approx(stretch, rel=1e-12)
    assert np.all(T > AMBIENT_I)  # the screw warms along all its length
    # The housing's and the base's terms.  Ambient = initial = T_ref and every source heats, so no
    # node of the implicit steps falls below 20 °C (their maximum principle): 0 ≤ ΔT̄.  Where a
    # part's section is at least A, ∫ ΔT̄ dx ≤ (1/A) ∫_V ΔT dV = V/A · ΔT_mean: over -95..480 mm
    # the base's section is one (A = 23200 mm²), over -95..0 mm the housing's at least 2400 mm².
    base_bound = ALPHA_BASE * BASE_VOLUME / BASE_SECTION * (r["base_C"] - AMBIENT_I) * 1e6  # [µm]
    housing_bound = ALPHA_HOUSING * HOUSING_VOLUME / HOUSING_MIN_SECTION * (r["front_housing_C"] - AMBIENT_I) * 1e6
    assert 0.0 < base_bound < 0.1 * stretch  # one hour in, the base has barely warmed
    assert housing_bound > 0.0
    # D − stretch = α_h ∫_-95^0 ΔT̄_housing dx − α_b ∫_-95^480 ΔT̄_base dx, each term from 0 to its bound
    assert stretch - base_bound <= r["D_end_um"] <= stretch + housing_bound
    # The screw at its anchor, x = 0, against the positioning reference (the first cell's
    # centre, 2.5 mm, less half a cell's stretch):
    #   u_screw(0) − u_base(0) = α_h ∫_-95^0 ΔT̄_housing dx − α_b ∫_-95^0 ΔT̄_base dx.
    at_anchor = u[free][0] - ALPHA_SCREW * 0.0025 * (T[free][0] - AMBIENT_I) * 1e6
    assert -base_bound <= at_anchor <= housing_bound
    # and D from it: u_screw(450) − u_base(0) = at_anchor + stretch, so
    #   at_anchor + stretch − D = u_base(480) − u_base(0) = α_b ∫_0^480 ΔT̄_base dx, in (0, base_bound].
    at_target = u[-1] + ALPHA_SCREW * 0.0025 * (T[-1] - AMBIENT_I) * 1e6  # the rear cell's centre plus half a cell
    assert at_target == pytest.approx(at_anchor + stretch, rel=1e-9)
    assert 0.0 < at_anchor + stretch - r["D_end_um"] <= base_bound
    # The positioning error: the screw's displacement relative to the base at x = 0 under the
    # nut's centre, which travels 213.5 mm (the nut spans 170 to 257 mm) ± 100 mm (stroke 200 mm).
    table_x = r["table_x_m"]
    np.testing.assert_allclose(table_x, 0.2135 + np.linspace(-0.100, 0.100, len(table_x)), rtol=0, atol=1e-12)
    E = r["positioning_error_um"]
    np.testing.assert_allclose(E, np.interp(table_x, x, u), rtol=1e-12)
    assert np.all(np.diff(E) > 0)  # a warm screw: E grows along the stroke, away from the fixed bearing


# --------------------------------------------------------------------------- compare_models


@pytest.mark.skipif(importlib.util.find_spec("gmsh") is None, reason="the FE model needs gmsh")
def test_compare_models_fast_and_fe_agree_within_a_kelvin(fast_result, tmp_path_factory, capsys):
    with pytest.MonkeyPatch.context() as mp:  # mesh into a cache of this test, not the user's
        mp.setenv("FEEDTHERM_CACHE", str(tmp_path_factory.mktemp("feedtherm-cache")))
        r = load("compare_models").main()
    assert r["ambient_C"] == pytest.approx(AMBIENT_I)
    for n in SENSORS:  # the project's acceptance (tests/integration/test_fem_bench.py): |ΔT| < 1 K, |ΔD| < 2 µm
        assert abs(r["difference_K"][n]) < 1.0, (n, r["difference_K"])
        assert r["fem_C"][n] > AMBIENT_I and r["fast_C"][n] > AMBIENT_I
        # the direct steady solve and the steady value a transient Solution carries are the same state
        assert r["fast_C"][n] == pytest.approx(fast_result["steady_C"][n], abs=1e-9)
    assert abs(r["difference_D_um"]) < 2.0
    assert r["difference_D_um"] == pytest.approx(r["fem_D_um"] - r["fast_D_um"], abs=1e-9)
    assert len(printed("compare_models", r, capsys)) == 2 + len(SENSORS) + 1


# --------------------------------------------------------------------------- sweep_speeds


def test_sweep_speeds_rows(paper, capsys):
    r = load("sweep_speeds").main()
    assert r["points"] == [(396.0, 360.0, 20.0), (1116.0, 360.0, 20.0)]
    # table speed = (n_screw − n_nut) · lead, 10 mm lead: 36 rpm → 0.36 m/min, 756 rpm → 7.56 m/min
    assert r["table_speed_m_per_min"] == pytest.approx([0.36, 7.56], rel=1e-12)
    assert all(abs(e) < 1e-6 for e in r["energy_relative_error"])
    low, high = r["final_T3_C"]
    assert AMBIENT_I < low < high  # more relative speed, more friction heat at the nut
    assert r["final_D_um"][0] < r["final_D_um"][1]
    # the first point is condition I of Table 5: the sweep's own condition runs the same physics
    condition_i = simulate(paper, condition="I", duration=r["duration_s"], motion="averaged")
    assert low == pytest.approx(condition_i.summary_values("final")["T3"], abs=1e-9)
    assert len(printed("sweep_speeds", r, capsys)) == 3


# --------------------------------------------------------------------------- calibrate

# Tables 6 and 7 of the paper: measured at condition I and II after 3 h.
MEASURED = {"I": {"T1": 27.1, "T2": 24.5, "T3": 34.5, "T4": 33.2, "T5": 31.9, "D_um": 29.9},
            "II": {"T1": 29.6, "T2": 26.2, "T3": 37.1, "T4": 35.8, "T5": 34.2, "D_um": 35.5}}
PRELOAD = "sources.screw_nut.preload"


def finals_with_preload(paper, preload, condition):
    """The final values as calibration computes them: cycle-averaged, its 60 s steps."""
    from feedtherm.analysis.calibration import CALIBRATION_OPTIONS, CALIBRATION_STEP_S

    run = simulate(with_values(paper, {PRELOAD: preload}), condition=condition, motion="averaged",
                   options=CALIBRATION_OPTIONS, sample_interval=CALIBRATION_STEP_S,
                   allow_overload=True)  # as calibration runs them: it reports the motors' duty instead
    return run.summary_values("final")


def weighted_cost(paper, finals, condition):
    """Σ ((simulated − measured)/σ)² with the description's σ (0.5 K, 2 µm)."""
    cal = paper.system.calibration
    return sum(((finals[q] - m) / (cal.elongation_sigma * 1e6 if q == "D_um" else cal.temperature_sigma)) ** 2
               for q, m in MEASURED[condition].items())


def test_calibrate_fits_the_preload_and_predicts_condition_ii(paper, capsys):
    r = load("calibrate").main()
    preload = paper.system.sources["screw_nut"].preload  # the description's value [N]
    assert r["parameter"] == "screw_nut_preload" and r["declared"] == pytest.approx(preload)
    assert r["held_out_measured"] == pytest.approx(MEASURED["II"])
    assert 50.0 < r["fitted"] < 365.0 and 0 < r["standard_error"] < r["fitted"]  # declared bounds
    # At the declared preload the model runs colder than measured at I, so the fit adds thread heat.
    declared = finals_with_preload(paper, preload, "I")
    assert all(declared[n] < MEASURED["I"][n] for n in SENSORS)
    assert r["fitted"] > r["declared"]
    # The fit is a least-squares minimum: lower cost than the declared value and than 5 % either side.
    at_fit = finals_with_preload(paper, r["fitted"], "I")
    cost = weighted_cost(paper, at_fit, "I")
    assert cost < weighted_cost(paper, declared, "I")
    for factor in (0.95, 1.05):
        assert cost <= weighted_cost(paper, finals_with_preload(paper, r["fitted"] * factor, "I"), "I")
    assert r["fit_deviation"] == pytest.approx({q: at_fit[q] - m for q, m in MEASURED["I"].items()}, abs=1e-6)
    # Held out: the description with the fitted preload, run at II, against Tables 6 and 7.
    at_ii = finals_with_preload(paper, r["fitted"], "II")
    assert r["held_out_deviation"] == pytest.approx({q: at_ii[q] - m for q, m in MEASURED["II"].items()}, abs=1e-6)
    rms = math.sqrt(sum((at_ii[n] - MEASURED["II"][n]) ** 2 for n in SENSORS) / len(SENSORS))
    assert r["held_out_rms_K"] == pytest.approx(rms, rel=1e-9)
    assert len(printed("calibrate", r, capsys)) == 4


# --------------------------------------------------------------------------- custom_model


@pytest.fixture(scope="module")
def custom():
    module = load("custom_model")
    yield module, module.main()
    unregister_model(module.MODEL.name)


def test_custom_model_runs_through_simulate_and_conserves_energy(custom, capsys):
    module, r = custom
    assert r["model"] == module.MODEL.name
    assert abs(r["energy_relative_error"]) < 1e-6
    for n in SENSORS:
        assert r["ambient_C"] < r["final_C"][n] < r["steady_C"][n], n
    # Every part is one isothermal node; the screw's is read by T4.  Each part stretches
    # uniformly from its anchor, the middle of where it meets its parent (the chain above
    # LASER_TARGET), so the front bearing, held at x = 0 and holding the screw there, stretches
    # nothing D reads:
    #   D = α_s (T_screw − 20) (450 − 0) mm + α_h (T_housing − 20) (0 − (−95)) mm
    #       − α_b (T_base − 20) (480 − (−95)) mm.
    parts = r["steady_parts_C"]
    assert parts["screw"] == pytest.approx(r["steady_C"]["T4"], abs=1e-9)
    hand = (ALPHA_SCREW * (parts["screw"] - AMBIENT_I) * (LASER_TARGET - SCREW_ANCHOR)
            + ALPHA_HOUSING * (parts["front_housing"] - AMBIENT_I) * (SCREW_ANCHOR - HOUSING_ANCHOR)
            - ALPHA_BASE * (parts["base"] - AMBIENT_I) * (LASER_MOUNT - HOUSING_ANCHOR))
    assert r["steady_D_um"] == pytest.approx(hand * 1e6, rel=1e-9)
    lines = printed("custom_model", r, capsys)
    assert len(lines) == 3 and f"D {r['steady_D_um']:.1f} µm" in lines[1]


def test_custom_model_reads_a_uniform_rise_as_one_lumped_body(custom, paper):
    """With every part at T_ref + ΔT the loop expands as one body of α: along the chain of anchors
    (base −250, housing −95, bearing 0, screw 0) D = α ΔT [(−95 + 250) + (0 + 95) + (0 − 0)
    + (450 − 0) − (480 + 250)] mm = α · 10 K · (450 − 480) mm, and the screw's one section (its
    centre, (−60 + 450)/2 = 195 mm) moves α ΔT [155 + 95 + 0 + 195 − (0 + 250)] mm = α ΔT · 195 mm
    from the positioning reference, the base at x = 0."""
    module, _ = custom
    model = module.PartLumped(paper.system, None)
    rows, offset = model.displacement_rows()
    assert rows.shape == (2, len(paper.system.parts))
    reference = paper.system.temperatures.reference
    np.testing.assert_allclose(model.displacements(model.uniform_state(reference)), 0.0, atol=1e-17)
    D, at_centre = model.displacements(model.uniform_state(reference + 10.0))
    assert D == pytest.approx(ALPHA_SCREW * 10.0 * (LASER_TARGET - LASER_MOUNT), rel=1e-9)
    assert D == pytest.approx(-3.6e-6, rel=1e-9)
    assert at_centre == pytest.approx(ALPHA_SCREW * 10.0 * 0.195, rel=1e-9)


def test_custom_model_steady_state_loses_all_the_heat_put_in(custom, paper):
    """At steady state every watt of the sources leaves through the surfaces:
    Σ_s (h_conv + h_rad)_s A_s (T_part(s) − T_sink) = Σ Q, with h, A and Q from the boundary conditions
    at the steady state's own temperatures (the bench couples them: coupling = "nonlinear")."""
    module, _ = custom
    run = simulate(paper, condition="I", model=module.MODEL.name, duration=60.0, motion="averaged", start="steady")
    T = {part: series[0] for part, series in run.part_temperatures.items()}  # t = 0: the coupled steady state
    # This model's readout by hand: a surface at its part's node, a source at the mean of the
    # parts its heat goes into, weighted by the shares.
    system = paper.system
    reading = LocalTemperatures(
        {name: T[surface.part] for name, surface in system.surfaces.items()},
        {name: sum(w * T[part] for part, w in source.into.items()) / sum(source.into.values())
         for name, source in system.sources.items()})
    bc = boundary_conditions_at(system, boundary_conditions(system, "I").point, temperatures=reading)
    # the run started from that state evaluated its boundary conditions there
    assert run.info["heat_W"] == pytest.approx({name: heat.power for name, heat in bc.heats.items()}, rel=1e-9)
    lost = sum(s.total * s.area * (T[s.part] - s.sink) for s in bc.surfaces.values())
    # The coupled steady state is a fixed point to STEADY_TOLERANCE [K] (its last iteration moved
    # no node by more): the balance holds to the surfaces' conductance Σ h A times that.
    conductance = sum(s.total * s.area for s in bc.surfaces.values())  # [W/K]
    assert lost == pytest.approx(bc.total_heat, rel=0, abs=STEADY_TOLERANCE * conductance)
