"""`feedtherm sweep --resume`: an interrupted sweep keeps its finished points and finishes with the
uninterrupted run's CSV, running only the points it did not keep; kept points of another sweep,
and records that are not whole, are never read back."""

import json
import os
import signal
import subprocess
import sys
import time

import pytest

from feedtherm import cli
from feedtherm.analysis import sweep as sweep_module
from feedtherm.outputs.sweep_partial import PARTIAL_DIR, SETTINGS_JSON

from child_process import environment
from child_process import finish as finish_within

# Six points of about half a second each (in a child process): long enough to be interrupted
# after two have finished and before the last.
SLOW_GRID = ["--screw-rpm", "396,1116,2214", "--nut-rpm", "360", "--ambient", "20,25", "--duration", "7200"]
# Four points of ~0.3 s, run in this process.
GRID = ["--screw-rpm", "396,1116", "--nut-rpm", "360", "--ambient", "20:25:5", "--duration", "1800"]
WAIT_S = 120


def records(out):
    """The kept points' records: not the settings, and not a record still being written (a hidden
    temporary file, which pathlib's glob matches too)."""
    folder = out / PARTIAL_DIR
    if not folder.is_dir():
        return []
    return sorted(p for p in folder.glob("*.json") if p.name != SETTINGS_JSON and not p.name.startswith("."))


#: ``python -m feedtherm`` as a terminal's foreground job starts it, Ctrl-C raising KeyboardInterrupt:
#: a suite started in the background (``make test &``, a job without a terminal) passes its children
#: SIGINT ignored, the POSIX rule for background jobs, and Python then installs no handler of its own.
FOREGROUND = ("import runpy, signal, sys; signal.signal(signal.SIGINT, signal.default_int_handler); "
              "sys.argv[0] = 'feedtherm'; runpy.run_module('feedtherm', run_name='__main__', alter_sys=True)")


def sweep(cwd, *args, **popen):
    return subprocess.Popen([sys.executable, "-c", FOREGROUND, "sweep", *args], cwd=cwd, env=environment(),
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **popen)


def finish(process):
    return finish_within(process, WAIT_S)


@pytest.fixture(scope="module")
def slow_reference(tmp_path_factory):
    cwd = tmp_path_factory.mktemp("reference")
    code, out, err = finish(sweep(cwd, *SLOW_GRID, "--out", "ref"))
    assert code == 0, err
    return (cwd / "ref" / "sweep.csv").read_bytes()


@pytest.mark.parametrize("where, stop", [
    ([], signal.SIGINT), (["--workers", "2"], signal.SIGINT), ([], signal.SIGTERM),
], ids=["ctrl-c", "ctrl-c-two-workers", "sigterm"])
def test_a_stopped_sweep_keeps_the_finished_points_and_resume_finishes_with_the_same_csv(tmp_path, slow_reference,
                                                                                          where, stop):
    """Ctrl-C is SIGINT to the whole process group, as a terminal sends it (the local cluster's
    workers get it too); SIGTERM (a batch system's time limit) goes to feedtherm alone.  Either
    comes once two points are on disk."""
    out = tmp_path / "out"
    process = sweep(tmp_path, *SLOW_GRID, *where, "--out", "out", start_new_session=True)
    deadline = time.monotonic() + WAIT_S
    while len(records(out)) < 2 and process.poll() is None and time.monotonic() < deadline:
        time.sleep(0.02)
    assert process.poll() is None, "the sweep ended before it could be stopped"
    if stop == signal.SIGINT:
        os.killpg(process.pid, signal.SIGINT)
    else:
        process.send_signal(signal.SIGTERM)
    code, stdout, stderr = finish(process)
    kept = len(records(out))
    assert code == 128 + stop, stderr
    assert stdout == ""
    assert 2 <= kept < 6
    word = "interrupted" if stop == signal.SIGINT else "terminated"
    assert stderr.splitlines() == [f"feedtherm: {word}; {kept} of 6 points kept in out/{PARTIAL_DIR}; "
                                   "the same command with --resume runs only the others"]
    assert not (out / "sweep.csv").exists()

    code, stdout, stderr = finish(sweep(tmp_path, *SLOW_GRID, *where, "--out", "out", "--resume"))
    assert code == 0, stderr
    assert stderr == ""
    assert stdout.startswith("out: sweep of 6 points written in ")
    summary, *warning = stdout.rstrip().splitlines()
    assert summary.endswith(f"; resumed {kept} of 6 points, ran {6 - kept}")
    # the two 2214 rpm points take the screw motor past its rating: said, and computed all the same
    assert len(warning) == 1 and warning[0].startswith("warning: 2 of 6 points need more than a motor's continuous torque")
    assert (out / "sweep.csv").read_bytes() == slow_reference
    assert not (out / PARTIAL_DIR).exists()  # dropped in the swap that brought the CSV in
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]  # no staging folder, no dask scratch space


# --------------------------------------------------------------------------- in this process


@pytest.fixture
def counted(monkeypatch):
    """The labels of the points that really run; the third run of the first sweep is "interrupted"."""
    real = sweep_module._simulate
    state = {"ran": [], "interrupt_at": None}

    def counting(run, progress=None):
        if len(state["ran"]) == state["interrupt_at"]:
            state["interrupt_at"] = None
            raise KeyboardInterrupt
        state["ran"].append(run.label)
        return real(run, progress)

    monkeypatch.setattr(sweep_module, "_simulate", counting)
    return state


def main(*args):
    return cli.main(["sweep", *args])


def test_resume_runs_only_the_missing_points_and_rereads_no_broken_record(tmp_path, counted, capsys):
    assert main(*GRID, "--out", str(tmp_path / "whole")) == 0
    reference = (tmp_path / "whole" / "sweep.csv").read_bytes()
    order = list(counted["ran"])
    assert len(order) == 4

    counted.update(ran=[], interrupt_at=2)
    out = tmp_path / "out"
    assert main(*GRID, "--out", str(out)) == 130
    assert capsys.readouterr().err.splitlines()[-1] == (f"feedtherm: interrupted; 2 of 4 points kept in "
                                                         f"{out / PARTIAL_DIR}; the same command with --resume runs "
                                                         f"only the others")
    broken, whole = records(out)
    # A record cut short (what a crash mid-write would leave, were it not renamed into place) and
    # a temporary file of a killed writer: neither is read back.
    broken.write_bytes(broken.read_bytes()[:40])
    (out / PARTIAL_DIR / f".tmp-1-abcd-{whole.name}").write_text('{"format": 1')
    row = json.loads(whole.read_text())["row"]
    kept_label = sweep_module.point_label(row["screw_rpm"], row["nut_rpm"], row["ambient_C"])
    assert kept_label in order[:2]

    counted.update(ran=[])
    assert main(*GRID, "--out", str(out), "--resume") == 0
    assert capsys.readouterr().out.rstrip().endswith("; resumed 1 of 4 points, ran 3")
    # The broken record's point and the two that never ran, in grid order; the kept one not again.
    assert counted["ran"] == [label for label in order if label != kept_label]
    assert (out / "sweep.csv").read_bytes() == reference
    assert sorted(p.name for p in out.iterdir()) == sorted(p.name for p in (tmp_path / "whole").iterdir())


@pytest.fixture
def interrupted(tmp_path, counted, capsys):
    """A sweep of GRID into tmp_path/out stopped after two points."""
    counted.update(interrupt_at=2)
    assert main(*GRID, "--out", str(tmp_path / "out")) == 130
    capsys.readouterr()
    counted.update(ran=[])
    return tmp_path / "out"


def test_without_resume_a_folder_with_kept_points_is_one_line_and_left_as_it_is(interrupted, counted, capsys):
    before = {p.name: p.read_bytes() for p in records(interrupted)}
    assert main(*GRID, "--out", str(interrupted)) == 2
    err = capsys.readouterr().err
    assert err.splitlines() == [f"feedtherm: error: {interrupted}: holds 2 finished points of an interrupted sweep "
                                f"({interrupted / PARTIAL_DIR}); add --resume to finish it, or delete that folder "
                                f"to start afresh"]
    assert counted["ran"] == []
    assert {p.name: p.read_bytes() for p in records(interrupted)} == before


@pytest.mark.parametrize("change, fragment", [
    (["--duration", "3600"], "(--duration: kept 1800, now 3600)"),
    (["--mode", "paper"], "(--mode: kept physics, now paper)"),
    (["--motion", "resolved"], "(--motion: kept averaged, now resolved)"),
])
def test_resume_with_other_settings_is_one_line_and_uses_nothing(interrupted, counted, capsys, change, fragment):
    grid = GRID[:-2] if change[0] == "--duration" else GRID
    assert main(*grid, *change, "--out", str(interrupted), "--resume") == 2
    lines = capsys.readouterr().err.splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"feedtherm: error: --resume: the interrupted sweep in "
                                                   f"{interrupted / PARTIAL_DIR} was run with other settings "), lines
    assert fragment in lines[0]
    assert counted["ran"] == [] and len(records(interrupted)) == 2


def test_a_larger_grid_reuses_the_points_it_shares(interrupted, counted, capsys):
    """The records are keyed by each point's inputs, not by its place in the grid."""
    grid = ["--screw-rpm", "396,700,1116", *GRID[2:]]
    assert main(*grid, "--out", str(interrupted), "--resume") == 0
    summary, *warning = capsys.readouterr().out.rstrip().splitlines()
    assert summary.endswith("; resumed 2 of 6 points, ran 4")
    assert warning == []  # every point of this grid within the motors' rating
    assert len(counted["ran"]) == 4


def test_a_failed_point_keeps_the_others_for_resume(tmp_path, monkeypatch, capsys):
    real = sweep_module._simulate
    ran = []

    def failing_once(run, progress=None):
        ran.append(run.label)
        if len(ran) == 3:
            raise RuntimeError("solver diverged")
        return real(run, progress)

    monkeypatch.setattr(sweep_module, "_simulate", failing_once)
    out = tmp_path / "out"
    assert main(*GRID, "--out", str(out)) == 1
    assert len(records(out)) == 3
    capsys.readouterr()
    ran.clear()
    assert main(*GRID, "--out", str(out), "--resume") == 0
    assert len(ran) == 1 and "resumed 3 of 4 points, ran 1" in capsys.readouterr().out
    assert not (out / PARTIAL_DIR).exists()


def test_a_kept_record_is_the_row_of_its_point(interrupted):
    """What a record holds: its key, and the row of the CSV as numbers."""
    document = json.loads(records(interrupted)[0].read_text())
    assert document["format"] == 1 and records(interrupted)[0].name == f"{document['key']}.json"
    assert list(document["row"])[:3] == ["screw_rpm", "nut_rpm", "ambient_C"]
    settings = json.loads((interrupted / PARTIAL_DIR / SETTINGS_JSON).read_text())
    assert {k: settings[k] for k in ("mode", "duration_s", "motion")} == {"mode": "physics", "duration_s": 1800.0,
                                                                         "motion": "averaged"}


def test_kept_rows_are_not_run_and_count_as_done_in_the_progress():
    from feedtherm.analysis.sweep import parse_grid, run_sweep
    from feedtherm.system.load import load_system

    loaded = load_system("paper")
    grid = parse_grid("396,1116", "360", "20")
    rows = run_sweep(loaded, grid, duration=1800)
    seen, kept = [], []
    again = run_sweep(loaded, grid, duration=1800, known={0: rows[0]}, progress=seen.append,
                      on_row=lambda index, row: kept.append((index, row)))
    assert again == rows
    assert kept == [(1, rows[1])]  # only the point that ran is handed on to be kept
    assert seen[0] == 0.5 and seen[-1] == 1.0 and seen == sorted(seen)
