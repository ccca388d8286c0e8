"""The kept rows of an unfinished sweep: written whole, read back only when whole and this sweep's."""

import json

import pytest

from feedtherm.errors import FeedthermError
from feedtherm.outputs.sweep_partial import PARTIAL_DIR, PartialSweep

COLUMNS = ["screw_rpm", "nut_rpm", "ambient_C", "final_D_um", "equilibrium_time_s"]
SETTINGS = {"feedtherm": "1.0", "description": "paper", "description_sha256": "a" * 64, "mode": "physics",
            "duration_s": 1800.0, "motion": "averaged"}
ROW = {"screw_rpm": 396.0, "nut_rpm": 360.0, "ambient_C": 20.0, "final_D_um": 7.125, "equilibrium_time_s": None}
KEY = "0" * 64


def kept(tmp_path, row=ROW):
    store = PartialSweep(tmp_path, SETTINGS, COLUMNS)
    store.save(KEY, row)
    return store


def test_a_saved_row_reads_back_exactly(tmp_path):
    row = dict(ROW, final_D_um=0.1 + 0.2)  # a float whose text needs all 17 digits
    kept(tmp_path, row)
    store = PartialSweep(tmp_path, SETTINGS, COLUMNS)
    store.open(resume=True)
    assert store.load(["1" * 64, KEY]) == {1: row}
    assert sorted(p.name for p in (tmp_path / PARTIAL_DIR).iterdir()) == [f"{KEY}.json", "sweep.json"]


@pytest.mark.parametrize("content", [
    "",  # empty: written by nothing we know
    '{"format": 1, "key": "' + KEY + '", "row": {"screw_rpm": 396.0',  # cut short
    b"\xff\xfe not text",
    json.dumps({"format": 2, "key": KEY, "row": ROW}),  # another layout
    json.dumps({"format": 1, "key": "1" * 64, "row": ROW}),  # another point's record under this name
    json.dumps({"format": 1, "key": KEY, "row": {k: v for k, v in ROW.items() if k != "final_D_um"}}),
    json.dumps({"format": 1, "key": KEY, "row": dict(ROW, final_D_um="7.1")}),
    json.dumps({"format": 1, "key": KEY, "row": dict(ROW, final_D_um=None)}),  # only an equilibrium time may be empty
    json.dumps({"format": 1, "key": KEY, "row": dict(ROW, final_D_um=True)}),
    '{"format": 1, "key": "' + KEY + '", "row": ' + json.dumps(ROW).replace("7.125", "NaN") + "}",
    json.dumps([1, 2]),
])
def test_a_record_that_is_not_whole_or_not_this_sweeps_is_not_read(tmp_path, content):
    kept(tmp_path)
    path = tmp_path / PARTIAL_DIR / f"{KEY}.json"
    path.write_bytes(content if isinstance(content, bytes) else content.encode())
    store = PartialSweep(tmp_path, SETTINGS, COLUMNS)
    store.open(resume=True)
    assert store.load([KEY]) == {}


def test_kept_points_of_other_settings_or_without_resume_are_one_line(tmp_path):
    kept(tmp_path)
    with pytest.raises(FeedthermError, match=r"^--resume: .* \(the description: kept aaaaaaaaaaaa, now bbbbbbbbbbbb; "
                                             r"--duration: kept 1800, now the default\)"):
        PartialSweep(tmp_path, dict(SETTINGS, description_sha256="b" * 64, duration_s=None), COLUMNS).open(resume=True)
    with pytest.raises(FeedthermError, match="holds 1 finished point of an interrupted sweep"):
        PartialSweep(tmp_path, SETTINGS, COLUMNS).open(resume=False)
    # the same description moved elsewhere is the same description
    PartialSweep(tmp_path, dict(SETTINGS, description="copy/paper.toml"), COLUMNS).open(resume=True)


def test_a_folder_without_points_is_cleared_and_nothing_is_made_before_a_point_finishes(tmp_path):
    (tmp_path / PARTIAL_DIR).mkdir()
    (tmp_path / PARTIAL_DIR / ".tmp-1-abcd-x.json").write_text("{")
    PartialSweep(tmp_path, SETTINGS, COLUMNS).open(resume=False)
    assert list(tmp_path.iterdir()) == []
    store = PartialSweep(tmp_path / "new", SETTINGS, COLUMNS)
    store.open(resume=True)
    assert store.load([KEY]) == {} and not (tmp_path / "new").exists()


def test_a_failed_write_leaves_no_temporary_file(tmp_path, monkeypatch):
    store = kept(tmp_path)

    def broken(*args):
        raise OSError("disk full")

    monkeypatch.setattr("os.replace", broken)
    with pytest.raises(OSError):
        store.save("1" * 64, ROW)
    assert sorted(p.name for p in (tmp_path / PARTIAL_DIR).iterdir()) == [f"{KEY}.json", "sweep.json"]


@pytest.mark.parametrize("when", ["before the rename", "after the rename"])
def test_a_ctrl_c_while_a_record_is_written_counts_it_only_once_it_is_on_disk(tmp_path, monkeypatch, when):
    """The count the interrupted sweep's message gives is the records on disk, whatever line the
    KeyboardInterrupt lands on."""
    import os

    store = kept(tmp_path)
    real = os.replace

    def interrupted(source, target):
        if when == "after the rename":
            real(source, target)
        raise KeyboardInterrupt

    monkeypatch.setattr("os.replace", interrupted)
    with pytest.raises(KeyboardInterrupt):
        store.save("1" * 64, ROW)
    on_disk = [p for p in (tmp_path / PARTIAL_DIR).iterdir() if p.name != "sweep.json"]
    assert store.count() == len(on_disk) == (2 if when == "after the rename" else 1)
