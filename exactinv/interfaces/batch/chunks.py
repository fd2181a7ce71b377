"""How many tasks one Dask task carries: chunks sized from measured durations.

A Dask task costs milliseconds of scheduling and a round trip (about 12 ms
of CPU over the batch's processes, measured on a 1-worker LocalCluster); a
small problem costs about as much.  So the engine ships *chunks* of problems,
each run one after another in the worker's long-lived sandbox
(:mod:`.resident`), and sizes each chunk from the problems measured so far
so that it lasts about :data:`TARGET_SECONDS` -- but never so large that a
worker thread could sit idle at the end while another finishes a long chunk:
at most a :data:`SHARE`-th of what is left per worker thread -- and never,
while more is left, shorter than :data:`FLOOR_SECONDS` (the tail of a corpus
would otherwise go one problem per Dask task, each costing Dask about what
the problem costs).  The first chunks, before any measurement, have
:data:`FIRST` tasks.

>>> sizer = ChunkSizer()
>>> sizer.next_size(remaining=1000, threads=2)         # nothing measured yet
2
>>> sizer.observe([{"seconds": 0.005}] * 4)             # 5 ms problems: 400 would last two seconds ...
>>> sizer.next_size(remaining=1000, threads=2)         # ... but 1000 / (2 x 4) is the fair share
125
>>> sizer.next_size(remaining=100000, threads=2), sizer.next_size(remaining=3, threads=2)
(400, 3)
>>> sizer.next_size(remaining=60, threads=2)           # the floor: a quarter second, 50 problems
50
>>> sizer.observe([{"seconds": 30.0}])                  # a slow one pulls the mean up
>>> sizer.next_size(remaining=100000, threads=2)
1
"""

from __future__ import annotations

import math
from typing import Iterable

__all__ = ["ChunkSizer", "TARGET_SECONDS", "FLOOR_SECONDS", "FIRST", "SHARE"]

TARGET_SECONDS = 2.0
"""The wall time a chunk aims at: long against Dask's per-task cost (~12 ms of CPU: 0.6 %), short
against a run's length."""

FLOOR_SECONDS = 0.25
"""The shortest chunk while more tasks are left than it would take: the fair share (:data:`SHARE`)
shrinks towards the end of a corpus, and without a floor the last chunks would carry one task each."""

FIRST = 2
"""Tasks per chunk before any has been measured."""

SHARE = 4
"""A chunk takes at most 1/SHARE of the tasks left per worker thread (but see :data:`FLOOR_SECONDS`),
so the last chunks shrink and the threads finish together (within about a floor's length)."""


class ChunkSizer:
    """The next chunk's size from the mean measured wall time per task (the records' ``seconds``)."""

    def __init__(self, target: float = TARGET_SECONDS, first: int = FIRST, share: int = SHARE,
                 floor: float = FLOOR_SECONDS):
        self.target, self.first, self.share, self.floor = target, first, share, floor
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
        (8, 4, 1)
        """
        if self.count == 0:
            return max(1, min(self.first, remaining))
        mean = max(self.seconds / self.count, 1e-4)
        size = max(int(self.target / mean), 1)
        fair = math.ceil(remaining / (max(threads, 1) * self.share))
        floor = max(int(self.floor / mean), 1)
        return max(1, min(max(min(size, fair), floor), remaining))
