"""What every worker process of a local cluster does when it starts (Dask's ``preload``).

Ctrl-C in a terminal sends SIGINT to the whole process group: to feedtherm, and to the worker
processes its local cluster started.  Feedtherm stops the batch and shuts the cluster down
cleanly; a worker that took the signal itself would die on its own and print Dask's tracebacks.
So a worker ignores SIGINT and ends when its cluster is closed.

When the cluster closes, a worker's heartbeat can still be on its way to the scheduler that
just stopped; Dask then logs "Failed to communicate with scheduler during heartbeat." at ERROR
level, with a traceback, although nothing failed (dask/distributed#7105, open).  A worker drops
that one message; a run that fails still comes back to feedtherm through its future, with its
inputs, whatever the worker logs.

Dask imports this module by name in each worker and calls :func:`dask_setup` there; importing
it anywhere else changes nothing.
"""

import logging
import signal
import threading

#: The start of the message a closing cluster's worker logs for a heartbeat that found no scheduler.
HEARTBEAT_AFTER_CLOSE = "Failed to communicate with scheduler during heartbeat"


class DropHeartbeatAfterClose(logging.Filter):
    """Drops the worker's heartbeat failure record (see the module's docstring); passes the rest."""

    def filter(self, record: logging.LogRecord) -> bool:
        return not str(record.msg).startswith(HEARTBEAT_AFTER_CLOSE)


def dask_setup(worker) -> None:
    """Called by Dask in a new worker process: ignore SIGINT, drop the heartbeat failure at close."""
    if threading.current_thread() is threading.main_thread():  # where Python allows handlers
        signal.signal(signal.SIGINT, signal.SIG_IGN)
    logger = logging.getLogger("distributed.worker")
    if not any(isinstance(f, DropHeartbeatAfterClose) for f in logger.filters):
        logger.addFilter(DropHeartbeatAfterClose())
