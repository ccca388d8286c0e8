"""A source's heat made in one part and entering others over their contacts with it (``through``).

A bearing's friction heat arises at the ball-raceway contacts: the inner ring's share enters the
shaft, the outer ring's the housing, and the ring part only conducts between them.
"""

from __future__ import annotations

import numpy as np
import pytest

from feedtherm.models.fast.discretization import FastDiscretization
from feedtherm.models.interface import source_shares
from feedtherm.models.options import ModelOptions
from feedtherm.system.load import load_system, parse_toml, read_text, validate_data
from feedtherm.system.variants import with_values


def split_front_bearing(loaded, inner=0.5):
    sources = dict(loaded.system.sources)
    sources["front_bearing"] = sources["front_bearing"].model_copy(
        update={"into": {"screw": inner, "front_housing": 1.0 - inner}, "through": "front_bearing"})
    return with_values(loaded, {"sources": sources})


def test_each_share_enters_over_its_contact_with_the_bearing():
    loaded = split_front_bearing(load_system("paper"), inner=0.3)
    shares = [s for s in source_shares(loaded.system) if s.source == "front_bearing"]
    assert [(s.part, s.power, s.over_contact_with) for s in shares] == [
        ("screw", 0.3, "front_bearing"), ("front_housing", pytest.approx(0.7), "front_bearing")]
    model = FastDiscretization(loaded.system, ModelOptions())
    layout = model.layout
    for share in shares:
        q = model.heat_distribution(share, 0)
        assert q.sum() == pytest.approx(1.0)
        nodes = np.flatnonzero(q)
        assert set(nodes) <= set(layout.part_nodes(share.part).tolist())  # none into the bearing itself
    screw = model.heat_distribution(shares[0], 0)
    x = layout.screw.centres[layout.screw.cell_at(0.0)]  # the bearing sits at -15..15 mm
    heated = np.flatnonzero(screw[layout.screw.nodes].sum(axis=1))
    assert heated.size and np.all(np.abs(layout.screw.centres[heated]) < 0.05), (x, layout.screw.centres[heated])


def test_through_must_be_joined_to_every_receiving_part():
    data = parse_toml(*read_text("paper"))
    data["sources"]["front_bearing"]["into"] = {"screw": 0.5, "rear_housing": 0.5}
    data["sources"]["front_bearing"]["through"] = "front_bearing"
    from feedtherm.errors import FeedthermError
    with pytest.raises(FeedthermError, match=r"sources.front_bearing.into: 'rear_housing' is not joined to 'front_bearing'"):
        validate_data(data, "test")
    data["sources"]["front_bearing"]["into"] = {"screw": 0.5, "front_bearing": 0.5}
    with pytest.raises(FeedthermError, match=r"sources.front_bearing.through: 'front_bearing' is also in into"):
        validate_data(data, "test")


def test_a_source_without_through_keeps_its_serialised_form():
    assert "through" not in load_system("paper").system.model_dump()["sources"]["front_bearing"]
