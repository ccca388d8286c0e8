"""The paper bench's values are frozen: a change must go through calibration, not an edit.

If this test fails, the bundled `paper` description changed.  Its assumptions were declared
once, before any comparison with the measurements (Tables 6 and 7); tuning them afterwards
would hide a fit inside the model.  Fit parameters with the calibration step, which writes a
separate, marked description, and leave this file alone.
"""

from feedtherm.system.load import load_system

# Changed through declared, reviewed changes of the assumption set (issue 12):
# - the base plate's underside, adiabatic before, stands on a bed at room temperature
#   (surfaces.base_bottom and its [[provenance]] entry), and calibration may fit that conductance;
# - the loss models that scale as the components do replace the paper's equations: motors by their
#   copper loss at the shaft torque plus their no-load loss (a declared 400 W-class servo's data
#   sheet), bearings by the SKF model on an ISO VG 100 oil, the thread preload 150 N (500 N would
#   exceed the declared motors' continuous torque), and temperatures.coupling = "nonlinear"; the
#   calibration parameters follow (motor_copper, motor_no_load, front_bearing_preload for
#   motor_efficiency).  The paper's equation models stay available (tests/conftest.py keeps them
#   as a variant for the hand calculations written against them). The thread preload's calibration
#   bound follows the motors: 365 N, where the circulating torque reaches their continuous torque.
# - temperatures.temperature_dependent_chtc became temperatures.coupling; calibration may fit the
#   room's air speed (calibration.parameters.room_air_speed).
# - calibration could fit where the laser reads the elongation (calibration.parameters.elongation_read_at,
#   100-450 mm: the paper does not state it); the declared value stayed 400 mm.
# - issue 14: declared uncertainties ([uncertainty.parameters], docs/uncertainty.md) say how far the
#   values that matter may lie from the declared ones; they change no value (the hash without them
#   is VALUES_SHA256, tested below).
# - issue 31: the thermal error is a displacement. [elongation] (a read point on the screw) gave way
#   to [mechanics]: the base on three feet (3-2-1), the floating rear bearing, the carriages and the
#   thread releasing x, the laser declared from the paper's text (on a stand on the base, aimed at the
#   screw's rear end face), the positioning reference, E and nu of the motors and the belt; the read
#   point is neither calibrated nor a declared uncertainty any more. The loop follows the paper's text
#   and common practice, not Table 7 (a rough estimate before it was declared showed that it takes the
#   measured ambient dependence of D away; it was declared as it is all the same).
#   The schema then gained mechanics.elements (the FE model's displacement elements, default
#   "linear", which the bench keeps): the canonical data gained the default, no value changed.
FROZEN_SHA256 = "9ec87f3dfb501cabf7619786e1595ae207cc70381f8765bd1a6beb22793c001e"
#: The hash of the bench's values alone, without its declared uncertainties.
VALUES_SHA256 = "5b3cecb3b43f9db88fb026f8bb3cd6832e19c2cbd50cd9b9efdaf331e8e95e2b"


def test_paper_bench_is_frozen():
    assert load_system("paper").sha256 == FROZEN_SHA256


def test_declared_uncertainties_change_no_value():
    from feedtherm.system.variants import with_values

    loaded = load_system("paper")
    assert loaded.system.uncertainty is not None
    assert with_values(loaded, {"uncertainty": None}).sha256 == VALUES_SHA256
