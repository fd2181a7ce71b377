"""How many tasks one Dask task carries: chunks sized from measured durations.

A Dask task costs milliseconds of scheduling and a round trip; a small
problem costs about as much.  So the engine ships *chunks* of problems, each
run one after another in the worker's long-lived sandbox (:mod:`.resident`),
and sizes each chunk from the problems measured so far so that it lasts about
:data:`TARGET_SECONDS` -- but never so large that a worker thread could sit
idle at the end while another finishes a long chunk: at most a
:data:`SHARE`-th of what is left per worker thread.  The first chunks, before
any measurement, have :data:`FIRST` tasks.

>>> sizer = ChunkSizer()
>>> sizer.next_size(remaining=1000, threads=2)         # nothing measured yet
2
>>> sizer.observe([{"seconds": 0.005}] * 4)             # 5 ms problems: 200 would last a second ...
>>> sizer.next_size(remaining=1000, threads=2)         # ... but 1000 / (2 x 8) is the fair share
63
>>> sizer.next_size(remaining=100000, threads=2), sizer.next_size(remaining=3, threads=2)
(200, 1)
>>> sizer.observe([{"seconds": 30.0}])                  # a slow one pulls the mean up
>>> sizer.next_size(remaining=100000, threads=2)
1
"""

from __future__ import annotations

import math
from typing import Iterable

__all__ = ["ChunkSizer", "TARGET_SECONDS", "FIRST", "SHARE"]

TARGET_SECONDS = 1.0
"""The wall time a chunk aims at: long against Dask's per-task cost, short against a run's length."""

FIRST = 2
"""Tasks per chunk before any has been measured."""

SHARE = 8
"""A chunk takes at most 1/SHARE of the tasks left per worker thread, so the last chunks shrink and
the threads finish together."""


class ChunkSizer:
    """The next chunk's size from the mean measured wall time per task (the records' ``seconds``)."""

    def __init__(self, target: float = TARGET_SECONDS, first: int = FIRST, share: int = SHARE):
        self.target, self.first, self.share = target, first, share
        self.seconds, self.count = 0.0, 0

    def observe(self, records: Iterable[dict]) -> None:
        """Count the measured wall time of finished tasks (records without a number are skipped).

        >>> sizer = ChunkSizer(); sizer.observe([{"seconds": 0.5}, {"status": "error"}]); sizer.count
        1
        """
        for record in records:
            seconds = record.get("seconds")
            if isinstance(seconds, (int, float)) and not isinstance(seconds, bool) and math.isfinite(seconds):
                self.seconds += max(seconds, 0.0)
                self.count += 1

    def next_size(self, remaining: int, threads: int) -> int:
        """How many of the ``remaining`` tasks the next chunk takes, with ``threads`` worker threads.

        >>> sizer = ChunkSizer(); sizer.observe([{"seconds": 0.25}])
        >>> sizer.next_size(10**6, 4), sizer.next_size(64, 4), sizer.next_size(1, 4)
        (4, 2, 1)
        """
        if self.count == 0:
            size = self.first
        else:
            mean = max(self.seconds / self.count, 1e-4)
            size = max(int(self.target / mean), 1)
        fair = math.ceil(remaining / (max(threads, 1) * self.share))
        return max(1, min(size, fair, remaining))
