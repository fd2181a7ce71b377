"""A long-lived sandbox: one forked child that runs one function on argument
after argument, each run under its own time and memory limit.

:func:`.sandbox.run_limited` forks a child per run: about 5 ms of ``fork``
plus the copy-on-write pages the child touches, more than a small problem
costs.  A :class:`Sandbox` forks once and keeps the child; the parent sends
it one argument at a time (pickled, through a pipe) and reads the JSON reply
(through another).  The limits are those of ``run_limited``, per run:

* memory: before each run the child sets its ``RLIMIT_AS`` (soft) to its
  address space at that moment plus ``memory_mb``, and lifts it after.
  Python's :class:`MemoryError` comes back as a ``"memory"`` reply; FLINT's
  and GMP's abort and glibc's exit 127 end the child, and the parent reads
  its wait status and last words (:func:`.sandbox.decode_exit`).
* time: the parent waits at most ``timeout`` seconds of wall time for the
  reply, then sends ``SIGKILL``; a CPU-time limit ``timeout`` + 5 s above
  the child's CPU time so far guards against the parent itself dying, and
  ``PR_SET_PDEATHSIG`` ends the child with the thread that forked it.

A sequence of runs (:meth:`Sandbox.run_all`, what a batch chunk uses) is
*pipelined*: as soon as the child has taken job k (its one-byte answer), job
k + 1 is written to its pipe, so the child goes from one job to the next
without waiting for the parent to read the reply and send again (the parent
is asleep in ``select`` on the replies meanwhile, never polling); and the
child, finding job k + 1 waiting when it finishes job k, takes it and writes
job k's reply and job k + 1's one-byte answer in one ``write``: one wake-up of
the parent per job, not two (each wake-up of the parent may preempt the child
on its CPU).  Job k + 1's clock starts when job k's reply is read (the child
is then free to take it).

After any outcome other than ``"ok"`` the child is killed and the next run
forks a fresh one, so a run that breached a limit never leaves a damaged
process behind; the child is also renewed every :data:`RENEW_AFTER` runs.
An idle child that died between runs (killed from outside, a Ctrl-C sent to
the process group, reaped by someone else) is noticed before the next job is
sent (``wait4(WNOHANG)``) or, dying just then, because it never takes the job:
the child answers each job with one byte the moment it has read it, so a broken
pipe or an end of file before that byte means the job never ran, and it is sent
again to a fresh child -- so is a job queued behind one that breached a limit
(its child is killed before the parent reads that byte).  Only a child that
dies *while running* a job (after that byte) makes that job a ``"crash"`` (or
``"memory"``).  A fork of the parent inherits the
:class:`Sandbox` object but not the child: there it is forgotten, never killed.
``seconds`` is the wall time of the run seen from the parent,
``cpu_seconds`` the child's CPU time for this run and ``peak_mb`` its peak
resident memory during the run (Linux's ``VmHWM``, reset before each run
through ``/proc/self/clear_refs``; it includes the pages shared with the
parent that the child touched).

Linux (POSIX ``fork``, ``RLIMIT_AS``, ``/proc``).

>>> box = Sandbox(len)
>>> [box.run(x, timeout=30).value for x in ("ab", [1, 2, 3])], box.forks
([2, 3], 1)
>>> box.run(10, timeout=30).status, box.forks  # a crash costs the child ...
('crash', 1)
>>> box.run("abcd", timeout=30).value, box.forks  # ... and the next run forks a new one
(4, 2)
>>> box.close()
"""

from __future__ import annotations

import contextlib
import fcntl
import gc
import json
import math
import os
import pickle
import resource
import select
import signal
import struct
import tempfile
import threading
import time
from dataclasses import replace
from typing import Any, Callable, Iterable

from .sandbox import CPU_GRACE, STDERR_TAIL, Outcome, address_space, decode_exit, die_with_parent, plain_fatal_signals

__all__ = ["Sandbox", "resident", "RENEW_AFTER"]

RENEW_AFTER = 2000
"""Runs after which a child is replaced by a fresh fork (bounds what a long life may accumulate)."""

_HEADER = struct.Struct(">Q")
_TAKEN = b"+"  # the child's first reply to a job: it has read it (a death from then on is the job's)


class Sandbox:
    """A long-lived child running ``fn`` (see the module docstring); ``fn``'s result must be
    JSON-able, its argument picklable.  Not thread-safe: one per thread (:func:`resident`)."""

    def __init__(self, fn: Callable[[Any], Any]):
        self.fn = fn
        self.pid: int | None = None
        self.forks = 0
        self._jobs = self._replies = -1
        self._stderr: Any = None
        self._runs = 0
        self._cpu = 0.0  # CPU seconds of the current child accounted to runs so far
        self._owner = os.getpid()  # the process that forked the child (a fork of it inherits this object)
        self._reader = _Reader(-1)  # the child's replies, buffered
        self._capacity = 0  # bytes the jobs pipe holds: a queued job must fit (or the write would block)
        self._said_at = 0  # the child's stderr size when a queued job was written to its pipe

    def run(self, arg: Any, timeout: float | None = None, memory_mb: float | None = None) -> Outcome:
        """``fn(arg)`` in the child, stopped after ``timeout`` seconds and denied memory beyond
        ``memory_mb`` megabytes more than the child holds when the run starts (None: no limit).

        >>> box = Sandbox(bytearray)
        >>> [(o.status, o.message) for o in (box.run(10**10, timeout=30, memory_mb=64),)]
        [('memory', 'MemoryError (the --memory limit of 64 MB)')]
        >>> box.run(3, timeout=30).status, box.forks  # not JSON-able: a crash, in a new child
        ('crash', 2)
        >>> box.close()
        """
        return self.run_all([arg], timeout, memory_mb)[0]

    def run_all(self, args: Iterable[Any], timeout: float | None = None,
                memory_mb: float | None = None) -> list[Outcome]:
        """The outcomes of ``fn(arg)`` for each of ``args``, in order: each exactly what :meth:`run`
        gives for it (its own limits, its own measurements; a breach replaces the child and the next
        argument runs in a fresh one), but *pipelined*: the next job is written to the child's pipe
        as soon as the child has taken the current one (its one-byte answer), so the child goes from
        one job to the next without waiting for the parent to read the reply and send again.  A
        queued job the child never took (it died, breached a limit or was killed first) is sent again
        to a fresh child; a job's clock starts when the child is free to take it (the previous reply
        read), its ``timeout`` counts from there.

        >>> box = Sandbox(abs)
        >>> [o.value for o in box.run_all([-1, 2, -3], timeout=30)], box.forks
        ([1, 2, 3], 1)
        >>> [o.status for o in box.run_all([-1, "x", -3], timeout=30)], box.forks  # abs("x") raises
        (['ok', 'crash', 'ok'], 2)
        >>> box.close()
        """
        jobs = [_frame(pickle.dumps((arg, timeout, memory_mb), pickle.HIGHEST_PROTOCOL)) for arg in args]
        outcomes: list[Outcome] = []
        queued = False  # jobs[k] is already in the current child's pipe (sent while k - 1 ran)
        free_at = 0.0  # when the current child became free to take a queued job (its previous reply read)
        try:
            for k, job in enumerate(jobs):
                outcome, queued, free_at = self._one(job, jobs[k + 1] if k + 1 < len(jobs) else None, queued,
                                                     free_at, timeout, memory_mb)
                outcomes.append(outcome)
        except BaseException:  # (Ctrl-C in the parent): never leave a child holding a job nobody reads
            self.close()
            raise
        return outcomes

    def _one(self, job: bytes, after: bytes | None, queued: bool, free_at: float, timeout: float | None,
             memory_mb: float | None) -> tuple[Outcome, bool, float]:
        """Run ``job`` (already in the pipe if ``queued``), queueing ``after`` once it is taken;
        (its outcome, whether ``after`` is queued in the current child, when that child became free)."""
        while True:
            if not queued:
                if self.pid is not None and (self._runs >= RENEW_AFTER or not self._alive()):
                    self.close()
                if self.pid is None:
                    self._spawn()
                start = time.monotonic()
                said_from = os.fstat(self._stderr.fileno()).st_size
            else:
                start, said_from = free_at, self._said_at
            deadline = None if timeout is None else start + timeout
            try:
                if not queued:
                    _write_all(self._jobs, job)
                taken, timed_out = self._reader.read_exact(1, deadline)  # the child's "job in hand"
            except BrokenPipeError:  # the child is gone and never read the job
                taken, timed_out = None, False
            queued = False
            if taken is None and not timed_out:  # it died before it took the job: the job never ran
                fresh = self._runs == 0
                wait_status, _, peak = self._reap()
                if not fresh:  # a fresh child runs it; one that dies before its first job is a crash
                    continue
                return decode_exit(b"", wait_status, None, time.monotonic() - start, peak,  # no limit was set
                                   self._said(said_from)), False, 0.0
            break
        self._runs += 1
        reply = None
        if not timed_out:
            if after is not None and self._runs < RENEW_AFTER and len(after) <= self._capacity:
                # the next job's stderr starts here: the child is busy with this job, so nothing of the next is
                # written yet (read after this job's reply, the size may already hold the next job's first words:
                # a queued job that wrote its failure at once was decoded without it)
                said_at = os.fstat(self._stderr.fileno()).st_size
                try:  # the next job waits in the pipe (which is empty: the child has read this one whole)
                    _write_all(self._jobs, after)
                    queued, self._said_at = True, said_at
                except BrokenPipeError:  # the child died: this job's reply says how; the next is resent
                    pass
            reply, timed_out = self._reader.read_frame(deadline)
        now = time.monotonic()
        seconds = now - start
        if timed_out:
            os.kill(self.pid, signal.SIGKILL)
        if reply is None:  # killed at the deadline, or died by itself
            wait_status, cpu, peak = self._reap()
            if timed_out:
                return Outcome("timeout", None, seconds, peak, f"stopped after {timeout:g} s (the --timeout limit)",
                               cpu), False, 0.0
            return replace(decode_exit(b"", wait_status, memory_mb, seconds, peak, self._said(said_from)),
                           cpu_seconds=cpu), False, 0.0
        answer = json.loads(reply)
        cpu, peak = answer["cpu"], answer["peak"]
        self._cpu += cpu
        if "ok" in answer:
            return Outcome("ok", answer["ok"], seconds, peak, cpu_seconds=cpu), queued, now
        self.close()  # a breach or a bug: never reuse that process (a queued job is resent to the next)
        status = "memory" if "memory" in answer else "crash"
        return Outcome(status, None, seconds, peak, answer[status], cpu_seconds=cpu), False, 0.0

    def close(self) -> None:
        """Kill and reap the child, if any; the next run forks a new one.

        >>> box = Sandbox(abs); box.run(-2).value, box.pid is not None
        (2, True)
        >>> box.close(); box.pid is None
        True
        """
        if self.pid is not None and self._alive():  # (a dead child is reaped, another process's forgotten)
            os.kill(self.pid, signal.SIGKILL)
            self._reap()

    def __del__(self) -> None:  # a thread that ends drops its sandbox: reap the child, close the pipes
        try:
            self.close()
        except Exception:
            pass

    def _spawn(self) -> None:
        jobs_r, jobs_w = os.pipe()
        replies_r, replies_w = os.pipe()
        if self._stderr is not None:
            self._stderr.close()  # the previous child's
        self._stderr = tempfile.TemporaryFile()
        pid = os.fork()
        if pid == 0:  # the child: never returns
            os.close(jobs_w)
            os.close(replies_r)
            os.dup2(self._stderr.fileno(), 2)
            _serve(self.fn, jobs_r, replies_w)
        os.close(jobs_r)
        os.close(replies_w)
        self.pid, self._jobs, self._replies, self._owner = pid, jobs_w, replies_r, os.getpid()
        self._reader, self._capacity = _Reader(replies_r), _pipe_capacity(jobs_w)
        self.forks += 1
        self._runs, self._cpu = 0, 0.0

    def _alive(self) -> bool:
        """Is the idle child still there?  One ``wait4(WNOHANG)``: a child that died since its last run
        (killed from outside, a signal to the process group) is reaped here and forgotten, so the next
        run forks a fresh one instead of sending its job to the dead.  In a fork of the process that
        forked it, the child is not ours: forgotten too."""
        if self._owner != os.getpid():
            self._forget()
            return False
        try:
            pid, _, _ = os.wait4(self.pid, os.WNOHANG)
        except ChildProcessError:  # already reaped by someone else (a waitpid(-1) in this process)
            pid = self.pid
        if pid == 0:
            return True
        self._forget()
        return False

    def _reap(self) -> tuple[int, float, float]:
        """Wait for the dead (or killed) child; its wait status, the CPU seconds it spent since the
        last accounted run, and its peak resident memory (MB) over its life (a child reaped by
        someone else: status 0 and no measurements)."""
        try:
            _, wait_status, usage = os.wait4(self.pid, 0)
        except ChildProcessError:
            self._forget()
            return 0, 0.0, 0.0
        cpu = max(usage.ru_utime + usage.ru_stime - self._cpu, 0.0)
        self._forget()
        return wait_status, cpu, usage.ru_maxrss / 1024

    def _forget(self) -> None:
        """Close this side's pipes and drop the child's pid (it is reaped, or not ours)."""
        for fd in (self._jobs, self._replies):
            with contextlib.suppress(OSError):
                os.close(fd)
        self.pid, self._jobs, self._replies = None, -1, -1

    def _said(self, offset: int) -> str:
        """The child's standard error since ``offset`` (its last STDERR_TAIL bytes)."""
        end = os.fstat(self._stderr.fileno()).st_size
        self._stderr.seek(max(offset, end - STDERR_TAIL))
        return self._stderr.read().decode("utf-8", "replace").strip()


_local = threading.local()


def resident(fn: Callable[[Any], Any]) -> Sandbox:
    """This thread's sandbox for ``fn``, forked on first use and kept for the thread's life (a
    Dask worker thread runs chunk after chunk in the same child).

    >>> resident(abs) is resident(abs), resident(abs).run(-7, timeout=30).value
    (True, 7)
    >>> resident(abs).close()
    """
    boxes = getattr(_local, "boxes", None)
    if boxes is None:
        boxes = _local.boxes = {}
    box = boxes.get(fn)
    if box is None:
        box = boxes[fn] = Sandbox(fn)
    return box


# --- the child ---------------------------------------------------------------------------------

def _serve(fn: Callable[[Any], Any], jobs: int, replies: int) -> None:
    """The child's loop: one job in, one reply out, until the parent closes the pipe.

    First, :func:`_settle`: the inherited heap leaves the child's garbage collector."""
    code = 0
    try:
        plain_fatal_signals()
        die_with_parent()
        _settle()
        proc = _ProcSelf()
        reader = _Reader(jobs)
        job, _ = reader.read_frame(None)
        if job is not None:
            _write_all(replies, _TAKEN)  # from here on a death is this job's
        while job is not None:
            arg, timeout, memory_mb = pickle.loads(job)
            reply = _frame(_one(fn, arg, timeout, memory_mb, proc))
            job = reader.ready_frame()  # pipelined: the next job is usually waiting already
            if job is not None:  # the reply and "the next job in hand" in one write: one wake-up of the parent
                _write_all(replies, reply + _TAKEN)
                continue
            _write_all(replies, reply)
            job, _ = reader.read_frame(None)
            if job is not None:
                _write_all(replies, _TAKEN)
    except BaseException:
        code = 3
    finally:
        os._exit(code)  # skip the parent's atexit handlers and buffered output


def _settle() -> None:
    """In a fresh child: ``gc.freeze()`` -- every object inherited from the parent (a Dask worker:
    Dask, exactinv, and the corpus's tasks when the worker was forked from `exactinv batch`) moves
    to the permanent generation, so the child's full collections walk only the child's own objects
    instead of the whole inherited heap, writing each object's GC header (a copy-on-write fault per
    page) -- the standard cure for a forked server (Python's gc docs).  Inherited objects are still
    freed by their reference counts; only cycles among them are never collected here (nor needed:
    the child's life is bounded, :data:`RENEW_AFTER`).  And the parent's ``gc.callbacks`` (Dask's
    worker registers a GC diagnosis that reads the process's memory and logs) are dropped: they
    watch the parent, not the child."""
    gc.freeze()
    gc.callbacks.clear()


class _ProcSelf:
    """The child's /proc files, opened once and re-read with ``pread`` (opening and parsing
    ``/proc/self/status`` by lines for every run cost 0.1-0.2 ms; a re-read costs a few µs):
    ``clear_refs`` to reset the resident high-water mark, ``status`` for it (``VmHWM``),
    ``statm`` for the address space (``VmSize``).  Where a file cannot be opened the measurement
    falls back to :func:`.sandbox.address_space` and the life-long ``ru_maxrss``."""

    def __init__(self) -> None:
        self.clear_refs = _open("/proc/self/clear_refs", os.O_WRONLY)
        self.status = _open("/proc/self/status", os.O_RDONLY)
        self.statm = _open("/proc/self/statm", os.O_RDONLY)

    def reset_peak(self) -> None:
        """Reset this process's resident high-water mark (VmHWM; Linux 4.0 and later)."""
        if self.clear_refs is not None:
            with contextlib.suppress(OSError):
                os.write(self.clear_refs, b"5")

    def peak_mb(self) -> float:
        """This process's resident high-water mark in MB: VmHWM, else the life-long ru_maxrss."""
        if self.status is not None:
            with contextlib.suppress(OSError, ValueError, IndexError):
                text = os.pread(self.status, 1 << 16, 0)
                at = text.index(b"VmHWM:")
                return int(text[at + 6:text.index(b"kB", at)]) / 1024
        return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024

    def address_space(self) -> int:
        """This process's virtual memory size in bytes (statm's first field, in pages: VmSize)."""
        if self.statm is not None:
            with contextlib.suppress(OSError, ValueError, IndexError):
                return int(os.pread(self.statm, 256, 0).split()[0]) * _PAGE
        return address_space()


_PAGE = os.sysconf("SC_PAGE_SIZE") if hasattr(os, "sysconf") else 4096


def _open(path: str, flags: int) -> int | None:
    try:
        return os.open(path, flags)
    except OSError:
        return None


def _one(fn: Callable[[Any], Any], arg: Any, timeout: float | None, memory_mb: float | None,
         proc: _ProcSelf) -> bytes:
    """One run under the limits: the JSON reply with the run's CPU seconds and peak memory."""
    cpu0 = _cpu()
    proc.reset_peak()
    limited = _set_limits(timeout, memory_mb, cpu0, proc)
    try:
        try:
            reply: dict = {"ok": fn(arg)}
        except MemoryError:
            reply = {"memory": f"MemoryError (the --memory limit of {memory_mb:g} MB)" if memory_mb is not None
                     else "MemoryError"}
        except BaseException as exc:  # the function's own bug: report it, never hang the batch
            reply = {"crash": f"{type(exc).__name__}: {exc}"}
    finally:
        _lift_limits(limited)
    meta = {"cpu": _cpu() - cpu0, "peak": proc.peak_mb()}
    try:
        return json.dumps({**reply, **meta}).encode()
    except (TypeError, ValueError) as exc:
        return json.dumps({"crash": f"the result is not JSON-able: {exc}", **meta}).encode()


def _cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def _set_limits(timeout: float | None, memory_mb: float | None, cpu_now: float, proc: _ProcSelf) -> tuple[int, ...]:
    """Set the run's limits; the resources limited."""
    limited = []
    if memory_mb is not None:
        _, hard = resource.getrlimit(resource.RLIMIT_AS)
        soft = min(proc.address_space() + int(memory_mb * 2**20), 2**62)
        resource.setrlimit(resource.RLIMIT_AS, (soft if hard == resource.RLIM_INFINITY else min(soft, hard), hard))
        limited.append(resource.RLIMIT_AS)
    if timeout is not None:
        _, hard = resource.getrlimit(resource.RLIMIT_CPU)
        soft = int(math.ceil(cpu_now + timeout)) + CPU_GRACE
        resource.setrlimit(resource.RLIMIT_CPU, (soft if hard == resource.RLIM_INFINITY else min(soft, hard), hard))
        limited.append(resource.RLIMIT_CPU)
    return tuple(limited)


def _lift_limits(limited: tuple[int, ...]) -> None:
    for which in limited:
        _, hard = resource.getrlimit(which)
        resource.setrlimit(which, (hard, hard))


# --- frames ------------------------------------------------------------------------------------

def _frame(payload: bytes) -> bytes:
    return _HEADER.pack(len(payload)) + payload


def _write_all(fd: int, data: bytes) -> None:
    view = memoryview(data)
    while view:
        view = view[os.write(fd, view):]


def _pipe_capacity(fd: int) -> int:
    """How many bytes the pipe ``fd`` holds (Linux ``F_GETPIPE_SZ``; POSIX guarantees PIPE_BUF)."""
    try:
        return fcntl.fcntl(fd, fcntl.F_GETPIPE_SZ)
    except (OSError, AttributeError):
        return select.PIPE_BUF


class _Reader:
    """Exact reads from a pipe through a buffer: one ``read`` takes whatever is there (a reply and
    the next job's one-byte answer, a job's header and payload), so a frame costs one system call,
    not two or three.  With a deadline the wait is a ``select`` on the descriptor: the process
    sleeps until the child writes, dies or the deadline passes (never a polling loop)."""

    def __init__(self, fd: int):
        self.fd = fd
        self.buf = bytearray()

    def read_exact(self, size: int, deadline: float | None) -> tuple[bytes | None, bool]:
        """``size`` bytes: (data, False); (None, False) at end of file (the writer died);
        (None, True) at the deadline."""
        while len(self.buf) < size:
            if deadline is not None:
                ready, _, _ = select.select([self.fd], [], [], max(deadline - time.monotonic(), 0))
                if not ready:
                    return None, True
            chunk = os.read(self.fd, max(size - len(self.buf), 1 << 16))
            if not chunk:
                return None, False
            self.buf += chunk
        data = bytes(self.buf[:size])
        del self.buf[:size]
        return data, False

    def ready_frame(self) -> bytes | None:
        """A whole frame if one is here already (buffered, or in the pipe), without waiting; else None
        (also at end of file or on an error: a blocking :meth:`read_frame` then says which)."""
        try:
            while True:
                if len(self.buf) >= _HEADER.size and len(self.buf) >= _HEADER.size + _HEADER.unpack_from(self.buf)[0]:
                    return self.read_frame(None)[0]
                ready, _, _ = select.select([self.fd], [], [], 0)
                if not ready:
                    return None
                chunk = os.read(self.fd, 1 << 16)
                if not chunk:
                    return None
                self.buf += chunk
        except (OSError, ValueError):
            return None

    def read_frame(self, deadline: float | None) -> tuple[bytes | None, bool]:
        """One frame: (payload, False); (None, False) at end of file (also mid-frame: the writer
        died); (None, True) at the deadline."""
        header, timed_out = self.read_exact(_HEADER.size, deadline)
        if header is None:
            return None, timed_out
        return self.read_exact(_HEADER.unpack(header)[0], deadline)
