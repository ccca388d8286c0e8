"""``feedtherm new NAME [--out DIR]``: names and targets it cannot write are refused in one line naming
``NAME`` or ``--out`` and the reason, before anything is written; a write that fails half-way leaves
nothing behind."""

from __future__ import annotations

import errno
import os
from pathlib import Path

import pytest

from feedtherm.benches import template


@pytest.mark.parametrize("name, says", [
    ("a" * 300, ("NAME:", "300 characters", f"at most {template.MAX_NAME_LENGTH}")),
    ("a" * (template.MAX_NAME_LENGTH + 1), ("NAME:", f"at most {template.MAX_NAME_LENGTH}")),
    ("mill\n", ("NAME:", "is not a valid bench name")),  # a trailing newline: the whole name must match
    ("mill/../x", ("NAME:", "is not a valid bench name")),
    ("müll", ("NAME:", "is not a valid bench name")),  # ASCII, as a description's names
])
def test_a_name_it_cannot_write_is_refused(refused, name, says):
    refused("new", name, says=says)


def test_the_longest_name_is_written(tmp_path, monkeypatch, capsys):
    from feedtherm.cli import main

    monkeypatch.chdir(tmp_path)
    name = "a" * template.MAX_NAME_LENGTH
    assert main(["new", name]) == 0
    assert (tmp_path / name / "description.toml").is_file()


def test_a_name_longer_than_the_file_system_allows_is_refused(refused, monkeypatch):
    # a file system of 14-byte names (System V's): the staging folder's name would not fit
    real = os.pathconf
    monkeypatch.setattr(os, "pathconf", lambda path, name: 14 if name == "PC_NAME_MAX" else real(path, name))
    refused("new", "my_mill", says=("NAME:", "too long for the file system", "14 bytes"))


def test_an_out_nested_beyond_the_path_limit_is_refused(refused, tmp_path, monkeypatch):
    real = os.pathconf
    limit = len(os.fsencode(str(tmp_path))) + 20
    monkeypatch.setattr(os, "pathconf", lambda path, name: limit if name == "PC_PATH_MAX" else real(path, name))
    refused("new", "my_mill", "--out", str(tmp_path), says=("--out:", "nested too deep", f"{limit} bytes"))


@pytest.mark.parametrize("out, says", [
    ("/dev/null", ("--out: /dev/null is a device, not a folder",)),
    ("missing", ("--out: missing does not exist",)),
    ("missing/deeper", ("--out: missing/deeper does not exist",)),
])
def test_an_out_that_is_no_folder_is_refused(refused, out, says):
    refused("new", "my_mill", "--out", out, says=says)


def test_an_out_that_is_a_file_is_refused(refused, tmp_path):
    (tmp_path / "notes.txt").write_text("mine")
    refused("new", "my_mill", "--out", "notes.txt", says=("--out: notes.txt is a file, not a folder",))
    assert (tmp_path / "notes.txt").read_text() == "mine"


def test_a_device_where_the_bench_would_go_is_refused(refused):
    refused("new", "null", "--out", "/dev", says=("/dev/null: exists and is a device",))


def test_a_symbolic_link_where_the_bench_would_go_is_refused(refused, tmp_path):
    (tmp_path / "my_mill").symlink_to(tmp_path / "nowhere")
    refused("new", "my_mill", says=("my_mill: exists and is a symbolic link",))
    assert (tmp_path / "my_mill").is_symlink() and not (tmp_path / "nowhere").exists()


def test_a_file_or_a_full_folder_in_the_way_is_refused(refused, tmp_path):
    (tmp_path / "axis").write_text("mine")
    refused("new", "axis", says=("axis: exists and is a file",))
    (tmp_path / "full").mkdir()
    (tmp_path / "full" / "keep.txt").write_text("mine")
    refused("new", "full", says=("full: exists and is a folder that is not empty",))
    assert (tmp_path / "axis").read_text() == "mine" and (tmp_path / "full" / "keep.txt").read_text() == "mine"


def test_an_out_it_may_not_write_in_is_refused(refused, tmp_path, monkeypatch):
    # os.access decides (root passes any permission bits, so the refusal is exercised through it)
    locked = tmp_path / "locked"
    locked.mkdir()
    locked.chmod(0o555)
    real = os.access
    monkeypatch.setattr(os, "access", lambda path, mode, **kw: False if Path(path) == Path("locked")
                        else real(path, mode, **kw))
    try:
        refused("new", "my_mill", "--out", "locked", says=("--out: locked is not writable",))
        assert list(locked.iterdir()) == []
    finally:
        locked.chmod(0o755)


def test_a_write_that_fails_half_way_leaves_nothing(refused, tmp_path, monkeypatch):
    written = []
    real = Path.write_text

    def full_disk(self, *args, **kwargs):
        if written:
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        written.append(self)
        return real(self, *args, **kwargs)

    monkeypatch.setattr(Path, "write_text", full_disk)
    refused("new", "my_mill", says=("my_mill: could not write the bench", "No space left on device",
                                    "nothing was written"))
    assert written  # the first file was written, in the staging folder that is gone again
    assert list(tmp_path.iterdir()) == []


def test_a_folder_that_cannot_be_made_is_refused(refused, tmp_path, monkeypatch):
    def read_only(self, *args, **kwargs):
        raise OSError(errno.EROFS, os.strerror(errno.EROFS))

    monkeypatch.setattr(Path, "mkdir", read_only)
    refused("new", "my_mill", says=("--out: cannot write in .", "Read-only file system"))
