"""Hostile and careless input, one module per kind of file a user hands over (``test_<kind>.py``:
law files, descriptions' geometry, ``feedtherm new``'s name and target, measurement files,
command-line values).  A new kind of file gets a module of its own.

Every case is refused as every command refuses bad input: one line naming the file or field and the reason,
exit 2, no traceback, nothing written (:func:`refused`); or, where the input is possible but
suspect, it runs with a warning that names the field (:func:`warned`).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from feedtherm import cli


def _files(folder: Path) -> set[str]:
    return {str(p.relative_to(folder)) for p in folder.rglob("*")}


@pytest.fixture
def refused(tmp_path, monkeypatch, capsys):
    """``refused(*argv, says=(...))``: runs ``feedtherm argv`` in ``tmp_path`` (in this process, so an
    uncaught exception fails the test as a traceback would) and checks exit 2, one line on stderr
    holding every fragment of ``says``, and no file created under ``tmp_path``; returns the line."""

    def check(*argv: str, says: tuple[str, ...] = ()) -> str:
        monkeypatch.chdir(tmp_path)
        before = _files(tmp_path)
        code = cli.main([str(a) for a in argv])
        out, err = capsys.readouterr()
        lines = [line for line in err.splitlines() if line.strip()]
        assert code == 2, (code, out, err)
        assert len(lines) == 1, err
        assert "Traceback" not in err
        for fragment in says:
            assert fragment in lines[0], (fragment, lines[0])
        created = _files(tmp_path) - before
        assert not created, f"written although refused: {sorted(created)}"
        return lines[0]

    return check


@pytest.fixture
def warned(tmp_path, monkeypatch, capsys):
    """``warned(*argv, says=(...))``: runs ``feedtherm argv`` in ``tmp_path``; checks exit 0 and a
    warning line holding every fragment of ``says``; returns stdout and stderr together."""

    def check(*argv: str, says: tuple[str, ...] = ()) -> str:
        monkeypatch.chdir(tmp_path)
        code = cli.main([str(a) for a in argv])
        out, err = capsys.readouterr()
        text = out + err
        assert code == 0, (code, text)
        assert "Traceback" not in text
        assert any(all(f in line for f in says) for line in text.splitlines()), text
        return text

    return check
