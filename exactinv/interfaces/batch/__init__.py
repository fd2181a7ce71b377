"""``exactinv batch``: certify or judge a corpus on Dask distributed.

:mod:`.corpus` reads the inputs into tasks, :mod:`.sandbox` runs one task in
a forked child under time and memory limits, :mod:`.task` turns a task into
an exact JSON record, :mod:`.engine` schedules the tasks on Dask and streams
the records, :mod:`.results` appends them to the results file, :mod:`.certdir` keeps the
certificates, :mod:`.summary` counts them.
"""

from .engine import BatchInterrupted, run_batch
from .summary import BatchSummary

__all__ = ["run_batch", "BatchSummary", "BatchInterrupted"]
