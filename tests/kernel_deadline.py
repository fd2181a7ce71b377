"""The kernel's verdict within a deadline: resource tests of the red-team files assert that an
oversized certificate is rejected by a price, quickly, not after minutes of work."""

import signal

from exactinv_check import check


class TooSlow(Exception):
    """The kernel had no verdict by the deadline."""


def check_within(cert, seconds: int):
    """check(cert), but raise TooSlow if the kernel has no verdict after ``seconds`` of
    this process's CPU time (ITIMER_PROF, SIGPROF: other processes' load does not count)."""
    def alarm(*_):
        raise TooSlow(f"no verdict after {seconds} s of CPU time")
    old = signal.signal(signal.SIGPROF, alarm)
    signal.setitimer(signal.ITIMER_PROF, seconds)
    try:
        return check(cert)
    finally:
        signal.setitimer(signal.ITIMER_PROF, 0)
        signal.signal(signal.SIGPROF, old)
