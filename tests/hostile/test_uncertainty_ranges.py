"""Declared uncertainties whose range leaves what the value accepts: an expansion coefficient's
prior reaching below zero, a contact resistance's beyond its range, a normal distribution whose
unbounded tails do.  Refused in one line naming the uncertainty's field, as the value itself
would be refused there (the same sign and Limit)."""

from __future__ import annotations

import pytest

from feedtherm.benches import bench

PAPER = bench("paper").description.read_text(encoding="utf-8")
FIRST = "[uncertainty.parameters.screw_nut_friction]"


def with_uncertainty(tmp_path, body: str) -> str:
    """The paper bench with one more declared uncertainty, ``steel_expansion``, written to ``tmp_path``."""
    assert FIRST in PAPER, "test fixture out of date"
    text = PAPER.replace(FIRST, f'[uncertainty.parameters.steel_expansion]\n{body}\nreason = "a test"\n\n{FIRST}', 1)
    path = tmp_path / "variant.toml"
    path.write_text(text, encoding="utf-8")
    return str(path)


EXPANSION = 'paths = ["materials.q345b.expansion"]\n'


@pytest.mark.parametrize("body, says", [
    # the audit's case: a uniform prior down to -1.1e-5 1/K gave D's band down to -11 um
    (f'kind = "value"\n{EXPANSION}distribution = "uniform"\nrange = ["-1.1e-5 1/K", "2e-5 1/K"]',
     ("uncertainty.parameters.steel_expansion.range", "reaches -1.1e-05 (SI) at materials.q345b.expansion",
      "must be positive")),
    # as a factor on the declared 1.2e-5 1/K
    (f'kind = "scale"\n{EXPANSION}distribution = "triangular"\nrange = [-0.9, 2.0]',
     ("uncertainty.parameters.steel_expansion.range", "reaches -1.08e-05 (SI)", "must be positive")),
    # above the accepted range, 0 to 1e-3 1/K
    (f'kind = "value"\n{EXPANSION}distribution = "uniform"\nrange = ["1e-5 1/K", "2e-3 1/K"]',
     ("uncertainty.parameters.steel_expansion.range", "outside the accepted range, 0 to 0.001 1/K")),
    # a normal without a range: its samples reach 7 standard deviations, below zero here
    (f'kind = "value"\n{EXPANSION}distribution = "normal"\nsigma = "3e-6 1/K"',
     ("uncertainty.parameters.steel_expansion.sigma", "a normal distribution without a range reaches",
      "give range = [low, high]")),
    # a factor on every contact resistance beyond the tcr's accepted 1e-7..1e4 m^2 K/W
    ('kind = "scale"\npaths = ["joints[*].tcr"]\ndistribution = "uniform"\nrange = [1e-6, 2.0]',
     ("uncertainty.parameters.steel_expansion.range", "at joints[0].tcr", "1e-07 to 10000 m^2*K/W")),
    # a Poisson ratio must stay below 0.5 (its field's own bound)
    ('kind = "value"\npaths = ["materials.q345b.poisson_ratio"]\ndistribution = "uniform"\nrange = [0.2, 0.6]',
     ("uncertainty.parameters.steel_expansion.range", "materials.q345b.poisson_ratio", "less than 0.5")),
])
def test_a_range_outside_what_the_value_accepts_is_refused(tmp_path, refused, body, says):
    refused("check", with_uncertainty(tmp_path, body), says=says)


def test_a_range_inside_what_the_value_accepts_loads(tmp_path, warned):
    body = f'kind = "value"\n{EXPANSION}distribution = "uniform"\nrange = ["1.0e-5 1/K", "1.4e-5 1/K"]'
    # exit 0, with the bench's own one warning (its stated feed speed)
    warned("check", with_uncertainty(tmp_path, body), says=("conditions.I.feed_speed",))
