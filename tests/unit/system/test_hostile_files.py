"""Files that are not what a description or a measurement file is: refused in one line naming the
file, without blocking, a MemoryError or a RecursionError (issue 35, item 4)."""

import os

import pytest

from feedtherm.analysis.measurements import read_measurements
from feedtherm.benches import bench
from feedtherm.cli import main
from feedtherm.errors import DescriptionError
from feedtherm.system.files import MAX_DESCRIPTION_BYTES, MAX_TOML_DEPTH
from feedtherm.system.load import load_system

BENCH = bench("paper").description.read_text(encoding="utf-8")


def refused(spec) -> str:
    with pytest.raises(DescriptionError) as info:
        load_system(str(spec))
    message = str(info.value)
    assert "\n" not in message and message.startswith(f"{spec}: ")
    return message


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs here")
def test_a_fifo_is_refused_without_blocking(tmp_path):
    fifo = tmp_path / "description.toml"
    os.mkfifo(fifo)
    assert "is not a regular file" in refused(fifo)


@pytest.mark.skipif(not os.path.exists("/dev/zero"), reason="no /dev/zero here")
def test_dev_zero_is_refused_without_reading_it():
    assert "is not a regular file" in refused("/dev/zero")


def test_a_description_larger_than_the_limit_is_refused(tmp_path):
    path = tmp_path / "huge.toml"
    with open(path, "wb") as f:
        f.truncate(MAX_DESCRIPTION_BYTES + 1)  # sparse: nothing is written
    assert "is larger than the 16 MB a description may have" in refused(path)


def test_toml_nested_past_the_readers_recursion_is_one_line(tmp_path):
    path = tmp_path / "deep.toml"
    path.write_text("a = " + "[" * 5000 + "]" * 5000 + "\n", encoding="utf-8")
    assert refused(path).endswith(f"tables or arrays nest deeper than {MAX_TOML_DEPTH} levels; a description nests "
                                  "5 at most")


def test_toml_nested_past_the_limit_is_refused(tmp_path):
    path = tmp_path / "deep.toml"
    path.write_text("a = " + "[" * 40 + "]" * 40 + "\n", encoding="utf-8")
    assert "nest deeper than" in refused(path)


def test_a_description_with_a_byte_order_mark_loads(tmp_path):
    path = tmp_path / "bom.toml"
    path.write_text("\ufeff" + BENCH, encoding="utf-8")
    assert load_system(str(path)).system.meta.name == "paper"


def test_a_measurement_file_with_a_byte_order_mark_reads(tmp_path):
    text = bench("paper").measurements.read_text(encoding="utf-8")
    path = tmp_path / "measured.csv"
    path.write_text("\ufeff" + text, encoding="utf-8")
    assert len(read_measurements(str(path)).rows) == len(read_measurements("bundled:paper").rows)


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs here")
def test_a_measurement_fifo_is_refused(tmp_path):
    fifo = tmp_path / "measured.csv"
    os.mkfifo(fifo)
    with pytest.raises(DescriptionError, match="measured.csv: is not a regular file"):
        read_measurements(str(fifo))


def test_an_empty_out_is_refused_in_one_line(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(SystemExit) as info:
        main(["run", "paper", "--condition", "I", "--out", ""])
    assert info.value.code == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "argument --out: an empty path; name a directory" in err
    assert list(tmp_path.iterdir()) == []


def test_a_duration_shorter_than_a_time_step_is_refused_in_one_line(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["run", "paper", "--condition", "I", "--duration", "1e-9", "--out", "o"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--duration: 1e-09 s is shorter than one time step of this run" in err
    assert list(tmp_path.iterdir()) == []
