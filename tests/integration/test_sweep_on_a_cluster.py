"""A sweep on an existing Dask cluster: a scheduler and two worker processes on 127.0.0.1, as a
user would start them (`dask scheduler`, `dask worker`), reached through `--scheduler`.

The cluster's processes are killed in the fixture's teardown, whatever the tests did; every wait
is bounded.
"""

import os
import signal
import socket
import subprocess
import sys
import time

import pytest

from child_process import environment
from child_process import finish as finish_within

# Six runs of about half a second: long enough that a worker can be killed mid-batch.
GRID = ["--screw-rpm", "396,1116,2214", "--nut-rpm", "360", "--ambient", "20,25", "--duration", "7200"]
START_TIMEOUT_S = 60
WAIT_S = 180


def free_port():
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


@pytest.fixture(scope="module")
def cluster(tmp_path_factory):
    """``(address, {name: worker process})``: a scheduler and two one-thread workers without nannies
    (a killed worker stays dead, as when its machine goes away)."""
    distributed = pytest.importorskip("distributed")
    cwd = tmp_path_factory.mktemp("cluster")  # the workers' scratch space
    address = f"tcp://127.0.0.1:{free_port()}"
    processes = []
    common = {"cwd": cwd, "env": environment(), "stdout": subprocess.DEVNULL, "stderr": subprocess.DEVNULL}
    try:
        processes.append(subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_scheduler", "--host",
                                           "127.0.0.1", "--port", address.rsplit(":", 1)[1], "--no-dashboard"],
                                          **common))
        workers = {}
        for name in ("w1", "w2"):
            workers[name] = subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_worker", address, "--name",
                                              name, "--nthreads", "1", "--no-nanny", "--host", "127.0.0.1",
                                              "--no-dashboard"], **common)
            processes.append(workers[name])
        with distributed.Client(address, timeout=START_TIMEOUT_S, set_as_default=False) as client:
            client.wait_for_workers(2, timeout=START_TIMEOUT_S)
        yield address, workers
    finally:
        for process in processes:
            if process.poll() is None:
                process.kill()
        for process in processes:
            process.wait(timeout=30)


def sweep(cwd, *args):
    return subprocess.Popen([sys.executable, "-m", "feedtherm", "sweep", *GRID, *args], cwd=cwd, env=environment(),
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def finish(process):
    return finish_within(process, WAIT_S)


@pytest.fixture(scope="module")
def serial_csv(tmp_path_factory):
    cwd = tmp_path_factory.mktemp("serial")
    code, _, err = finish(sweep(cwd, "--out", "serial"))
    assert code == 0, err
    return (cwd / "serial" / "sweep.csv").read_bytes()


def test_a_sweep_through_scheduler_is_the_serial_sweep(cluster, serial_csv, tmp_path):
    address, _ = cluster
    code, out, err = finish(sweep(tmp_path, "--out", "cluster", "--scheduler", address))
    assert code == 0, err
    assert err == ""
    assert out.startswith("cluster: sweep of 6 points written in ")
    assert (tmp_path / "cluster" / "sweep.csv").read_bytes() == serial_csv


def test_the_dask_variable_names_the_scheduler(cluster, serial_csv, tmp_path):
    address, _ = cluster
    process = subprocess.Popen([sys.executable, "-m", "feedtherm", "sweep", *GRID, "--out", "env"], cwd=tmp_path,
                               env={**environment(), "DASK_SCHEDULER_ADDRESS": address},
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    code, _, err = finish(process)
    assert code == 0, err
    assert (tmp_path / "env" / "sweep.csv").read_bytes() == serial_csv


def test_a_worker_killed_mid_batch_loses_nothing(cluster, serial_csv, tmp_path):
    """SIGKILL to a worker while it runs a point: the scheduler gives the point to the other
    worker, and the CSV is the serial one.  (Last in this module: it leaves one worker.)"""
    import distributed

    address, workers = cluster
    process = sweep(tmp_path, "--out", "killed", "--scheduler", address)
    killed = None
    try:
        with distributed.Client(address, timeout=START_TIMEOUT_S, set_as_default=False) as client:
            names = {info["name"]: addr for addr, info in client.scheduler_info()["workers"].items()}
            deadline = time.monotonic() + 60
            while killed is None and time.monotonic() < deadline and process.poll() is None:
                busy = client.processing()
                for name in ("w1", "w2"):
                    if busy.get(names[name]):  # this worker holds a run of the sweep now
                        os.kill(workers[name].pid, signal.SIGKILL)
                        killed = name
                        break
                else:
                    time.sleep(0.02)
    finally:
        code, _, err = finish(process)
    assert killed is not None, "no worker was seen running a point"
    assert code == 0, err
    assert (tmp_path / "killed" / "sweep.csv").read_bytes() == serial_csv
