"""One task of a batch, as a worker runs it: certify (and kernel-check) a
problem, or judge an oracle row, inside the sandbox's time and memory
limits, and return one JSON-able record -- alone in a fresh child
(:func:`run_task`) or as one of a chunk in the thread's long-lived sandbox
(:func:`run_chunk`, what the engine runs); the records are the same.
Neither raises: a problem that fails is recorded and the batch goes on.

A record holds exact values only as the certificate encodes them
(:func:`exactinv.core.encode.encode_real`): a rational as ``"p/q"``,
infinity as ``"oo"``, an algebraic number as ``{"poly": [...], "interval":
[lo, hi]}`` -- strings, never floats.  ``seconds`` and ``peak_mb`` are
measurements, not results.

>>> box = '{"system": {"A": [[-1]]}, "polyhedron": {"G": [[1], [-1]], "b": [1, 1]}, "method": {"taylor": 2}}'
>>> r = run_task(Task("box", "certify", text=box), Limits(timeout=60))
>>> r["status"], r["outcome"], r["values"]["gamma_star"], r["values"]["largest_threshold"]
('ok', 'proved', '1/2', '2')

Each record also has an ``outcome`` (:mod:`exactinv.interfaces.exit_codes`):
``proved``, ``refuted`` (the set is not invariant; a judged claim is
invalid), ``undecided``, ``bad_input`` (the problem or row cannot be read)
or ``error`` (an engine failure, a certificate the kernel rejected, a
timeout, the memory limit).
"""

from __future__ import annotations

import re
import sys
from dataclasses import dataclass, replace
from fractions import Fraction
from pathlib import Path
from typing import Any, Sequence

from ...core.encode import dumps, encode_real
from ...core.real_algebraic import RealAlgebraic
from ...core.scalars import Infinity
from ...errors import ExactinvException, InvalidInput, Undecided, VerificationFailed
from ..exit_codes import CODES
from ..oracle import judge_row
from ..pipeline import certify
from ..problem import load_problem
from .corpus import Task
from .resident import Sandbox, resident
from .sandbox import Outcome, run_limited

__all__ = ["Limits", "STATUSES", "run_task", "run_chunk", "chunk_sandbox", "engine_version", "record_outcome"]

STATUSES = ("ok", "rejected", "error", "timeout", "memory")
"""A record's status: the kernel verified the certificate (or, with
``check=False``, the engine finished; for a judged row: the row was judged,
its verdict is in ``verdict``); the kernel rejected it; bad input or an
engine failure (``error`` says which); the time limit; the memory limit."""



def record_outcome(record: dict) -> str:
    """The outcome of a record (its ``outcome``; for a record written before outcomes were
    recorded: ``refuted`` for an invalid verdict or gamma* = oo, ``error`` for a status other
    than ok, else ``proved``).

    >>> record_outcome({"status": "ok", "values": {"gamma_star": "oo"}}), record_outcome({"status": "timeout"})
    ('refuted', 'error')
    """
    outcome = record.get("outcome")
    if outcome in CODES:
        return outcome
    if record.get("status") == "undecided":
        return "undecided"
    if record.get("status") != "ok":
        return "error"
    verdict, values = record.get("verdict"), record.get("values")
    if (isinstance(verdict, dict) and verdict.get("status") == "invalid") or (
            isinstance(values, dict) and values.get("gamma_star") == "oo"):
        return "refuted"
    return "proved"


@dataclass(frozen=True)
class Limits:
    """How each task runs: wall-clock ``timeout`` (seconds) and ``memory_mb``
    (megabytes beyond what the worker holds) per task, None for no limit;
    ``check``: run the trusted kernel on each certificate; ``tolerance``:
    the oracle's relative tolerance for ``tight``; ``keep_certificate``: the
    record carries the certificate's JSON text (``certificate_json``) for the
    machine that writes the results (``--cert-dir``) -- not if the kernel rejected it."""

    timeout: float | None = None
    memory_mb: float | None = None
    check: bool = True
    tolerance: str = "1e-9"
    keep_certificate: bool = False


def engine_version() -> str:
    """The exactinv version of this process.  Called on every worker (in its main thread: pplpy's
    cysignals can only be imported there) before any task, so that a worker imports exactinv safely
    and a cluster running another version is refused.

    >>> engine_version() == sys.modules["exactinv"].__version__
    True
    """
    return sys.modules[__name__.split(".")[0]].__version__


def run_task(task: Task, limits: Limits) -> dict:
    """The record of ``task`` run under ``limits`` (see the module docstring).

    Taylor(2) on x' = -x, P = [-1, 1]: r(-h) = 1 - h + h^2/2 >= -1 for all h and
    <= 1 iff h <= 2, so the largest threshold is 2.  An unreadable input is an
    ``error`` record without running.

    >>> box = '{"system": {"A": [[-1]]}, "polyhedron": {"G": [[1], [-1]], "b": [1, 1]}, "method": {"taylor": 2}}'
    >>> r = run_task(Task("box", "certify", text=box), Limits(timeout=60, check=False))
    >>> r["status"], r["checked"], r["values"]["largest_threshold"]
    ('ok', False, '2')
    >>> run_task(Task("bad", "certify", error="bad.json: cannot read"), Limits())["status"]
    'error'
    """
    if task.error:
        return _unreadable(task)
    return _record(task, run_limited(_solve, (task, limits), limits.timeout, limits.memory_mb))


def run_chunk(tasks: Sequence[Task], limits: Limits) -> list[dict]:
    """The records of ``tasks``, in order, each run under ``limits`` as :func:`run_task` runs it,
    but one after another in this thread's long-lived sandbox (:mod:`.resident`): one fork for
    the whole chunk (and for every later chunk of this thread), not one per task, and pipelined
    (:meth:`.resident.Sandbox.run_all`: the next task waits in the child's pipe while one runs,
    so the child never waits for this thread between tasks).  A task that
    breaches a limit is recorded, the sandbox is replaced, and the rest of the chunk runs.  The
    records are :func:`run_task`'s, exact values and all; only the measurements differ.

    >>> box = '{"system": {"A": [[-1]]}, "polyhedron": {"G": [[1], [-1]], "b": [1, 1]}, "method": {"taylor": %d}}'
    >>> chunk = [Task(f"t{p}", "certify", text=box % p) for p in (1, 2)] + [Task("bad", "certify", error="unread")]
    >>> [(r["id"], r["status"], r["values"]["largest_threshold"] if "values" in r else None)
    ...  for r in run_chunk(chunk, Limits(timeout=60))]
    [('t1', 'ok', '2'), ('t2', 'ok', '2'), ('bad', 'error', None)]
    """
    runnable = [task for task in tasks if not task.error]
    outcomes = iter(chunk_sandbox().run_all([(task, limits) for task in runnable], limits.timeout, limits.memory_mb))
    return [_unreadable(task) if task.error else _record(task, next(outcomes)) for task in tasks]


def chunk_sandbox() -> Sandbox:
    """This thread's long-lived sandbox, in which :func:`run_chunk` runs its tasks (forked on first
    use, kept for the thread's life; :func:`.resident.resident`).

    >>> chunk_sandbox() is chunk_sandbox()
    True
    """
    return resident(_solve)


def _unreadable(task: Task) -> dict:
    """The record of a task whose input could not be read (nothing runs)."""
    return {"id": task.id, "kind": task.kind, "source": task.source, "status": "error", "outcome": "bad_input",
            "error": task.error, "seconds": 0.0, "peak_mb": 0.0}


def _record(task: Task, outcome: Outcome) -> dict:
    """The record of a task from the outcome of its run."""
    head = {"id": task.id, "kind": task.kind, "source": task.source}
    record = dict(outcome.value) if outcome.status == "ok" else {
        "status": "error" if outcome.status == "crash" else outcome.status, "outcome": "error",
        "error": outcome.message}
    return {**head, **record, "seconds": round(outcome.seconds, 4), "cpu_seconds": round(outcome.cpu_seconds, 4),
            "peak_mb": round(outcome.peak_mb, 1)}


def _solve(job: tuple[Task, Limits]) -> dict:
    task, limits = job
    try:
        if task.kind == "certify":
            return _certify(task, limits.check, limits.keep_certificate)
        return _judge(task, limits.tolerance)
    except VerificationFailed as exc:
        return {"status": "error", "outcome": "error", "error": f"internal verification failed: {exc}"}
    except Undecided as exc:
        return {"status": "error", "outcome": "undecided", "error": f"undecided: {exc}"}
    except ExactinvException as exc:
        return {"status": "error", "outcome": "bad_input", "error": str(exc)}
    except RecursionError:
        return {"status": "error", "outcome": "bad_input", "error": "input nested too deeply"}
    except MemoryError:
        raise
    except Exception as exc:  # an engine bug: recorded, never the end of the batch
        return {"status": "error", "outcome": "error",
                "error": f"internal error (a bug; please report it): {type(exc).__name__}: {exc}"}


def _folder(source: str) -> str | None:
    """The folder of a task's file ("dir/p.json" or "dir/corpus.jsonl:12"): where a
    problem's relative cdd file is looked up."""
    path = re.sub(r":\d+\Z", "", source or "")
    return str(Path(path).resolve().parent) if path else None


def _certify(task: Task, check: bool, keep: bool = False) -> dict:
    text = task.text or ""
    if not text.lstrip().startswith("{"):
        raise InvalidInput("expected a problem: a JSON object with \"system\" and \"polyhedron\"")
    problem = load_problem(text, base=_folder(task.source))
    if problem.name == "problem" and task.kind == "certify" and task.source.endswith(".json"):
        problem = replace(problem, name=Path(task.source).stem)  # a file's name, as `exactinv certify` does
    report = certify(problem, check=check)
    record = {"status": "ok" if not check or report.ok else "rejected", "outcome": report.outcome,
              "name": report.problem.name, "method": report.method.name if report.method else None,
              "checked": check, "claims": len(report.certificate["claims"]), "values": report.values()}
    if check and not report.ok:
        record["error"] = f"the kernel rejected the certificate: {report.check}"
    elif keep:  # verified (or unchecked, as asked): the machine that writes the results keeps it
        record["certificate_json"] = dumps(report.certificate)
    if report.undecided:  # a partial answer: status "undecided", the decided claims in "values"
        record["undecided"] = {what: why for what, why in report.undecided}
        record["status"] = "undecided" if record["status"] == "ok" else record["status"]
    return record


def _judge(task: Task, tolerance: str) -> dict:
    row = judge_row(task.row or {}, tolerance=tolerance, number=int(task.id.rsplit(":", 1)[-1]))
    record = {"name": row.name, "method": row.method, "quantity": row.quantity, "claimed": row.claimed}
    if row.verdict is None:
        return {"status": "error", "outcome": "bad_input", **record, "error": row.error}
    v = row.verdict
    verdict = {"status": str(v.status), "exact": _jsonable(v.exact), "message": v.message}
    if v.relative_gap is not None:
        verdict["relative_gap"] = str(v.relative_gap)
    if v.counterexample is not None:
        verdict["counterexample"] = _jsonable(v.counterexample)
    return {"status": "ok", "outcome": "refuted" if v.status == "invalid" else "proved", **record, "verdict": verdict}


def _jsonable(x: Any) -> Any:
    """Exact values as the certificate writes them, containers element by element, anything else as text."""
    if isinstance(x, (Fraction, int, Infinity, RealAlgebraic)) and not isinstance(x, bool):
        return encode_real(x)
    if isinstance(x, dict):
        return {str(k): _jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_jsonable(v) for v in x]
    return x if isinstance(x, (str, bool)) or x is None else str(x)
