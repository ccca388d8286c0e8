"""Property: ``check`` reports an overlap naming both parts exactly when two boxes' interiors
intersect (computed here on its own), and none otherwise, wherever the second box is put, whatever
its size, and whether it is the block's or a second box of the plate; and when a box is duplicated,
into its own part or the other, left in place or moved (issue 35: a box moved, resized or
duplicated).

The suite runs a short fixed-seed budget (``FEEDTHERM_TOPOLOGY_EXAMPLES``, default 60);
``FEEDTHERM_TOPOLOGY_EXAMPLES=500`` runs the issue's 500 in each (about 30 s for the two on a
shared 2-core machine, 2026-11: too long for every run of the suite).
"""

import os

from hypothesis import given, settings
from hypothesis import strategies as st

from feedtherm.system.checks import check_system

from topology_cases import BLOCK_BOX, PLATE_BOX, box, system, text

EXAMPLES = int(os.environ.get("FEEDTHERM_TOPOLOGY_EXAMPLES", "60"))
PLATE = ((0, 0, 0), (200, 100, 20))  # mm, as PLATE_BOX

# Whole mm: two faces either meet exactly or are a mm apart, so "overlap" has no borderline.
coordinate = st.integers(-60, 260)
extent = st.integers(1, 120)


def interiors_intersect(a, b) -> bool:
    (ao, asz), (bo, bsz) = a, b
    return all(max(ao[k], bo[k]) < min(ao[k] + asz[k], bo[k] + bsz[k]) for k in range(3))


@settings(max_examples=EXAMPLES, derandomize=True, deadline=None, database=None)
@given(origin=st.tuples(coordinate, coordinate, st.integers(-40, 60)), size=st.tuples(extent, extent, extent),
       where=st.sampled_from(["block", "plate"]))
def test_an_overlap_is_reported_exactly_when_the_boxes_intersect(origin, size, where):
    moved = box(origin, size)
    if where == "block":  # the block moved or resized
        description = text(PLATE_BOX, moved)
        parts = ("plate", "block")
    else:  # a second box of the plate, beside the block
        description = text(f"{PLATE_BOX}, {moved}", BLOCK_BOX)
        parts = ("plate", "plate")
    overlap = [str(f) for f in check_system(system(description)) if "overlap" in f.message]
    expected = interiors_intersect(PLATE, (origin, size))
    if where == "plate":
        block = ((50, 20, 20), (100, 60, 40))
        expected_block = interiors_intersect(block, (origin, size))
        if expected_block:  # the plate's new box runs into the block: that pair is reported too
            assert any("'block'" in f and f.startswith("parts.plate.boxes[1]") for f in overlap), overlap
        assert any(f.startswith("parts.plate: boxes[0] and boxes[1] overlap") for f in overlap) is expected, overlap
        assert len(overlap) == expected + expected_block, overlap
    else:
        assert bool(overlap) is expected, overlap
        if expected:
            [line] = overlap
            assert line.startswith("parts.plate.boxes[0]: overlaps part 'block'"), line
            assert all(f"'{p}'" in line or f"parts.{p}" in line for p in parts)


BLOCK = ((50, 20, 20), (100, 60, 40))  # mm, as BLOCK_BOX
offset = st.one_of(st.just(0), st.integers(-150, 150))  # a copy left in place, or moved


@settings(max_examples=EXAMPLES, derandomize=True, deadline=None, database=None)
@given(source=st.sampled_from(["plate", "block"]), into=st.sampled_from(["plate", "block"]),
       shift=st.tuples(offset, offset, offset))
def test_a_duplicated_box_is_reported_exactly_where_it_overlaps(source, into, shift):
    """A box copied (a line pasted twice, then perhaps edited) into its own part or the other one:
    each pair of a part's boxes that intersect is one error, and the two parts are one line if any
    of their boxes intersect; a copy left in place overlaps its original completely."""
    origin, size = PLATE if source == "plate" else BLOCK
    copy = (tuple(o + d for o, d in zip(origin, shift)), size)
    boxes = {"plate": [PLATE], "block": [BLOCK]}
    boxes[into].append(copy)
    description = text(", ".join(box(*b) for b in boxes["plate"]), ", ".join(box(*b) for b in boxes["block"]))
    overlap = sorted(str(f) for f in check_system(system(description)) if "overlap" in f.message)
    within = [f"parts.{into}: boxes[0] and boxes[1] overlap"] if interiors_intersect(boxes[into][0], copy) else []
    between = any(interiors_intersect(a, b) for a in boxes["plate"] for b in boxes["block"])
    assert len(overlap) == len(within) + between, overlap
    assert all(any(line.startswith(w) for line in overlap) for w in within), overlap
    if between:
        [line] = [f for f in overlap if "overlaps part 'block'" in f]
        assert line.startswith("parts.plate.boxes["), line
    if shift == (0, 0, 0):  # an exact duplicate overlaps its original, wherever it was put
        assert overlap and (bool(within) if into == source else between), overlap
