"""Ctrl-C (SIGINT) around the batch's critical moments.

* :class:`CtrlC`: while a batch runs, Ctrl-C raises KeyboardInterrupt in the
  main thread -- except inside :meth:`CtrlC.deferred` (a record and its
  certificate are written whole), where it is noted and raised right after.
  A Python-level handler, so it works whichever thread the operating system
  delivers the signal to (the Dask client runs threads of its own);
* :func:`sigint_ignored`: while a local cluster starts (its worker processes
  inherit the ignored signal) and while an interrupted batch shuts down.

Both restore the previous handler afterwards, re-armed if it is cysignals'
(pplpy's), whose C-level handler a plain restore would lose.
"""

from __future__ import annotations

import contextlib
import signal
import sys
import threading
from typing import Iterator

__all__ = ["CtrlC", "sigint_ignored"]


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
        _restore(previous)


def _restore(previous) -> None:
    signal.signal(signal.SIGINT, previous)
    cysignals = sys.modules.get("cysignals.signals")
    if cysignals is not None and str(getattr(previous, "__module__", "")).startswith("cysignals"):
        cysignals.init_cysignals()  # re-arm its C-level handler (a plain restore loses it)


class CtrlC:
    """A context manager: Ctrl-C raises KeyboardInterrupt, but not inside :meth:`deferred`.

    >>> import os
    >>> with CtrlC() as ctrl_c:
    ...     try:
    ...         with ctrl_c.deferred():
    ...             os.kill(os.getpid(), signal.SIGINT)
    ...             written = True
    ...     except KeyboardInterrupt:
    ...         print("interrupted after the block:", written)
    interrupted after the block: True
    """

    def __init__(self) -> None:
        self.critical = 0
        self.pending = False
        self.previous = None

    def _handler(self, signum, frame) -> None:
        if self.critical:
            self.pending = True
        else:
            raise KeyboardInterrupt

    def __enter__(self) -> "CtrlC":
        if threading.current_thread() is threading.main_thread():
            self.previous = signal.signal(signal.SIGINT, self._handler)
        return self

    def __exit__(self, *exc) -> None:
        if self.previous is not None:
            _restore(self.previous)
            self.previous = None

    @contextlib.contextmanager
    def deferred(self) -> Iterator[None]:
        """The block runs whole; a Ctrl-C meanwhile raises KeyboardInterrupt right after it.

        >>> with CtrlC() as ctrl_c, ctrl_c.deferred():
        ...     ctrl_c.critical
        1
        """
        self.critical += 1
        try:
            yield
        finally:
            self.critical -= 1
        if self.pending and not self.critical:
            self.pending = False
            raise KeyboardInterrupt
