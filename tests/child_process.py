"""Commands run in a child process by the integration tests: the environment they get, and a
bounded wait for them (pytest puts the directory of tests/conftest.py on sys.path)."""

import os
import subprocess


def environment() -> dict:
    """The suite's environment (its PYTHONPATH names this feedtherm), without a scheduler of the user's."""
    return {k: v for k, v in os.environ.items() if k != "DASK_SCHEDULER_ADDRESS"}


def finish(process: subprocess.Popen, timeout: float) -> tuple[int, str, str]:
    """``(exit code, stdout, stderr)`` of ``process``; killed (and the test failed) after ``timeout`` s."""
    try:
        out, err = process.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        process.kill()
        process.communicate()
        raise
    return process.returncode, out, err
