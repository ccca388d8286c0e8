"""The execution layer of batches: the choice of executor, results in input order, failures kept."""

import math
import sys
import time

import pytest

from feedtherm.analysis.execution import Execution, TaskFailure, resolve_execution, run_ordered
from feedtherm.errors import FeedthermError, Terminated

# --------------------------------------------------------------------------- choosing


def test_serial_is_the_default_and_one_worker_is_serial():
    assert resolve_execution(environ={}) == Execution()
    assert resolve_execution(1, environ={}).serial
    assert resolve_execution(3, environ={}) == Execution(workers=3)


def test_the_scheduler_address_comes_from_the_option_or_the_dask_variable():
    assert resolve_execution(scheduler="tcp://127.0.0.1:8786", environ={}) == Execution(scheduler="tcp://127.0.0.1:8786")
    env = {"DASK_SCHEDULER_ADDRESS": "127.0.0.1:8786"}
    assert resolve_execution(environ=env) == Execution(scheduler="127.0.0.1:8786")
    # an explicit --workers wins over the environment
    assert resolve_execution(2, environ=env) == Execution(workers=2)
    assert resolve_execution(1, environ=env).serial


@pytest.mark.parametrize("workers, scheduler, env, fragment", [
    (0, None, {}, "--workers: must be a positive whole number, got 0"),
    (2, "127.0.0.1:8786", {}, "--workers and --scheduler: give one"),
    (None, "localhost", {}, "--scheduler: 'localhost' is not a scheduler address"),
    (None, "tcp://127.0.0.1:99999", {}, "is not a scheduler address"),
    (None, "http://127.0.0.1:8786", {}, "is not a scheduler address"),
    (None, None, {"DASK_SCHEDULER_ADDRESS": "nowhere"}, "DASK_SCHEDULER_ADDRESS: 'nowhere' is not"),
])
def test_bad_choices_are_one_line(workers, scheduler, env, fragment):
    with pytest.raises(FeedthermError) as info:
        resolve_execution(workers, scheduler, environ=env)
    assert fragment in str(info.value) and "\n" not in str(info.value)


# --------------------------------------------------------------------------- running


def slow_square(x):
    """Earlier inputs take longer, so two workers finish them out of order."""
    time.sleep(0.05 * (4 - x) if x < 4 else 0.0)
    if x == 2:
        raise ValueError(f"no square of {x} today")
    return x * x


def test_serial_results_in_order_with_a_failure_in_its_place():
    seen = []
    results = list(run_ordered(math.sqrt, [4.0, -1.0, 9.0], describe=lambda x: f"x = {x:g}", progress=seen.append))
    assert [index for index, _ in results] == [0, 1, 2]
    assert results[0][1] == 2.0 and results[2][1] == 3.0
    failure = results[1][1]
    assert isinstance(failure, TaskFailure) and failure.index == 1
    assert str(failure) == "x = -1: ValueError: math domain error"
    assert seen == pytest.approx([1 / 3, 2 / 3, 1.0])


def _inside_a_serialiser(kind):
    """A task that pydantic-core interrupts as it does when ``kind`` (Ctrl-C's KeyboardInterrupt, or the
    CLI's SIGTERM handler's Terminated) lands in a wrap serialiser: its error names the class, no chain."""
    from pydantic_core import PydanticSerializationError

    def task(item):
        if item == "b":
            raise PydanticSerializationError(f"Error calling function `serialise`: {kind.__name__}")
        return item

    return task


def _chained(kind):
    """A task whose library catches ``kind`` and raises its own error from it."""

    def task(item):
        try:
            raise kind
        except kind as exc:
            raise RuntimeError("a library caught the interruption and raised its own error") from exc

    return task


@pytest.mark.parametrize("kind", [KeyboardInterrupt, Terminated], ids=["ctrl-c", "sigterm"])
@pytest.mark.parametrize("form", [_inside_a_serialiser, _chained])
def test_an_interruption_that_a_library_reports_as_its_own_error_stops_the_serial_batch_as_itself(kind, form):
    """The interruption is raised again of its own kind: after a SIGTERM the CLI then says the run was
    terminated and exits 143, not 130 as after Ctrl-C (a sweep's SIGTERM test saw 130 once, with the
    signal inside a library's call)."""
    done = []
    with pytest.raises(KeyboardInterrupt) as stopped:
        for _, result in run_ordered(form(kind), ["a", "b", "c"], on_done=lambda i, r: done.append(r)):
            pass
    assert type(stopped.value) is kind
    assert all(not isinstance(r, TaskFailure) for r in done)  # no run was counted as failed


def test_a_serialisers_own_error_or_a_mention_of_the_word_is_a_failed_run():
    from pydantic_core import PydanticSerializationError

    def unserialisable(item):
        raise PydanticSerializationError("Unable to serialize unknown type: <class 'object'>")

    def mentions(item):
        raise ValueError("KeyboardInterrupt is only a word here")

    for task in (unserialisable, mentions):
        assert isinstance(list(run_ordered(task, ["a"]))[0][1], TaskFailure)


def test_serial_passes_each_run_its_share_of_the_progress():
    seen = []

    def task(item, progress=None):
        progress(0.5)
        return item

    assert [r for _, r in run_ordered(task, ["a", "b"], progress=seen.append, passes_progress=True)] == ["a", "b"]
    assert seen == pytest.approx([0.25, 0.5, 0.75, 1.0])


def test_an_empty_batch_yields_nothing():
    assert list(run_ordered(math.sqrt, [], execution=Execution(workers=2))) == []


@pytest.fixture
def by_value():
    """Workers cannot import this test module by name: its functions travel by value."""
    import cloudpickle

    module = sys.modules[__name__]
    cloudpickle.register_pickle_by_value(module)
    yield
    cloudpickle.unregister_pickle_by_value(module)


def test_two_local_workers_give_the_serial_results_in_the_same_order(by_value):
    items = [0, 1, 2, 3, 4, 5]
    serial = list(run_ordered(slow_square, items, describe=lambda x: f"x = {x}"))
    seen = []
    parallel = list(run_ordered(slow_square, items, execution=Execution(workers=2), describe=lambda x: f"x = {x}",
                                progress=seen.append))
    assert parallel == serial
    assert [i for i, _ in parallel] == items
    assert parallel[2][1] == TaskFailure(2, "x = 2", "ValueError: no square of 2 today")
    assert [r for i, r in parallel if i != 2] == [0, 1, 9, 16, 25]
    assert seen == pytest.approx([k / 6 for k in range(1, 7)])  # the bar moves as runs finish


def _free_port() -> int:
    import socket

    with socket.socket() as probe:  # a free port on which nothing listens
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def test_a_scheduler_address_that_refuses_is_one_line_at_once(monkeypatch):
    import distributed

    def no_client(*args, **kwargs):  # Dask's client would retry for CONNECT_TIMEOUT_S first
        raise AssertionError("the client was asked to connect to an address that refuses")

    monkeypatch.setattr(distributed, "Client", no_client)
    port = _free_port()
    with pytest.raises(FeedthermError, match=f"cannot reach the Dask scheduler at tcp://127.0.0.1:{port} "
                                             r"\(the connection was refused: nothing listens there\)"):
        list(run_ordered(math.sqrt, [1.0], execution=Execution(scheduler=f"tcp://127.0.0.1:{port}")))


def test_a_scheduler_that_does_not_answer_is_one_line_after_the_timeout(monkeypatch):
    from feedtherm.analysis import execution

    monkeypatch.setattr(execution, "CONNECT_TIMEOUT_S", 2)
    monkeypatch.setattr(execution, "_refused", lambda address: None)  # as a host that drops the packets
    port = _free_port()
    with pytest.raises(FeedthermError, match=f"cannot reach the Dask scheduler at tcp://127.0.0.1:{port} within 2 s"):
        list(run_ordered(math.sqrt, [1.0], execution=Execution(scheduler=f"tcp://127.0.0.1:{port}")))


def test_on_done_sees_each_result_before_it_is_yielded(by_value):
    """Serially in input order; on two workers in the order they finish, each once, and always
    before the result is yielded (a result waiting for an earlier one is already kept)."""
    seen = []
    list(run_ordered(slow_square, [0, 1, 3], describe=str, on_done=lambda i, r: seen.append((i, r))))
    assert seen == [(0, 0), (1, 1), (2, 9)]
    events = []
    for index, result in run_ordered(slow_square, [0, 4, 5], execution=Execution(workers=2),
                                     on_done=lambda i, r: events.append(("done", i, r))):
        events.append(("yielded", index, result))
    assert sorted(e for e in events if e[0] == "done") == [("done", 0, 0), ("done", 1, 16), ("done", 2, 25)]
    assert [e for e in events if e[0] == "yielded"] == [("yielded", 0, 0), ("yielded", 1, 16), ("yielded", 2, 25)]
    for index in range(3):
        assert events.index(("done", index, index and (index + 3) ** 2)) < events.index(
            ("yielded", index, index and (index + 3) ** 2))


def test_a_cluster_kept_open_serves_many_batches(by_value):
    from feedtherm.analysis.execution import kept_open

    with kept_open(Execution(workers=2)) as running:
        client = running.client
        assert not running.serial and running == Execution(workers=2)
        first = list(run_ordered(slow_square, [3, 4], execution=running))
        assert client.status == "running"  # the batch left the cluster up
        second = list(run_ordered(slow_square, [5], execution=running))
        workers = set(client.scheduler_info()["workers"])
        assert len(workers) == 2
    assert (first, second) == ([(0, 9), (1, 16)], [(0, 25)])
    assert client.status == "closed"
    with kept_open(Execution()) as running:
        assert running == Execution() and running.client is None


def _environment(names: tuple[str, ...]) -> dict[str, str | None]:
    import os

    return {name: os.environ.get(name) for name in names}


def test_local_workers_keep_dasks_thread_limits_but_not_its_malloc_trim(by_value, monkeypatch):
    """Dask's MALLOC_TRIM_THRESHOLD_ fixes glibc's mmap threshold: a reduced model's run in such a
    worker took twice its time (execution.UNSET_WORKER_ENVIRONMENT)."""
    import os

    monkeypatch.delenv("MALLOC_TRIM_THRESHOLD_", raising=False)
    for name in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
        monkeypatch.delenv(name, raising=False)
    names = ("MALLOC_TRIM_THRESHOLD_", "OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS")
    [(_, seen)] = list(run_ordered(_environment, [names], execution=Execution(workers=2)))
    assert seen == {"MALLOC_TRIM_THRESHOLD_": None, "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1"}
    assert "MALLOC_TRIM_THRESHOLD_" not in os.environ  # nor is this process's environment given it
