"""``exactinv batch``: a corpus of problems (or oracle rows) through Dask
distributed, results streamed to a JSON-lines file.

The scheduling is Dask's: by default a ``LocalCluster`` with one
single-threaded worker process per core of this machine; with ``scheduler``
an existing Dask cluster (``dask scheduler`` / ``dask worker``, dask-jobqueue,
dask-kubernetes; docs/scale.md).  A Dask task is a chunk of problems, sized
from the durations measured so far to last about two seconds (:mod:`.chunks`);
a worker thread runs its chunks' problems one after another in one
long-lived forked sandbox, each under its own time and memory limits
(:mod:`.resident`), so a runaway problem is stopped and recorded, its
sandbox replaced, and the chunk and the batch go on.  A worker that dies
takes its chunks in flight with it; Dask runs them again elsewhere, and as a
chunk's records are written only when it comes back, none is written twice.

Resumable: ids already in ``out`` are skipped, and every record is appended
as one whole line the moment its chunk arrives (:mod:`.results`), so an
interrupted batch loses at most the chunks in flight.  Ctrl-C raises
:class:`BatchInterrupted` after a quiet shutdown: the futures are cancelled,
the cluster is closed, and the worker processes of a local cluster ignore
the signal (:func:`_connect`), so no worker prints a traceback.

Nothing the user gave is overwritten: ``out`` and every certificate of
``cert_dir`` are refused (:class:`InvalidInput`, before any work) when they
are one of the inputs, and the batch never reads its own output as a problem
(:func:`.corpus.scan_corpus`).

Dask is an optional extra (``pip install "exactinv[batch]"``), imported only
when a batch actually runs.
"""

from __future__ import annotations

import collections
import contextlib
import logging
import math
import os
import sys
import time
from typing import Any, Callable, Sequence, TextIO

from ...core.scalars import to_rational
from ...errors import InvalidInput
from ..files import atomic_write, check_writable, is_results_file, refuse_foreign, refuse_inputs
from .certdir import prepare_cert_dir
from .chunks import ChunkSizer
from .corpus import Task, scan_corpus
from .results import ResultsFile, read_records
from .signals import CtrlC, sigint_ignored
from .summary import BatchSummary, Tally
from .task import Limits, engine_version, run_chunk

__all__ = ["run_batch", "BatchInterrupted"]


class BatchInterrupted(KeyboardInterrupt):
    """Ctrl-C stopped a batch: ``done`` tasks of the corpus are recorded in ``out``
    (earlier runs' included); running the batch again does the rest."""

    def __init__(self, done: int, out: str):
        super().__init__(f"interrupted: {done} done, resumable")
        self.done, self.out = done, out

_WINDOW = 2  # chunks in flight per worker thread: one running, one queued behind it (chunks last about two seconds)
_CONNECT_TIMEOUT = "30s"  # to reach an existing scheduler
_RECOUNT = 2.0  # seconds between counts of the worker threads (a cluster may grow, e.g. SLURM jobs starting)


def run_batch(inputs: Sequence[str | os.PathLike], out: str | os.PathLike, *, workers: int | None = None,
              scheduler: str | None = None, timeout: float | None = None, memory_mb: float | None = None,
              check: bool = True, tolerance: str = "1e-9", progress: bool | None = None,
              cert_dir: str | os.PathLike | None = None,
              notice: Callable[[str], None] | None = None) -> BatchSummary:
    """Certify every problem (judge every oracle row) of ``inputs`` -- problem
    directories, ``.json``, ``.jsonl`` or oracle ``.csv`` files
    (:mod:`.corpus`) -- and append one JSON record per task to ``out``,
    skipping ids already there.  ``workers``: local worker processes (default:
    every core); ``scheduler``: the address of an existing Dask scheduler
    instead.  ``timeout`` (seconds) and ``memory_mb`` limit each task;
    ``check`` runs the trusted kernel on every certificate; ``cert_dir``
    keeps each problem's certificate there (:mod:`.certdir`).  ``progress``:
    a progress bar on stderr (default: when stderr is a terminal);
    ``notice(line)``: told, before any work, of every file of the inputs that
    is not read and why.  Every value in ``out`` is exact (see :mod:`.task`).
    The summary covers every record of ``out``.  Ctrl-C raises
    :class:`BatchInterrupted` (a ``KeyboardInterrupt``).

    >>> import os, tempfile
    >>> corpus = tempfile.mkdtemp()
    >>> with open(os.path.join(corpus, "box.json"), "w") as fh:
    ...     _ = fh.write('{"system": {"A": [[-1]]}, "polyhedron": {"G": [[1], [-1]], "b": [1, 1]}}')
    >>> out = os.path.join(corpus, "results.jsonl")
    >>> with open(out, "w") as fh:  # as if an earlier run had done it
    ...     _ = fh.write('{"id": "box.json", "status": "ok"}\\n')
    >>> summary = run_batch([corpus], out, progress=False)
    >>> summary.total, summary.skipped, summary.ran, summary.exit_code
    (1, 1, 0, 0)
    >>> run_batch([corpus], out, workers=0)
    Traceback (most recent call last):
    ...
    exactinv.errors.InvalidInput: workers: expected a positive integer, got 0
    >>> run_batch([corpus], os.path.join(corpus, "box.json"))
    Traceback (most recent call last):
    ...
    exactinv.errors.InvalidInput: --out ...box.json: this is the input ...box.json; exactinv never overwrites an input (choose another file name)
    """  # noqa: E501 (doctest output)
    limits = _limits(timeout, memory_mb, check, tolerance)
    workers = _workers(workers, scheduler)
    out = os.fspath(out) if isinstance(out, (str, os.PathLike)) else out
    _check_out(out)
    cert_dir = os.fspath(cert_dir) if isinstance(cert_dir, (str, os.PathLike)) else cert_dir
    if cert_dir is not None and (not isinstance(cert_dir, str) or not cert_dir):
        raise InvalidInput(f"cert_dir: expected a directory name, got {cert_dir!r}")
    if cert_dir is not None:
        _refuse_cert_dir_over_inputs(cert_dir, inputs)
    corpus = scan_corpus(inputs, out=out, cert_dir=cert_dir)
    refuse_inputs(out, "--out", corpus.files)
    refuse_foreign(out, "--out", is_results_file, "an exactinv batch results file")
    if notice is not None:
        for line in _skipped_lines(corpus.ignored):
            notice(line)
    done = set(read_records(out))
    todo = [t for t in corpus.tasks if t.id not in done]
    targets: dict[str, str] = {}
    if cert_dir is not None:
        limits = Limits(limits.timeout, limits.memory_mb, limits.check, limits.tolerance, keep_certificate=True)
        targets = prepare_cert_dir(cert_dir, [t.id for t in todo if t.kind == "certify"], corpus.files, out)
    start, threads = time.monotonic(), 0
    ran = 0
    if todo:
        bar = _Bar(len(todo), sys.stderr if (progress if progress is not None else sys.stderr.isatty()) else None)
        try:
            threads, ran = _run(_dask(), todo, limits, workers, scheduler, out, targets, bar)
        except _Interrupted as stop:
            bar.close()
            raise BatchInterrupted(len(corpus.tasks) - len(todo) + stop.written, out) from None
        bar.close()
    tally = Tally()
    for record in read_records(out).values():
        tally.add(record)
    return tally.summary(str(out), len(corpus.tasks), len(corpus.tasks) - len(todo), ran,
                         time.monotonic() - start, threads, corpus.ignored)


def _skipped_lines(ignored: Sequence[tuple[str, str]]) -> list[str]:
    """One line per file not read, or one per folder and reason when more than three share them.

    >>> _skipped_lines([("d/a.json", "why"), ("c/1.cert.json", "cert")] + [(f"c/{k}.cert.json", "cert") for k in range(2, 5)])
    ['skipped d/a.json: why', 'skipped 4 files in c: cert']
    """
    groups: dict[tuple[str, str], list[str]] = {}
    for path, why in ignored:
        groups.setdefault((os.path.dirname(path), why), []).append(path)
    lines = []
    for (folder, why), paths in groups.items():
        if len(paths) > 3:
            lines.append(f"skipped {len(paths)} files in {folder}: {why}")
        else:
            lines.extend(f"skipped {path}: {why}" for path in paths)
    return lines


def _refuse_cert_dir_over_inputs(cert_dir: str, inputs: Any) -> None:
    """--cert-dir may lie inside an input directory (its files are then not read), but may not be
    an input or hold one: its files are never read as problems."""
    folder = os.path.realpath(cert_dir)
    for given in [inputs] if isinstance(inputs, (str, os.PathLike)) else list(inputs):
        here = os.path.realpath(given)
        if os.path.commonpath([here, folder]) == folder:
            raise InvalidInput(f"--cert-dir {cert_dir}: holds the input {os.fspath(given)}; give the certificates "
                               "a directory of their own")


class _Interrupted(Exception):
    """Ctrl-C inside :func:`_run`, after the quiet shutdown; ``written`` records were appended."""

    def __init__(self, written: int):
        super().__init__(written)
        self.written = written


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


def _dask() -> Any:
    """The module dask.distributed, or InvalidInput saying how to install it."""
    try:
        import dask.distributed
    except ImportError:
        raise InvalidInput('exactinv batch needs Dask distributed: pip install "exactinv[batch]" '
                           '(or pip install "dask[distributed]")') from None
    return dask.distributed


def _run(dask: Any, todo: list[Task], limits: Limits, workers: int | None, scheduler: str | None,
         out: str, targets: dict[str, str], bar: "_Bar") -> tuple[int, int]:
    """Submit ``todo`` to Dask in chunks (:mod:`.chunks`, each run by :func:`.task.run_chunk`),
    about ``_WINDOW`` chunks per worker thread in flight (re-counted as workers join or leave),
    append each record to ``out`` as its chunk comes back (its certificate to ``targets[id]``
    first); (the most worker threads seen, records written).  Ctrl-C: a quiet shutdown, then
    :class:`_Interrupted`."""
    client = cluster = sink = None
    futures: dict[Any, list[Task]] = {}
    written, interrupted = 0, False
    ctrl_c = CtrlC()
    try:
        client, cluster = _connect(dask, workers, scheduler)
        ctrl_c.__enter__()
        _same_engine(client)
        sink = ResultsFile(out)
        pending, stream, sizer = collections.deque(todo), dask.as_completed(), ChunkSizer()
        threads, counted = _threads(client), time.monotonic()
        most = threads

        def top_up() -> None:
            while pending and len(futures) < max(threads, 1) * _WINDOW:
                size = sizer.next_size(len(pending), threads)
                chunk = [pending.popleft() for _ in range(size)]
                future = client.submit(run_chunk, chunk, limits, pure=False)
                futures[future] = chunk
                stream.add(future)

        top_up()
        for future in stream:
            records = _records(future, futures.pop(future))
            sizer.observe(records)
            with ctrl_c.deferred():  # the certificates, then their records (one write): all whole or none
                for record in records:
                    _keep_certificate(record, targets)
                sink.extend(records)
                written += len(records)
            for record in records:
                bar.step(record["status"])
            if time.monotonic() - counted > _RECOUNT:
                threads, counted = _threads(client), time.monotonic()
                most = max(most, threads)
            top_up()
        return most, written
    except KeyboardInterrupt:
        interrupted = True
        raise _Interrupted(written) from None
    finally:
        ctrl_c.__exit__()
        _shutdown(client, cluster, sink, list(futures), quiet=interrupted)


def _keep_certificate(record: dict, targets: dict[str, str]) -> None:
    """Write the certificate a record carries (only verified ones do) to its file; the record names it."""
    text = record.pop("certificate_json", None)
    path = targets.get(record["id"])
    if text is not None and path is not None:
        atomic_write(path, text)
        record["certificate"] = path


def _shutdown(client: Any, cluster: Any, sink: ResultsFile | None, futures: list, quiet: bool) -> None:
    """Close the results file, cancel what is in flight, close the client and our own cluster.
    After Ctrl-C: quietly (Dask's loggers muted, a second Ctrl-C ignored meanwhile)."""
    muted = [logging.getLogger(name) for name in ("distributed", "tornado", "asyncio")] if quiet else []
    levels = [log.level for log in muted]
    for log in muted:
        log.setLevel(logging.CRITICAL + 1)
    try:
        with sigint_ignored() if quiet else contextlib.nullcontext():
            if sink is not None:
                sink.close()
            if client is not None:
                if futures:
                    with contextlib.suppress(Exception):  # the cluster may already be gone
                        client.cancel(futures, force=True)
                with contextlib.suppress(Exception):
                    client.close(timeout=10)
            if cluster is not None:
                with contextlib.suppress(Exception):
                    cluster.close(timeout=10)
    finally:
        for log, level in zip(muted, levels):
            log.setLevel(level)


def _threads(client: Any) -> int:
    return sum(client.nthreads().values())


def _records(future: Any, chunk: list[Task]) -> list[dict]:
    """The records of a finished chunk; if Dask gave up on it (its workers died ``allowed-failures``
    times, or it could not be shipped), an ``error`` record for each of its tasks: never fatal."""
    try:
        return future.result()
    except Exception as exc:
        return [{"id": task.id, "kind": task.kind, "source": task.source, "status": "error", "outcome": "error",
                 "error": f"the Dask worker failed: {type(exc).__name__}: {exc}", "seconds": 0.0, "peak_mb": 0.0}
                for task in chunk]


def _connect(dask: Any, workers: int | None, scheduler: str | None) -> tuple[Any, Any]:
    """A Dask client: to ``scheduler``, or to a new LocalCluster (closed by the caller)."""
    if scheduler is not None:
        try:
            return dask.Client(scheduler, timeout=_CONNECT_TIMEOUT), None
        except (OSError, TimeoutError, ValueError) as exc:
            raise InvalidInput(f"scheduler: cannot connect to {scheduler} ({exc})") from None
    # The worker processes ignore SIGINT (a Ctrl-C in the terminal reaches every process of the job):
    # they start with it ignored (inherited from this process while the cluster starts), and the
    # preload re-ignores it after importing cysignals (pplpy's), which installs its own handler.
    # This process alone handles Ctrl-C and shuts the cluster down quietly: no worker traceback.
    # dashboard_address=None does not stop the scheduler's HTTP server: it then asks for port 8787
    # and warns on stderr when that is taken (two batches at once); a free local port is quiet.
    # LOCAL_CONFIG: no profiler, quieter monitors, and worker processes forked from this one (Dask's
    # default spawns them: a fresh interpreter that imports Dask and then exactinv again, 1-2 s of
    # CPU per worker, seconds of wall time on a busy machine); forked, they start with everything
    # this process imported.
    import dask as dask_core
    with sigint_ignored(), dask_core.config.set(LOCAL_CONFIG):
        cluster = dask.LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1, processes=True,
                                    dashboard_address="127.0.0.1:0", silence_logs=logging.CRITICAL, preload=[_WORKER_PRELOAD])
    try:
        return dask.Client(cluster), cluster
    except BaseException:
        cluster.close()
        raise


LOCAL_CONFIG = {
    "distributed.worker.profile.enabled": False,
    "distributed.worker.multiprocessing-method": "fork",
    "distributed.admin.tick.interval": "1s",
    "distributed.worker.memory.monitor-interval": "1s",
    "distributed.admin.system-monitor.interval": "2s",
}
"""The Dask settings of the local cluster ``exactinv batch --workers`` starts: no statistical
profiler (a sample of every worker thread every 10 ms, for a dashboard nobody opens); worker
processes forked from the batch's process, not spawned; the event loops' tick (which only
watches for a blocked loop), the nannies' memory monitor and the system monitor woken every
second or two instead of every 20, 100 and 500 ms.  Idle, a LocalCluster of one worker with
its client then costs 1.5 % of a core instead of 7.1 % (4.5 % this process: scheduler, nanny,
client; 2.6 % the worker), which a batch pays for every second it runs."""

_WORKER_PRELOAD = """\
# exactinv batch: a local worker ignores Ctrl-C (the process that started the batch handles it)
import signal
try:
    import cysignals.signals  # installs a SIGINT handler when first imported (by pplpy)
except ImportError:
    pass
signal.signal(signal.SIGINT, signal.SIG_IGN)
"""


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
