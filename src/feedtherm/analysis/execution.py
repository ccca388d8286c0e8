"""Where the independent runs of a batch execute: here, one after another (the default), on a
local Dask cluster of worker processes (``--workers N``), or on an existing Dask scheduler
(``--scheduler ADDRESS``, or the ``DASK_SCHEDULER_ADDRESS`` variable Dask itself reads).

:func:`run_ordered` is the one loop: it yields each task's result **in the order of its
inputs**, whatever order the workers finish in, so a batch run in parallel gives the same rows
in the same order as the serial run (every task is the same deterministic function of its
inputs, wherever it runs).  A task that raises does not stop the others: its place in the
sequence holds a :class:`TaskFailure` naming its inputs.

Dask is imported only when a batch really runs on a cluster: the CLI's start-up stays fast and
a serial batch never needs it.
"""

from __future__ import annotations

import contextlib
import logging
import os
import re
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field, replace

from ..errors import FeedthermError, Terminated
from . import dask_worker

#: The variable Dask's own tools read for the scheduler's address.
SCHEDULER_ENV = "DASK_SCHEDULER_ADDRESS"
#: How long to try reaching a scheduler before giving up [s] (Dask's default is 30 s; an address
#: with a typo should fail sooner).
CONNECT_TIMEOUT_S = 10
#: Workers of a local cluster listen here only: nothing of a run leaves the machine.
LOCAL_HOST = "127.0.0.1"
#: What a local cluster's workers are started without of Dask's pre-spawn environment
#: (``distributed.nanny.pre-spawn-environ``; its thread limits stay).  Dask sets
#: ``MALLOC_TRIM_THRESHOLD_`` so that a worker hands freed memory back to the system at once; glibc
#: then also stops raising its mmap threshold, so every array above 128 kB is mapped and unmapped
#: anew, page by page.  A reduced model's run, which makes a few thousand r × r arrays, took twice
#: its time in such a worker (0.50 s against 0.25 s; benchmarks/README.md).
UNSET_WORKER_ENVIRONMENT = ("MALLOC_TRIM_THRESHOLD_",)

# tcp://host:port, tls://host:port or host:port (IPv6 hosts in brackets).
_ADDRESS = re.compile(r"(?:(?:tcp|tls)://)?(?:\[[0-9A-Fa-f:.]+\]|[A-Za-z0-9_.-]+):(\d{1,5})")


@dataclass(frozen=True)
class Execution:
    """Where a batch runs: ``Execution()`` is serial, in this process.

    Build it from command-line values with :func:`resolve_execution`, which checks them.
    """

    #: Worker processes of a local cluster (one thread each); None: no local cluster.
    workers: int | None = None
    #: Address of a running Dask scheduler; None: no existing cluster.
    scheduler: str | None = None
    #: A Dask client already connected (set by :func:`kept_open`): batches run on it and leave it
    #: open, instead of each starting and stopping a cluster of its own.
    client: object | None = field(default=None, compare=False, repr=False)

    @property
    def serial(self) -> bool:
        return self.workers is None and self.scheduler is None

    def describe(self) -> str:
        if self.scheduler is not None:
            return f"the Dask scheduler at {self.scheduler}"
        if self.workers is not None:
            return f"a local Dask cluster of {self.workers} worker processes"
        return "this process"


def resolve_execution(workers: int | None = None, scheduler: str | None = None,
                      environ: dict | None = None) -> Execution:
    """The execution the options ask for, checked before anything runs.

    ``--workers 1`` is serial (a cluster of one process only adds its start-up).  Without either
    option, a ``DASK_SCHEDULER_ADDRESS`` in the environment names the scheduler.

    Raises
    ------
    FeedthermError
        One line: a worker count below 1, both options at once, or an address that is not
        ``[tcp://|tls://]host:port``.
    """
    if workers is not None and workers < 1:
        raise FeedthermError(f"--workers: must be a positive whole number, got {workers}")
    if workers is not None and scheduler is not None:
        raise FeedthermError("--workers and --scheduler: give one (a local cluster of N workers, "
                             "or the address of a running scheduler)")
    source = "--scheduler"
    if workers is None and scheduler is None:
        scheduler = (os.environ if environ is None else environ).get(SCHEDULER_ENV) or None
        source = SCHEDULER_ENV
    if scheduler is not None:
        scheduler = scheduler.strip()
        match = _ADDRESS.fullmatch(scheduler)
        if match is None or not 0 < int(match.group(1)) < 65536:
            raise FeedthermError(f"{source}: {scheduler!r} is not a scheduler address such as "
                                 f"tcp://127.0.0.1:8786 or 127.0.0.1:8786")
        return Execution(scheduler=scheduler)
    return Execution(workers=workers if workers is not None and workers > 1 else None)


@dataclass(frozen=True)
class TaskFailure:
    """A task that raised: its position in the batch, its inputs as text and the error."""

    index: int
    inputs: str
    message: str

    def __str__(self) -> str:
        return f"{self.inputs}: {self.message}"


def run_ordered(function: Callable, items: Sequence, *, execution: Execution = Execution(),
                describe: Callable[[object], str] = repr, progress: Callable[[float], None] | None = None,
                passes_progress: bool = False,
                on_done: Callable[[int, object], None] | None = None) -> Iterator[tuple[int, object]]:
    """Call ``function(item)`` for every item; yield ``(index, result)`` in the order of ``items``.

    A result is a :class:`TaskFailure` where the call raised an ``Exception`` (its text from
    ``describe(item)``); the other tasks go on.  ``progress`` gets the fraction of the batch
    done (0-1).  Serially, with ``passes_progress``, ``function`` is also called with
    ``progress=`` its share of the batch, so a long single run moves the bar; on a cluster the
    bar moves as runs finish.  ``on_done(index, result)`` is called in this process as soon as
    each task finishes, in the order they finish (on a cluster a result may wait there for an
    earlier one before it is yielded): the place to keep a result on disk at once.
    ``function`` and the items must pickle when ``execution`` is not serial (a module-level
    function; workers import it by name).
    """
    if not items:
        return
    if execution.serial:
        yield from _serial(function, items, describe, progress, passes_progress, on_done)
    else:
        yield from _on_dask(function, items, execution, describe, progress, on_done)


def _serial(function, items, describe, progress, passes_progress, on_done) -> Iterator[tuple[int, object]]:
    count = len(items)
    for index, item in enumerate(items):
        kwargs = {}
        if passes_progress and progress is not None:
            kwargs["progress"] = progress_share(progress, index, count)
        try:
            result = function(item, **kwargs)
        except Exception as exc:  # one run's failure is reported with its inputs; the others go on
            kind = interruption(exc)
            if kind is not None:
                raise kind() from exc
            result = TaskFailure(index, describe(item), _message(exc))
        if on_done is not None:
            on_done(index, result)
        yield index, result
        if progress is not None:
            progress((index + 1) / count)


def interruption(exc: BaseException) -> type[KeyboardInterrupt] | None:
    """The interruption ``exc`` carries, or None: a KeyboardInterrupt (Ctrl-C) or a
    :class:`~feedtherm.errors.Terminated` (SIGTERM) in its chain, or named in the message of
    pydantic-core's serialisation error, which reports one that lands inside a wrap serialiser as
    ``PydanticSerializationError: ... KeyboardInterrupt`` and keeps no chain.  The batch stops
    then, as at any other interruption of that kind, and does not count a failed run."""
    seen: BaseException | None = exc
    while seen is not None:
        if isinstance(seen, KeyboardInterrupt):
            return type(seen)
        seen = seen.__cause__ or seen.__context__
    if type(exc).__name__ == "PydanticSerializationError":
        for kind in (Terminated, KeyboardInterrupt):  # the subclass first: a message names the class raised
            if kind.__name__ in str(exc):
                return kind
    return None


def progress_share(progress: Callable[[float], None], index: int, count: int) -> Callable[[float], None]:
    """One run's progress as its share of the whole batch."""
    return lambda fraction: progress((index + min(max(fraction, 0.0), 1.0)) / count)


def _on_dask(function, items, execution, describe, progress, on_done) -> Iterator[tuple[int, object]]:
    from distributed import as_completed

    count = len(items)
    with _client(execution) as client:
        # pure=False: two equal inputs are still two runs (and two keys), as in the serial loop.
        futures = [client.submit(function, item, pure=False) for item in items]
        index_of = {future.key: index for index, future in enumerate(futures)}
        finished: dict[int, object] = {}
        next_index = done = 0
        try:
            for future in as_completed(futures, loop=client.loop):
                index = index_of[future.key]
                if future.status == "finished":
                    finished[index] = future.result()
                else:  # "error"; "cancelled" when the scheduler lost it
                    error = future.exception() if future.status == "error" else None
                    message = _message(error) if error is not None else f"the run was {future.status} by the cluster"
                    finished[index] = TaskFailure(index, describe(items[index]), message)
                future.release()  # the result is here now: the cluster need not keep it
                if on_done is not None:
                    on_done(index, finished[index])
                done += 1
                if progress is not None:
                    progress(done / count)
                # Yield what is contiguous from the front; later results wait for earlier ones.
                while next_index in finished:
                    yield next_index, finished.pop(next_index)
                    next_index += 1
        finally:
            # An interrupted batch (Ctrl-C, an error in the caller) leaves nothing running.
            client.cancel([f for f in futures if not f.done()])


@contextlib.contextmanager
def kept_open(execution: Execution) -> Iterator[Execution]:
    """``execution`` with its cluster started (or its scheduler reached) once, for many batches.

    A calibration asks for hundreds of small batches: starting a local cluster for each would
    cost more than the runs.  Inside the block, :func:`run_ordered` with the execution this
    yields submits to the one open client; the cluster stops when the block ends (also on
    Ctrl-C).  A serial execution, or one already kept open, is yielded as it is.

    Raises
    ------
    FeedthermError
        The scheduler cannot be reached (one line), as :func:`run_ordered` would.
    """
    if execution.serial or execution.client is not None:
        yield execution
        return
    with _client(execution) as client:
        yield replace(execution, client=client)


def _refused(address: str) -> None:
    """Fail at once when nothing listens at a TCP scheduler address (the host refuses the connection):
    Dask's client would retry for :data:`CONNECT_TIMEOUT_S` first.  Other addresses, and hosts that do
    not answer at all, are left to the client and its timeout."""
    import socket
    from urllib.parse import urlsplit

    try:
        parts = urlsplit(address)
        host, port = parts.hostname, parts.port
    except ValueError:
        return
    if parts.scheme != "tcp" or host is None or port is None:
        return
    try:
        with socket.create_connection((host, port), timeout=CONNECT_TIMEOUT_S):
            return
    except ConnectionRefusedError:
        raise FeedthermError(f"cannot reach the Dask scheduler at {address} (the connection was refused: "
                             f"nothing listens there)") from None
    except OSError:
        return


@contextlib.contextmanager
def _client(execution: Execution):
    if execution.client is not None:  # kept open by the caller, who closes it
        yield execution.client
        return
    import dask
    from distributed import Client, LocalCluster

    # Dask logs connection chatter (a worker leaving, a closed stream) as warnings on stderr; a
    # feedtherm command prints one line, so only Dask's errors get through while a batch runs.
    logger = logging.getLogger("distributed")
    level = logger.level
    logger.setLevel(logging.ERROR)
    try:
        if execution.scheduler is not None:
            _refused(execution.scheduler)
            try:
                client = Client(execution.scheduler, timeout=CONNECT_TIMEOUT_S, set_as_default=False)
            except (OSError, TimeoutError) as exc:
                raise FeedthermError(f"cannot reach the Dask scheduler at {execution.scheduler} within "
                                     f"{CONNECT_TIMEOUT_S} s ({type(exc).__name__})") from None
            with client:
                yield client
        else:
            # Processes with one thread each: a run holds the GIL, and the numerical libraries
            # inside a worker stay on one thread (Dask sets OMP/MKL/OpenBLAS to 1 for its workers).
            # The workers ignore Ctrl-C (dask_worker.py): this process stops the batch and the cluster.
            # Dask's configuration drops a pre-spawn variable set to None (a variable of the user's own
            # environment still reaches the workers, as any other does)
            unset = {f"distributed.nanny.pre-spawn-environ.{name}": None for name in UNSET_WORKER_ENVIRONMENT}
            with dask.config.set(unset), \
                    LocalCluster(n_workers=execution.workers, threads_per_worker=1, processes=True, host=LOCAL_HOST,
                                 dashboard_address=None, silence_logs=logging.ERROR,
                                 preload=[dask_worker.__name__]) as cluster, \
                    Client(cluster, set_as_default=False) as client:
                yield client
    finally:
        logger.setLevel(level)


def _message(error: BaseException) -> str:
    """One line: a feedtherm error as it is; anything else with its type, which says more."""
    text = " ".join(str(error).split())
    if isinstance(error, FeedthermError):
        return text
    return f"{type(error).__name__}: {text}" if text else type(error).__name__
