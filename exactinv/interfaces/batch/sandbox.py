"""Run one function in a forked child under a time and a memory limit.

The child is a ``fork`` of the calling process, so everything the parent has
imported (exactinv, FLINT, pplpy) is there at no cost; the result comes back
as JSON through a pipe.  Limits are enforced by the operating system, not by
the computation's good will:

* memory: ``setrlimit(RLIMIT_AS)`` in the child, at the address space it
  inherits plus ``memory_mb``.  Python then raises :class:`MemoryError`;
  FLINT and GMP abort the child when an allocation fails, and glibc ends it
  with exit code 127 when it cannot allocate a thread's or a library's
  thread-local storage.  All three are reported as ``"memory"``; the child's
  standard error goes to a file whose tail the parent reads to tell the last
  one from an ordinary exit without a result.
* time: the parent waits at most ``timeout`` seconds of wall time, then sends
  ``SIGKILL`` -- which stops a FLINT loop that never returns to Python.  A
  CPU-time limit a little above ``timeout`` is a second guard should the
  parent itself die.

Linux (POSIX ``fork`` and ``RLIMIT_AS``).

>>> run_limited(sum, [1, 2, 3], timeout=30).value
6
>>> run_limited(bytearray, 10 ** 10, timeout=30, memory_mb=64).status
'memory'
"""

from __future__ import annotations

import ctypes
import json
import math
import os
import resource
import select
import signal
import tempfile
import time
from dataclasses import dataclass, replace
from typing import Any, Callable

__all__ = ["Outcome", "run_limited", "decode_exit", "address_space", "die_with_parent", "plain_fatal_signals",
           "STDERR_TAIL", "CPU_GRACE"]

_FATAL = (signal.SIGSEGV, signal.SIGFPE, signal.SIGABRT, signal.SIGBUS, signal.SIGILL)
STDERR_TAIL = 4096  # bytes of the child's standard error kept for the message
CPU_GRACE = 5  # seconds of CPU time above the wall-clock timeout before the kernel stops an orphan


@dataclass(frozen=True)
class Outcome:
    """What became of one limited run: ``status`` is ``"ok"`` (``value`` holds
    the function's JSON-able result), ``"timeout"``, ``"memory"`` or
    ``"crash"`` (``message`` says how); ``seconds`` is the wall time,
    ``cpu_seconds`` the child's CPU time (user + system) and ``peak_mb`` its
    peak resident memory (it includes the pages shared with the parent that
    the child touched)."""

    status: str
    value: Any = None
    seconds: float = 0.0
    peak_mb: float = 0.0
    message: str = ""
    cpu_seconds: float = 0.0


def run_limited(fn: Callable[[Any], Any], arg: Any, timeout: float | None = None,
                memory_mb: float | None = None) -> Outcome:
    """``fn(arg)`` in a forked child, killed after ``timeout`` seconds and
    denied memory beyond ``memory_mb`` megabytes more than it inherits
    (either limit None: no limit).  The result must be JSON-able.  An
    exception other than MemoryError is the caller's to catch inside ``fn``;
    one that escapes is reported as a ``"crash"`` with its message.

    >>> from fractions import Fraction
    >>> run_limited(lambda q: str(Fraction(*q) ** 2), (2, 3), timeout=30).value
    '4/9'
    >>> o = run_limited(lambda x: 1 // x, 0, timeout=30); o.status, o.message
    ('crash', 'ZeroDivisionError: integer division or modulo by zero')
    """
    read_end, write_end = os.pipe()
    with tempfile.TemporaryFile() as stderr:
        start = time.monotonic()
        pid = os.fork()
        if pid == 0:  # the child: never returns
            os.close(read_end)
            os.dup2(stderr.fileno(), 2)
            _child(fn, arg, write_end, timeout, memory_mb)
        os.close(write_end)
        data, timed_out = _read_until(read_end, None if timeout is None else start + timeout)
        if timed_out:
            os.kill(pid, signal.SIGKILL)
        _, wait_status, usage = os.wait4(pid, 0)
        seconds = time.monotonic() - start
        stderr.seek(max(os.fstat(stderr.fileno()).st_size - STDERR_TAIL, 0))
        said = stderr.read().decode("utf-8", "replace").strip()
    peak = usage.ru_maxrss / 1024  # kilobytes on Linux
    if timed_out:
        outcome = Outcome("timeout", None, seconds, peak, f"stopped after {timeout:g} s (the --timeout limit)")
    else:
        outcome = decode_exit(data, wait_status, memory_mb, seconds, peak, said)
    return replace(outcome, cpu_seconds=usage.ru_utime + usage.ru_stime)


def _child(fn, arg, fd: int, timeout, memory_mb) -> None:
    code = 0
    try:
        _limit(timeout, memory_mb)
        try:
            reply = {"ok": fn(arg)}
        except MemoryError:
            reply = {"memory": f"MemoryError (the --memory limit of {memory_mb:g} MB)" if memory_mb is not None
                     else "MemoryError"}
        except BaseException as exc:  # the function's own bug: report it, never hang the batch
            reply = {"crash": f"{type(exc).__name__}: {exc}"}
        payload = json.dumps(reply).encode()
        view = memoryview(payload)
        while view:
            view = view[os.write(fd, view):]
    except BaseException:
        code = 3
    finally:
        os._exit(code)  # skip the parent's atexit handlers and buffered output


def _limit(timeout: float | None, memory_mb: float | None) -> None:
    plain_fatal_signals()
    die_with_parent()
    if memory_mb is not None:
        ceiling = min(address_space() + int(memory_mb * 2**20), 2**62)
        resource.setrlimit(resource.RLIMIT_AS, (ceiling, ceiling))
    if timeout is not None:
        cpu = int(math.ceil(timeout)) + CPU_GRACE
        resource.setrlimit(resource.RLIMIT_CPU, (cpu, cpu + 1))


def plain_fatal_signals() -> None:
    """In a child: a fatal signal ends it at once -- no crash handler (cysignals, loaded by pplpy,
    would attach a debugger) and no core dump.

    >>> run_limited(lambda _: plain_fatal_signals() or signal.getsignal(signal.SIGSEGV) == signal.SIG_DFL,
    ...             None, timeout=30).value
    True
    """
    for sig in _FATAL:
        signal.signal(sig, signal.SIG_DFL)
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))


def die_with_parent() -> None:
    """SIGKILL this child when the thread that forked it dies (Linux ``PR_SET_PDEATHSIG``): a worker
    closed by an interrupted batch leaves no orphan computing on.

    >>> run_limited(lambda _: die_with_parent() is None, None, timeout=30).value
    True
    """
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, signal.SIGKILL, 0, 0, 0)  # PR_SET_PDEATHSIG = 1
    except (OSError, AttributeError):
        return
    if os.getppid() == 1:  # the parent died before prctl took effect
        os._exit(3)


def address_space() -> int:
    """The current virtual memory size of this process, in bytes (Linux /proc).

    >>> before = address_space(); block = bytearray(2**26); address_space() - before >= 2**26
    True
    """
    with open("/proc/self/status", encoding="ascii") as fh:
        for line in fh:
            if line.startswith("VmSize:"):
                return int(line.split()[1]) * 1024
    raise OSError("VmSize missing from /proc/self/status")


def _read_until(fd: int, deadline: float | None) -> tuple[bytes, bool]:
    """Everything written to ``fd`` until end of file, or (partial, True) at the deadline."""
    chunks = []
    try:
        while True:
            wait = None if deadline is None else max(deadline - time.monotonic(), 0)
            ready, _, _ = select.select([fd], [], [], wait)
            if not ready:
                return b"".join(chunks), True
            chunk = os.read(fd, 1 << 16)
            if not chunk:
                return b"".join(chunks), False
            chunks.append(chunk)
    finally:
        os.close(fd)


def decode_exit(data: bytes, wait_status: int, memory_mb: float | None, seconds: float, peak: float,
                said: str) -> Outcome:
    """What became of a child from its reply ``data`` (JSON: ``{"ok": value}``, ``{"memory": why}`` or
    ``{"crash": why}``; empty if it died first), its wait status and ``said``, its last words on
    standard error: a fatal signal under a memory limit, or glibc's exit on failed thread-local
    allocation, is ``"memory"``; any other death without a reply is a ``"crash"``.

    >>> decode_exit(b'{"ok": 6}', 0, None, 0.1, 70.0, "").value
    6
    >>> decode_exit(b"", 127 << 8, 200, 0.1, 70.0, "cannot allocate memory for thread-local data: ABORT").status
    'memory'
    >>> decode_exit(b"", 5 << 8, None, 0.1, 70.0, "").message
    'the child exited with code 5 without a result'
    """
    if os.WIFSIGNALED(wait_status):
        sig = signal.Signals(os.WTERMSIG(wait_status)).name
        if sig == "SIGXCPU":
            return Outcome("timeout", None, seconds, peak, "stopped by the CPU-time limit")
        if memory_mb is not None and sig in ("SIGABRT", "SIGSEGV", "SIGBUS", "SIGKILL"):
            return Outcome("memory", None, seconds, peak,
                           f"the child died of {sig} under the --memory limit of {memory_mb:g} MB "
                           "(FLINT and GMP abort when an allocation fails)")
        return Outcome("crash", None, seconds, peak, f"the child died of {sig}")
    try:
        reply = json.loads(data)
    except ValueError:
        code = os.waitstatus_to_exitcode(wait_status)
        last = said.splitlines()[-1] if said else ""
        if memory_mb is not None and "cannot allocate memory" in last.lower():
            return Outcome("memory", None, seconds, peak,
                           f"the child exited with code {code} under the --memory limit of {memory_mb:g} MB: {last}")
        return Outcome("crash", None, seconds, peak,
                       f"the child exited with code {code} without a result" + (f": {last}" if last else ""))
    if "ok" in reply:
        return Outcome("ok", reply["ok"], seconds, peak)
    if "memory" in reply:
        return Outcome("memory", None, seconds, peak, reply["memory"])
    return Outcome("crash", None, seconds, peak, reply["crash"])
