"""``exactinv batch``: certify or judge a corpus on Dask distributed.

:mod:`.corpus` reads the inputs into tasks, :mod:`.sandbox` runs one task in
a forked child under time and memory limits, :mod:`.resident` runs task after
task in one long-lived forked child under each task's limits, :mod:`.task`
turns a task (:func:`.task.run_task`) or a chunk of tasks
(:func:`.task.run_chunk`) into exact JSON records, :mod:`.chunks` sizes the
chunks from measured durations, :mod:`.engine` schedules the chunks on Dask
and streams the records, :mod:`.results` appends them to the results file, :mod:`.certdir` keeps the
certificates, :mod:`.summary` counts them.
"""

from .engine import BatchInterrupted, run_batch
from .summary import BatchSummary

__all__ = ["run_batch", "BatchSummary", "BatchInterrupted"]
