"""Files that are not what a description, an overlay or a measurement file is: refused in one line
naming the file, without blocking, a MemoryError or a RecursionError (issue 35, item 4)."""

import os

import pytest

from feedtherm.system.measurements import read_measurements
from feedtherm.benches import bench
from feedtherm.cli import main
from feedtherm.errors import DescriptionError
from feedtherm.system.files import MAX_DESCRIPTION_BYTES, MAX_TOML_DEPTH
from feedtherm.system.load import load_system
from feedtherm.system.overlay import OVERLAY, OVERLAY_DEPTH, read_overlay

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


# --------------------------------------------------------------------------- overlays
# An overlay (system/overlay.py) is read by the same rules as a description: `heat` reads the
# overlay a description names in meta.overlay, beside the computed values.
OVERLAY_TEXT = bench("paper").folder.joinpath(OVERLAY).read_text(encoding="utf-8")


def heat_with_overlay(tmp_path, capsys, overlay: str) -> tuple[int, str, str]:
    """`feedtherm heat` on the paper bench copied to a file that names ``overlay`` as its overlay."""
    path = tmp_path / "mine.toml"
    path.write_text(BENCH.replace('measurements = "bundled:paper"',
                                  f'measurements = "bundled:paper"\noverlay = "{overlay}"', 1), encoding="utf-8")
    code = main(["heat", str(path), "--condition", "I"])
    out, err = capsys.readouterr()
    return code, out, err


def overlay_refused(tmp_path, capsys, overlay: str, name: str) -> str:
    code, out, err = heat_with_overlay(tmp_path, capsys, overlay)
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and err.startswith(f"feedtherm: error: {name}: "), err
    return err


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs here")
def test_an_overlay_fifo_is_refused_without_blocking(tmp_path, capsys):
    os.mkfifo(tmp_path / "printed.toml")
    assert "is not a regular file" in overlay_refused(tmp_path, capsys, "printed.toml", tmp_path / "printed.toml")


@pytest.mark.skipif(not os.path.exists("/dev/zero"), reason="no /dev/zero here")
def test_an_overlay_on_dev_zero_is_refused_without_reading_it(tmp_path, capsys):
    assert "is not a regular file" in overlay_refused(tmp_path, capsys, "/dev/zero", "/dev/zero")


def test_an_overlay_larger_than_the_limit_is_refused(tmp_path, capsys):
    with open(tmp_path / "printed.toml", "wb") as f:
        f.truncate(MAX_DESCRIPTION_BYTES + 1)  # sparse: nothing is written
    err = overlay_refused(tmp_path, capsys, "printed.toml", tmp_path / "printed.toml")
    assert "is larger than the 16 MB an overlay may have" in err


@pytest.mark.parametrize("depth", [40, 5000])  # past the limit, and past the TOML reader's recursion
def test_an_overlay_nested_too_deep_is_refused(tmp_path, capsys, depth):
    (tmp_path / "printed.toml").write_text("a = " + "[" * depth + "]" * depth + "\n", encoding="utf-8")
    err = overlay_refused(tmp_path, capsys, "printed.toml", tmp_path / "printed.toml")
    assert err.endswith(f"tables or arrays nest deeper than {MAX_TOML_DEPTH} levels; an overlay nests "
                        f"{OVERLAY_DEPTH} at most\n"), err


def test_an_overlay_with_a_byte_order_mark_reads(tmp_path, capsys, paper):
    (tmp_path / "printed.toml").write_text("\ufeff" + OVERLAY_TEXT, encoding="utf-8")
    code, out, err = heat_with_overlay(tmp_path, capsys, "printed.toml")
    assert code == 0 and err == "" and "4.95" in out  # Table 1's front bearing, printed beside
    bundled = read_overlay(bench("paper").folder / OVERLAY, paper.system)
    assert read_overlay(tmp_path / "printed.toml", paper.system) == bundled
