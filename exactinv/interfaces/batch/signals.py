"""Ctrl-C (SIGINT) around the batch's critical moments.

* :func:`sigint_deferred`: a record and its certificate are written whole --
  a Ctrl-C pressed meanwhile arrives right after;
* :func:`sigint_ignored`: while a local cluster starts (its worker processes
  inherit the ignored signal) and while an interrupted batch shuts down.
  The previous handler is restored afterwards, re-armed if it is
  cysignals' (pplpy's), whose C-level handler a plain restore would lose.
"""

from __future__ import annotations

import contextlib
import signal
import sys
import threading
from typing import Iterator

__all__ = ["sigint_deferred", "sigint_ignored"]


@contextlib.contextmanager
def sigint_deferred() -> Iterator[None]:
    """Hold SIGINT back in this thread for the block; a Ctrl-C pressed meanwhile arrives right after it.

    >>> with sigint_deferred():
    ...     signal.SIGINT in signal.pthread_sigmask(signal.SIG_BLOCK, set())
    True
    """
    try:
        old = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    except (AttributeError, OSError, ValueError):  # no POSIX signal masks here
        yield
        return
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, old)


@contextlib.contextmanager
def sigint_ignored() -> Iterator[None]:
    """Ignore SIGINT for the block (only the main thread can; elsewhere nothing changes).

    >>> before = signal.getsignal(signal.SIGINT)
    >>> with sigint_ignored():
    ...     signal.getsignal(signal.SIGINT) == signal.SIG_IGN
    True
    >>> signal.getsignal(signal.SIGINT) == before
    True
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
        cysignals = sys.modules.get("cysignals.signals")
        if cysignals is not None and str(getattr(previous, "__module__", "")).startswith("cysignals"):
            cysignals.init_cysignals()  # re-arm its C-level handler (a plain restore loses it)
