"""The paper bench's description as text, with changes made: the hostile and error tests' variants."""

from feedtherm.benches import bench

PAPER = bench("paper").description.read_text(encoding="utf-8")


def paper_text(*changes: tuple[str, str]) -> str:
    """The paper bench's description with each ``(old, new)`` replaced once; a change whose ``old``
    is not in the file fails the test (its fixture is out of date), never passes it unchanged."""
    text = PAPER
    for old, new in changes:
        assert old in text, f"test fixture out of date: {old!r} not in the bench file"
        text = text.replace(old, new, 1)
    return text
