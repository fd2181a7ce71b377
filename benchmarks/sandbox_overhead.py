"""The long-lived sandbox's own costs (issue 24; exactinv/interfaces/batch/resident.py),
measured without any problem, so they do not drown in the problems' noise:

* per run: a job of the size of a batch task (a problem's text, the limits) down
  the pipe and a record of a batch record's size back, ``--runs`` times in one
  child; CPU of the parent (this process) and of the child per run, with no limits and with both limits set;
* per full garbage collection in the child: the child inherits its parent's heap
  (a Dask worker: Dask, exactinv, and -- forked from `exactinv batch`'s process --
  the corpus's tasks); a full collection there walks every inherited object (and
  writes to each one's GC header: a copy-on-write page fault per page).  Measured
  as the child's CPU for ``gc.collect()`` over a parent holding ``--objects``
  extra objects (a corpus of tasks), for the child as `Sandbox` forks it now.

CPU is user + system (load-independent to first order); the load average is printed.

Run:  python benchmarks/sandbox_overhead.py [--runs 1990] [--objects 200000]
"""

from __future__ import annotations

import argparse
import gc
import json
import os
import resource
import time

import dask.distributed  # noqa: F401  (a Dask worker's heap)

import exactinv  # noqa: F401
from exactinv.interfaces.batch.corpus import Task
from exactinv.interfaces.batch.resident import RENEW_AFTER, Sandbox
from exactinv.interfaces.batch.task import Limits

RECORD = {"status": "ok", "outcome": "proved", "name": "t00001", "method": "taylor(4)", "checked": True, "claims": 5,
          "values": {"gamma_star": "3/2", "forward_euler": "2/3", "threshold": "2/3",
                     "largest_threshold": {"poly": [-12, 12, -6, 0, 1], "interval": ["7/4", "35/20"]},
                     "valid_set": [["0", {"poly": [-12, 12, -6, 0, 1], "interval": ["7/4", "35/20"]}]]}}
TEXT = json.dumps({"name": "t00001", "system": {"A": [[-2, 1], [-1, -2]]},
                   "polyhedron": {"G": [[1, 0], [-1, 0], [0, 1], [0, -1]], "b": [1, 1, 2, 2]}, "method": {"taylor": 4}})


def _echo(job):
    """A batch record for a batch task, no work: what the protocol costs."""
    if job == "usage":
        return _cpu()
    if job == "collect":
        cpu = time.process_time()
        gc.collect()
        return time.process_time() - cpu
    return RECORD


def _cpu() -> float:
    u = resource.getrusage(resource.RUSAGE_SELF)
    return u.ru_utime + u.ru_stime


def per_run(runs: int, timeout: float | None, memory_mb: float | None) -> tuple[float, float]:
    """(parent ms, child ms) of CPU per run."""
    box = Sandbox(_echo)
    job = (Task("t00001", "certify", text=TEXT, source="corpus.jsonl:1"), Limits(timeout, memory_mb))
    runs = min(runs, RENEW_AFTER - 2)  # one child throughout
    child0 = box.run("usage").value  # the fork, outside the clock
    cpu = _cpu()
    for _ in range(runs):
        out = box.run(job, timeout, memory_mb)
        assert out.status == "ok", out
    parent = _cpu() - cpu
    child = box.run("usage").value - child0
    box.close()
    return 1000 * parent / runs, 1000 * child / runs


def full_collection(objects: int) -> tuple[float, float]:
    """(ms of CPU of gc.collect() in a fresh sandbox child: first, second) over a parent
    holding ``objects`` extra tracked objects (tasks of a corpus)."""
    corpus = [Task(f"t{i:06d}", "certify", text=TEXT, source=f"corpus.jsonl:{i}") for i in range(objects)]
    box = Sandbox(_echo)
    try:
        first = box.run("collect", timeout=600).value
        second = box.run("collect", timeout=600).value
    finally:
        box.close()
    del corpus
    return 1000 * first, 1000 * second


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--runs", type=int, default=1990)
    parser.add_argument("--objects", type=int, default=200000)
    args = parser.parse_args()
    print(f"load average {' '.join(f'{x:.1f}' for x in os.getloadavg())}; {len(gc.get_objects())} objects tracked here")
    for label, t, m in (("no limits", None, None), ("--timeout 60 --memory 500", 60.0, 500.0)):
        parent, child = per_run(args.runs, t, m)
        print(f"per run, {label}: parent {parent:.3f} ms, child {child:.3f} ms of CPU")
    for objects in (0, args.objects):
        first, second = full_collection(objects)
        print(f"gc.collect() in the child, parent holding {objects} more tasks: first {first:.1f} ms, "
              f"second {second:.1f} ms of CPU")
    print(f"load average {' '.join(f'{x:.1f}' for x in os.getloadavg())}")


if __name__ == "__main__":
    main()
