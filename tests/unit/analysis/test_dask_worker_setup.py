"""A local cluster's worker: drops the heartbeat failure a closing cluster causes, keeps every other record."""

import logging

from feedtherm.analysis import dask_worker


class Kept(logging.Handler):
    """Collects the records that reach it (on the logger itself: Dask's loggers may not propagate)."""

    def __init__(self):
        super().__init__(logging.DEBUG)
        self.messages = []

    def emit(self, record):
        self.messages.append(record.getMessage())


def test_the_heartbeat_failure_at_close_is_dropped_and_other_errors_are_kept(monkeypatch):
    monkeypatch.setattr(dask_worker.signal, "signal", lambda *args: None)  # leave this process's Ctrl-C alone
    logger = logging.getLogger("distributed.worker")
    filters, level, disabled = list(logger.filters), logger.level, logger.disabled
    kept = Kept()
    logger.addHandler(kept)
    logger.setLevel(logging.INFO)
    logger.disabled = False
    try:
        dask_worker.dask_setup(None)
        dask_worker.dask_setup(None)  # a second call adds no second filter
        assert sum(isinstance(f, dask_worker.DropHeartbeatAfterClose) for f in logger.filters) == 1
        try:
            raise OSError("Stream is closed")
        except OSError:
            logger.exception("Failed to communicate with scheduler during heartbeat.")
        logger.error("Compute Failed")
        logger.info("Stopping worker")
        assert kept.messages == ["Compute Failed", "Stopping worker"]
    finally:
        logger.removeHandler(kept)
        logger.filters[:] = filters
        logger.setLevel(level)
        logger.disabled = disabled
