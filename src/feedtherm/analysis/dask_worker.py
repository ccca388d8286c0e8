"""What every worker process of a local cluster does when it starts (Dask's ``preload``).

Ctrl-C in a terminal sends SIGINT to the whole process group: to feedtherm, and to the worker
processes its local cluster started.  Feedtherm stops the batch and shuts the cluster down
cleanly; a worker that took the signal itself would die on its own and print Dask's tracebacks.
So a worker ignores SIGINT and ends when its cluster is closed.

Dask imports this module by name in each worker and calls :func:`dask_setup` there; importing
it anywhere else changes nothing.
"""

import signal
import threading


def dask_setup(worker) -> None:
    """Called by Dask in a new worker process: ignore SIGINT (see the module's docstring)."""
    if threading.current_thread() is threading.main_thread():  # where Python allows handlers
        signal.signal(signal.SIGINT, signal.SIG_IGN)
