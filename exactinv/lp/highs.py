"""A silent HiGHS: the one place exactinv constructs ``highspy.Highs``.

HiGHS (from highspy 1.8 on, e.g. 1.16) prints a banner, "Running HiGHS
x.y.z ...: Copyright ...", from C++ on the process's standard output the
first time a ``Highs`` object is constructed -- before any option such as
``output_flag`` can be set.  exactinv's standard output carries only its own
report (its tests and users parse it), so the first construction in a
process runs with file descriptor 1 pointed at ``/dev/null``; every instance
then gets ``output_flag = False``.  Later constructions print nothing.

The redirect happens once per process, under a lock, and is undone in a
``finally``.  Where it cannot be done (no file descriptor 1, no C library to
flush) the object is constructed plainly: a banner is then possible, a
failure is not.
"""

from __future__ import annotations

import ctypes
import os
import sys
import threading

import highspy

__all__ = ["silence_banner", "silent_highs"]

_lock = threading.Lock()
_banner_done = False


def silent_highs() -> highspy.Highs:
    """A new ``highspy.Highs`` with its output off, its banner swallowed.

    >>> isinstance(silent_highs(), highspy.Highs)
    True
    """
    silence_banner()
    highs = highspy.Highs()
    highs.setOptionValue("output_flag", False)
    return highs


def silence_banner() -> None:
    """Swallow HiGHS' once-per-process banner now (idempotent, thread-safe).

    Called before any code that may construct ``highspy.Highs`` itself, e.g.
    cvxpy's HiGHS interface under the cvxpy hint backend.

    >>> silence_banner(); silence_banner()  # the second call does nothing
    """
    global _banner_done
    with _lock:
        if not _banner_done:
            _construct_without_stdout()
            _banner_done = True


def _construct_without_stdout() -> highspy.Highs:
    try:
        libc = ctypes.CDLL(None)
        sys.stdout.flush()
        libc.fflush(None)
        saved = os.dup(1)
    except (OSError, AttributeError, ValueError):
        return highspy.Highs()
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        try:
            os.dup2(devnull, 1)
            try:
                return highspy.Highs()
            finally:
                libc.fflush(None)  # the banner leaves C's buffer while 1 is /dev/null
                os.dup2(saved, 1)
        finally:
            os.close(devnull)
    finally:
        os.close(saved)
