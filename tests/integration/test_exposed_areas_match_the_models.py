"""The exposed areas `check` and `heat` report are the areas the fast model gives to the air.

The report derives them from the primitives (feedtherm.system.areas); the fast model finds them
on its own face samples (models/fast/samples.py), the moving group mid-stroke.  They agree to
the samples' resolution of holes (22.5° patches around a bore): within 2 %.
"""

import pytest

from feedtherm.benches.template import TEMPLATE
from feedtherm.simulate import discretize
from feedtherm.system.areas import exposed_area
from feedtherm.system.load import load_system


def template(tmp_path):
    path = tmp_path / "description.toml"
    path.write_text((TEMPLATE / "description.toml").read_text(encoding="utf-8").replace("__BENCH_NAME__", "t"))
    return str(path)


@pytest.mark.parametrize("bench", ["template", "paper"])
def test_each_surface_without_an_area_exposes_what_the_fast_model_exposes(tmp_path, bench):
    loaded = load_system(template(tmp_path) if bench == "template" else bench)
    model = discretize(loaded.system, "fast")
    mid = len(model.positions) // 2
    compared = 0
    for name, surface in loaded.system.surfaces.items():
        if surface.area is not None:
            continue
        assert model.surface_exposure(name, mid)[1].sum() == pytest.approx(exposed_area(loaded.system, name), rel=0.02)
        compared += 1
    assert compared >= 13
