"""``exactinv batch``: certify or judge a corpus on Dask distributed.

:mod:`.corpus` reads the inputs into tasks, :mod:`.sandbox` runs one task in
a forked child under time and memory limits, :mod:`.task` turns a task into
an exact JSON record, :mod:`.engine` schedules the tasks on Dask and streams
the records, :mod:`.summary` counts them.
"""

from .engine import run_batch
from .summary import BatchSummary

__all__ = ["run_batch", "BatchSummary"]
