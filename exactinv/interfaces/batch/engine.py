"""``exactinv batch``: a corpus of problems (or oracle rows) through Dask
distributed, results streamed to a JSON-lines file.

The scheduling is Dask's: by default a ``LocalCluster`` with one
single-threaded worker process per core of this machine; with ``scheduler``
an existing Dask cluster (``dask scheduler`` / ``dask worker``, dask-jobqueue,
dask-kubernetes; docs/scale.md).  Each task runs on a worker in a forked
child under the per-task time and memory limits (:mod:`.sandbox`), so a
runaway problem is stopped and recorded and the batch goes on.

Resumable: ids already in ``out`` are skipped, and every record is written
and flushed the moment it arrives, so an interrupted batch loses at most the
tasks in flight.

Dask is an optional extra (``pip install "exactinv[batch]"``), imported only
when a batch actually runs.
"""

from __future__ import annotations

import contextlib
import itertools
import json
import logging
import math
import os
import sys
import time
from typing import Any, Sequence, TextIO

from ...core.scalars import to_rational
from ...errors import InvalidInput
from ..files import check_writable
from .corpus import Task, done_ids, read_corpus
from .summary import BatchSummary, Tally
from .task import Limits, engine_version, run_task

__all__ = ["run_batch"]

_WINDOW = 4  # tasks in flight per worker thread: enough to keep workers busy, few enough to scale to 10^5 tasks
_CONNECT_TIMEOUT = "30s"  # to reach an existing scheduler
_RECOUNT = 2.0  # seconds between counts of the worker threads (a cluster may grow, e.g. SLURM jobs starting)


def run_batch(inputs: Sequence[str | os.PathLike], out: str | os.PathLike, *, workers: int | None = None,
              scheduler: str | None = None, timeout: float | None = None, memory_mb: float | None = None,
              check: bool = True, tolerance: str = "1e-9", progress: bool | None = None) -> BatchSummary:
    """Certify every problem (judge every oracle row) of ``inputs`` -- problem
    directories, ``.json``, ``.jsonl`` or oracle ``.csv`` files
    (:mod:`.corpus`) -- and append one JSON record per task to ``out``,
    skipping ids already there.  ``workers``: local worker processes (default:
    every core); ``scheduler``: the address of an existing Dask scheduler
    instead.  ``timeout`` (seconds) and ``memory_mb`` limit each task;
    ``check`` runs the trusted kernel on every certificate.  ``progress``: a
    progress bar on stderr (default: when stderr is a terminal).  Every value
    in ``out`` is exact (see :mod:`.task`).

    >>> import os, tempfile
    >>> corpus = tempfile.mkdtemp()
    >>> with open(os.path.join(corpus, "box.json"), "w") as fh:
    ...     _ = fh.write('{"system": {"A": [[-1]]}, "polyhedron": {"G": [[1], [-1]], "b": [1, 1]}}')
    >>> out = os.path.join(corpus, "results.jsonl")
    >>> with open(out, "w") as fh:  # as if an earlier run had done it
    ...     _ = fh.write('{"id": "box.json", "status": "ok"}\\n')
    >>> summary = run_batch([corpus], out, progress=False)
    >>> summary.total, summary.skipped, summary.ran
    (1, 1, 0)
    >>> run_batch([corpus], out, workers=0)
    Traceback (most recent call last):
    ...
    exactinv.errors.InvalidInput: workers: expected a positive integer, got 0
    """
    limits = _limits(timeout, memory_mb, check, tolerance)
    workers = _workers(workers, scheduler)
    out = os.fspath(out) if isinstance(out, (str, os.PathLike)) else out
    _check_out(out)
    tasks = read_corpus(inputs)
    done = done_ids(out)
    todo = [t for t in tasks if t.id not in done]
    tally, start = Tally(), time.monotonic()
    threads = 0
    if todo:
        bar = _Bar(len(todo), sys.stderr if (progress if progress is not None else sys.stderr.isatty()) else None)
        threads = _run(_dask(), todo, limits, workers, scheduler, out, tally, bar)
        bar.close()
    return tally.summary(str(out), len(tasks), len(tasks) - len(todo), time.monotonic() - start, threads)


def _limits(timeout: Any, memory_mb: Any, check: Any, tolerance: Any) -> Limits:
    for name, value in (("timeout", timeout), ("memory_mb", memory_mb)):
        if value is not None and (isinstance(value, bool) or not isinstance(value, (int, float))
                                  or not 0 < value < math.inf):
            raise InvalidInput(f"{name}: expected a positive finite number (or None for no limit), got {value!r}")
    if not isinstance(check, bool):
        raise InvalidInput(f"check: expected True or False, got {check!r}")
    if to_rational(tolerance, "tolerance") < 0:
        raise InvalidInput(f"tolerance: must be >= 0, got {tolerance}")
    return Limits(timeout, memory_mb, check, str(tolerance))


def _workers(workers: Any, scheduler: Any) -> int | None:
    if scheduler is not None and workers is not None:
        raise InvalidInput("workers: give either workers (a local cluster) or scheduler (an existing one), not both")
    if scheduler is not None and not (isinstance(scheduler, str) and scheduler):
        raise InvalidInput(f"scheduler: expected an address such as tcp://10.0.0.1:8786, got {scheduler!r}")
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 1):
        raise InvalidInput(f"workers: expected a positive integer, got {workers!r}")
    return workers


def _check_out(out: Any) -> None:
    if not isinstance(out, str) or not out:
        raise InvalidInput(f"out: expected a file name for the results (JSON lines), got {out!r}")
    check_writable(out, "out", "results.jsonl")


def _end_torn_line(path: str, sink: TextIO) -> None:
    """Start on a fresh line if an interrupted run left a torn last line (it then counts as not done)."""
    if sink.tell() > 0:
        with open(path, "rb") as fh:
            fh.seek(-1, os.SEEK_END)
            if fh.read(1) != b"\n":
                sink.write("\n")


def _dask() -> Any:
    """The module dask.distributed, or InvalidInput saying how to install it."""
    try:
        import dask.distributed
    except ImportError:
        raise InvalidInput('exactinv batch needs Dask distributed: pip install "exactinv[batch]" '
                           '(or pip install "dask[distributed]")') from None
    return dask.distributed


def _run(dask: Any, todo: list[Task], limits: Limits, workers: int | None, scheduler: str | None,
         out: str, tally: Tally, bar: "_Bar") -> int:
    """Submit ``todo`` to Dask, about ``_WINDOW`` tasks per worker thread in flight (re-counted as
    workers join or leave), append each record to ``out`` as it comes; the most worker threads seen."""
    client, cluster = _connect(dask, workers, scheduler)
    stack = contextlib.ExitStack()
    try:
        _same_engine(client)
        sink = stack.enter_context(open(out, "a", encoding="utf-8"))
        _end_torn_line(out, sink)
        pending, futures, stream = iter(todo), {}, dask.as_completed()
        threads, counted = _threads(client), time.monotonic()
        most = threads

        def top_up() -> None:
            for task in itertools.islice(pending, max(max(threads, 1) * _WINDOW - len(futures), 0)):
                future = client.submit(run_task, task, limits, pure=False)
                futures[future] = task
                stream.add(future)

        top_up()
        for future in stream:
            record = _record(future, futures.pop(future))
            sink.write(json.dumps(record) + "\n")
            sink.flush()
            tally.add(record)
            bar.step(record["status"])
            if time.monotonic() - counted > _RECOUNT:
                threads, counted = _threads(client), time.monotonic()
                most = max(most, threads)
            top_up()
        return most
    finally:
        stack.close()
        client.close()
        if cluster is not None:
            cluster.close()


def _threads(client: Any) -> int:
    return sum(client.nthreads().values())


def _record(future: Any, task: Task) -> dict:
    try:
        return future.result()
    except Exception as exc:  # the worker itself died or the task could not be shipped: recorded, never fatal
        return {"id": task.id, "kind": task.kind, "source": task.source, "status": "error",
                "error": f"the Dask worker failed: {type(exc).__name__}: {exc}", "seconds": 0.0, "peak_mb": 0.0}


def _connect(dask: Any, workers: int | None, scheduler: str | None) -> tuple[Any, Any]:
    """A Dask client: to ``scheduler``, or to a new LocalCluster (closed by the caller)."""
    if scheduler is not None:
        try:
            return dask.Client(scheduler, timeout=_CONNECT_TIMEOUT), None
        except (OSError, TimeoutError, ValueError) as exc:
            raise InvalidInput(f"scheduler: cannot connect to {scheduler} ({exc})") from None
    cluster = dask.LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1, processes=True,
                                dashboard_address=None, silence_logs=logging.ERROR)
    return dask.Client(cluster), cluster


def _same_engine(client: Any) -> None:
    """Import exactinv on every worker now (in its main thread) and refuse workers with another version."""
    mine = engine_version()
    other = {addr: v for addr, v in client.run(engine_version).items() if v != mine}
    if other:
        addr, version = next(iter(other.items()))
        raise InvalidInput(f"scheduler: the worker {addr} runs exactinv {version}, this machine {mine}; "
                           "install the same version everywhere")


class _Bar:
    """A one-line progress bar with counts by status, rate and time left; silent without a stream."""

    def __init__(self, total: int, stream: TextIO | None):
        self.total, self.stream, self.done = total, stream, 0
        self.counts: dict[str, int] = {}
        self.start = self.shown = time.monotonic()

    def step(self, status: str) -> None:
        self.done += 1
        self.counts[status] = self.counts.get(status, 0) + 1
        now = time.monotonic()
        if self.stream is not None and (now - self.shown > 0.2 or self.done == self.total):
            self.shown = now
            rate = self.done / max(now - self.start, 1e-9)
            filled = 30 * self.done // self.total
            counts = " ".join(f"{k} {v}" for k, v in sorted(self.counts.items()))
            print(f"\r[{'#' * filled}{'.' * (30 - filled)}] {self.done}/{self.total}  {counts}  "
                  f"{rate:.1f}/s  ETA {(self.total - self.done) / rate:.0f} s ", end="", file=self.stream, flush=True)

    def close(self) -> None:
        if self.stream is not None:
            print(file=self.stream, flush=True)
