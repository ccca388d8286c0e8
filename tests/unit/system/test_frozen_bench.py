"""The paper bench's values are frozen: a change must go through calibration, not an edit.

If this test fails, the bundled `paper` description changed.  Its assumptions were declared
once, before any comparison with the measurements (Tables 6 and 7); tuning them afterwards
would hide a fit inside the model.  Fit parameters with the calibration step, which writes a
separate, marked description, and leave this file alone.
"""

from feedtherm.system.load import load_system

FROZEN_SHA256 = "f675a5794096a44614ee6f285ed6595d4df01d7de90690d5ee84510286019956"


def test_paper_bench_is_frozen():
    assert load_system("paper").sha256 == FROZEN_SHA256
