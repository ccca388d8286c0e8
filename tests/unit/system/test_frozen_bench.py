"""The paper bench's values are frozen: a change must go through calibration, not an edit.

If this test fails, the bundled `paper` description changed.  Its assumptions were declared
once, before any comparison with the measurements (Tables 6 and 7); tuning them afterwards
would hide a fit inside the model.  Fit parameters with the calibration step, which writes a
separate, marked description, and leave this file alone.
"""

from feedtherm.system.load import load_system

FROZEN_SHA256 = "7f5313d700b9f695c340bfaa924c5ddd80fb7d3fde956ba872dce16429aa7965"


def test_paper_bench_is_frozen():
    assert load_system("paper").sha256 == FROZEN_SHA256
