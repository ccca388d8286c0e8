"""A local cluster's worker: drops the heartbeat failure a closing cluster causes, keeps every other record."""

import logging

from feedtherm.analysis import dask_worker


def test_the_heartbeat_failure_at_close_is_dropped_and_other_errors_are_kept(monkeypatch, caplog):
    monkeypatch.setattr(dask_worker.signal, "signal", lambda *args: None)  # leave this process's Ctrl-C alone
    logger = logging.getLogger("distributed.worker")
    before = list(logger.filters)
    try:
        dask_worker.dask_setup(None)
        dask_worker.dask_setup(None)  # a second call adds no second filter
        assert sum(isinstance(f, dask_worker.DropHeartbeatAfterClose) for f in logger.filters) == 1
        with caplog.at_level(logging.INFO, logger="distributed.worker"):
            try:
                raise OSError("Stream is closed")
            except OSError:
                logger.exception("Failed to communicate with scheduler during heartbeat.")
            logger.error("Compute Failed")
            logger.info("Stopping worker")
        assert [r.getMessage() for r in caplog.records] == ["Compute Failed", "Stopping worker"]
    finally:
        logger.filters[:] = before
