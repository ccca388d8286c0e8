"""Writing a set of result files: staged, swapped in whole, cleaned up after a killed run; JSON."""

from __future__ import annotations

import json
import math
import os
import stat
import subprocess
import sys
import textwrap
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

from feedtherm.errors import FeedthermError
from feedtherm.outputs import files
from feedtherm.outputs.files import (
    check_output_dir,
    json_text,
    remove_stale_staging,
    staged_directory,
    to_json_ready,
    write_json,
)

# --------------------------------------------------------------------------- JSON


@dataclass
class Point:
    name: str
    x: float


@dataclass
class Result:
    where: Point
    values: np.ndarray
    path: Path


def test_numpy_scalars_and_arrays_become_python_numbers_and_lists():
    ready = to_json_ready({"n": np.int64(137), "x": np.float32(0.5), "ok": np.bool_(True),
                           "grid": np.arange(6.0).reshape(2, 3), "zero_d": np.array(2.5)})
    assert ready == {"n": 137, "x": 0.5, "ok": True, "grid": [[0.0, 1.0, 2.0], [3.0, 4.0, 5.0]], "zero_d": 2.5}
    assert type(ready["n"]) is int and type(ready["x"]) is float and type(ready["ok"]) is bool
    assert type(ready["grid"][1][2]) is float
    json.dumps(ready, allow_nan=False)


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf, np.float64("nan"), np.float32("inf")])
def test_nan_and_infinities_become_null(bad):
    assert to_json_ready(bad) is None
    assert to_json_ready([1.0, bad]) == [1.0, None]
    assert to_json_ready(np.array([[1.0, bad]])) == [[1.0, None]]


def test_paths_dataclasses_tuples_and_keys():
    result = Result(where=Point("T1", 0.25), values=np.array([1.0, np.nan]), path=Path("out") / "run")
    ready = to_json_ready({"result": result, "pair": (1, "a"), 3: "three"})
    assert ready == {"result": {"where": {"name": "T1", "x": 0.25}, "values": [1.0, None], "path": "out/run"},
                     "pair": [1, "a"], "3": "three"}


def test_an_unknown_type_is_an_error_naming_it():
    with pytest.raises(TypeError, match="cannot write a complex as JSON"):
        to_json_ready({"z": 1 + 2j})
    with pytest.raises(TypeError, match="type"):
        to_json_ready(Point)  # a dataclass type, not an instance


def test_json_text_and_write_json(tmp_path):
    value = {"D_um": np.float64(28.14), "error": np.float64(np.inf), "unit": "µm"}
    text = json_text(value)
    assert '"unit": "µm"' in text and "Infinity" not in text
    assert json.loads(text) == {"D_um": 28.14, "error": None, "unit": "µm"}
    path = tmp_path / "summary.json"
    write_json(path, value)
    assert path.read_text(encoding="utf-8") == text + "\n"


# --------------------------------------------------------------------------- helpers


def write_set(directory: Path, tag: str, names=("a.csv", "summary.json")) -> None:
    for name in names:
        (directory / name).write_text(f"{tag} {name}\n")


def contents(directory: Path) -> dict[str, str]:
    return {p.name: p.read_text() for p in sorted(directory.iterdir()) if p.is_file() and not p.is_symlink()}


def hidden(parent: Path) -> list[str]:
    return sorted(p.name for p in parent.iterdir() if p.name.startswith("."))


def run_python(code: str, *args) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", textwrap.dedent(code), *map(str, args)],
                          check=False, capture_output=True, text=True, timeout=120)


@pytest.fixture
def old_run(tmp_path) -> Path:
    """An earlier run's set, with a user's file beside it."""
    target = tmp_path / "run"
    target.mkdir()
    write_set(target, "old")
    (target / "notes.txt").write_text("mine\n")
    return target


# --------------------------------------------------------------------------- writing a set


def test_a_new_directory_appears_with_its_parents_and_nothing_else(tmp_path):
    target = tmp_path / "deep" / "er" / "run"
    with staged_directory(target) as stage:
        assert stage.parent == target.parent and stage.name.startswith(".run.partial-")
        write_set(stage, "new")
        assert not target.exists()  # nothing visible before the set is complete
    assert contents(target) == {"a.csv": "new a.csv\n", "summary.json": "new summary.json\n"}
    assert os.listdir(target.parent) == ["run"]


def test_a_swap_replaces_the_whole_set_and_keeps_other_files(old_run):
    notes_inode = (old_run / "notes.txt").stat().st_ino
    (old_run / "plot_b.png").write_text("old plot\n")  # belongs to the old set, not written now
    (old_run / "data").mkdir()
    (old_run / "data" / "measured.csv").write_text("x\n")
    os.symlink("notes.txt", old_run / "link")
    with staged_directory(old_run, replaces=["plot_*.png"]) as stage:
        write_set(stage, "new")
    assert contents(old_run) == {"a.csv": "new a.csv\n", "notes.txt": "mine\n", "summary.json": "new summary.json\n"}
    assert (old_run / "notes.txt").stat().st_ino == notes_inode  # kept as a link to the same file
    assert (old_run / "data" / "measured.csv").read_text() == "x\n"
    assert os.readlink(old_run / "link") == "notes.txt"
    assert not (old_run / "plot_b.png").exists()
    assert hidden(old_run.parent) == []


def test_a_reader_never_sees_new_files_beside_old_ones(old_run, monkeypatch):
    """Look at the directory at every rename of the swap: always the old set whole, or the new."""
    seen = []
    real_rename = os.rename

    def watched(source, destination):
        seen.append(contents(old_run) if old_run.exists() else None)
        real_rename(source, destination)

    monkeypatch.setattr(files.os, "rename", watched)
    with staged_directory(old_run) as stage:
        write_set(stage, "new")
    seen.append(contents(old_run))
    old = {"a.csv": "old a.csv\n", "notes.txt": "mine\n", "summary.json": "old summary.json\n"}
    new = {"a.csv": "new a.csv\n", "notes.txt": "mine\n", "summary.json": "new summary.json\n"}
    assert len(seen) == 3 and seen[0] == old and seen[-1] == new
    assert all(state in (old, new, None) for state in seen)


def test_a_failure_while_writing_leaves_the_old_directory_and_no_staging_folder(old_run):
    before = contents(old_run)
    inode = old_run.stat().st_ino
    with pytest.raises(RuntimeError, match="disk on fire"), staged_directory(old_run) as stage:
        (stage / "a.csv").write_text("new a.csv\n")
        raise RuntimeError("disk on fire")
    assert contents(old_run) == before and old_run.stat().st_ino == inode
    assert hidden(old_run.parent) == []


def test_a_failure_during_the_swap_puts_the_old_directory_back(old_run, monkeypatch):
    before = contents(old_run)
    real_rename = os.rename

    def stage_cannot_move_in(source, destination):
        if ".partial-" in Path(source).name and Path(destination) == old_run:
            raise OSError(5, "Input/output error")
        real_rename(source, destination)

    monkeypatch.setattr(files.os, "rename", stage_cannot_move_in)
    with (pytest.raises(FeedthermError, match=r"run: cannot write the outputs \(Input/output error\)"),
          staged_directory(old_run) as stage):
        write_set(stage, "new")
    assert contents(old_run) == before
    assert hidden(old_run.parent) == []


def test_the_directory_keeps_its_permissions(old_run):
    old_run.chmod(0o750)
    with staged_directory(old_run) as stage:
        write_set(stage, "new")
    assert stat.S_IMODE(old_run.stat().st_mode) == 0o750


def test_a_symbolic_link_to_the_directory_stays_a_link(old_run, tmp_path):
    link = tmp_path / "latest"
    link.symlink_to(old_run)
    with staged_directory(link) as stage:
        write_set(stage, "new")
    assert link.is_symlink() and link.resolve() == old_run
    assert contents(old_run)["summary.json"] == "new summary.json\n"
    assert hidden(tmp_path) == []


# --------------------------------------------------------------------------- the output directory


def test_the_current_directory_cannot_be_the_output_directory(old_run, monkeypatch):
    (old_run / "sub").mkdir()
    for cwd in (old_run, old_run / "sub"):
        monkeypatch.chdir(cwd)
        with pytest.raises(FeedthermError, match="holds the current directory"):
            check_output_dir(old_run)
    check_output_dir(old_run / "sub" / "out")  # below the current directory: fine


def test_a_file_in_the_way_is_an_error(tmp_path):
    (tmp_path / "run").write_text("not a directory")
    with pytest.raises(FeedthermError, match="exists and is not a directory"):
        check_output_dir(tmp_path / "run")
    with pytest.raises(FeedthermError, match="is a file, not a directory"):
        check_output_dir(tmp_path / "run" / "inside")


# --------------------------------------------------------------------------- after a killed run


KILLED_WHILE_WRITING = """
    import os, sys
    from feedtherm.outputs.files import staged_directory
    with staged_directory(sys.argv[1]) as stage:
        (stage / "a.csv").write_text("half")
        os._exit(9)  # as SIGKILL: no clean-up runs
"""

KILLED_DURING_THE_SWAP = """
    import os, sys
    from feedtherm.outputs import files
    real_rename = os.rename
    def rename(source, destination):
        real_rename(source, destination)
        if ".replaced-" in os.path.basename(destination):
            os._exit(9)  # the old set is aside, the new one not yet in place
    files.os.rename = rename
    with files.staged_directory(sys.argv[1]) as stage:
        (stage / "a.csv").write_text("killed a.csv\\n")
        (stage / "summary.json").write_text("killed summary.json\\n")
"""


def test_a_staging_folder_of_a_killed_run_is_removed_by_the_next_run(old_run):
    killed = run_python(KILLED_WHILE_WRITING, old_run)
    assert killed.returncode == 9, killed.stderr
    [left] = hidden(old_run.parent)
    assert left.startswith(".run.partial-") and (old_run.parent / left / "a.csv").exists()
    before = contents(old_run)
    assert before["summary.json"] == "old summary.json\n"  # the killed run changed nothing
    with staged_directory(old_run) as stage:
        write_set(stage, "new")
    assert hidden(old_run.parent) == []
    assert contents(old_run)["summary.json"] == "new summary.json\n"


def test_a_swap_cut_midway_is_undone_by_the_next_run(old_run):
    killed = run_python(KILLED_DURING_THE_SWAP, old_run)
    assert killed.returncode == 9, killed.stderr
    assert not old_run.exists()
    assert [name.split("-")[0] for name in hidden(old_run.parent)] == [".run.partial", ".run.replaced"]
    remove_stale_staging(old_run)
    assert contents(old_run) == {"a.csv": "old a.csv\n", "notes.txt": "mine\n", "summary.json": "old summary.json\n"}
    assert hidden(old_run.parent) == []


def test_only_our_folders_of_processes_that_are_gone_are_removed(old_run):
    killed = run_python(KILLED_WHILE_WRITING, old_run)
    assert killed.returncode == 9, killed.stderr
    [left] = hidden(old_run.parent)
    _, host, dead_pid, _ = left.rsplit("-", 3)
    others = [".run.partial-0123456789ab",  # no process id: cannot tell whether it is stale
              f".run2.partial-{host}-{dead_pid}-0123456789ab",  # another directory's
              f".run.partial-x{host}-{dead_pid}-0123456789ab",  # another host's: its process cannot be probed
              f".run.partial-{host}-{dead_pid}-0123456789ab.keep"]  # not our name
    for name in others:
        (old_run.parent / name).mkdir()
    with staged_directory(old_run) as stage:
        remove_stale_staging(old_run)  # this process runs: its own staging folder stays
        assert stage.is_dir()
        write_set(stage, "new")
    assert hidden(old_run.parent) == sorted(others)
