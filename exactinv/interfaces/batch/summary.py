"""The summary of a batch: counts by status (and, for judged oracle rows, by
verdict) and by outcome, times and memory, and the table ``exactinv batch``
prints.  It covers **every record of the results file** -- a resumed run's
earlier records included -- so its exit code describes the whole outcome
(:mod:`exactinv.interfaces.exit_codes`); ``ran`` and ``seconds`` are this run's.

>>> tally = Tally()
>>> for r in ({"status": "ok", "seconds": 0.5, "peak_mb": 90.0}, {"status": "timeout", "seconds": 2.0, "peak_mb": 60.0}):
...     tally.add(r)
>>> s = tally.summary("out.jsonl", total=3, skipped=1, ran=2, seconds=2.5, workers=2)
>>> s.ran, s.count("ok"), s.ok, s.exit_code
(2, 1, False, 4)
>>> print(s.table())
status        count    mean s     max s   max MB
ok                1     0.500     0.500     90.0
rejected          0         -         -        -
error             0         -         -        -
timeout           1     2.000     2.000     60.0
memory            0         -         -        -
outcomes: proved 1, error 1 (exit code 4)
3 problems: 1 already in out.jsonl (skipped), 2 run in 2.5 s on 2 workers (0.80 problems/s); the table covers all 2 records in out.jsonl
"""  # noqa: E501 (doctest output)

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, field

from ..exit_codes import CODES, exit_code
from .task import STATUSES, record_outcome

__all__ = ["BatchSummary", "Tally"]


@dataclass(frozen=True)
class BatchSummary:
    """A batch after one run.  ``total`` tasks in the corpus, ``skipped`` of
    them already recorded in ``out`` before this run, ``ran`` run this time in
    ``seconds`` of wall time on ``workers`` worker threads.  ``stats``: per
    status (count, summed seconds, max seconds, max peak MB), ``verdicts``: the
    oracle verdicts of judged rows, ``outcomes``: per outcome -- all three over
    **every record in out**, earlier runs' included.  ``ignored``: the files of
    the inputs that were not read, each with the reason.  ``exit_code``: the
    highest code of the outcomes; ``ok``: it is 0."""

    out: str
    total: int
    skipped: int
    ran: int
    seconds: float
    workers: int
    stats: tuple[tuple[str, int, float, float, float], ...] = field(repr=False)
    verdicts: tuple[tuple[str, int], ...] = ()
    outcomes: tuple[tuple[str, int], ...] = ()
    ignored: tuple[tuple[str, str], ...] = field(default=(), repr=False)

    @property
    def records(self) -> int:
        """How many records ``out`` holds (one per id)."""
        return sum(row[1] for row in self.stats)

    def count(self, status: str) -> int:
        """How many records of ``out`` have ``status`` (0 for a status never seen).

        >>> s = BatchSummary("out.jsonl", 3, 0, 3, 1.0, 1, (("ok", 2, 0.4, 0.3, 50.0), ("error", 1, 0.1, 0.1, 40.0)))
        >>> s.count("ok"), s.count("error"), s.count("timeout")
        (2, 1, 0)
        """
        return next((row[1] for row in self.stats if row[0] == status), 0)

    @property
    def exit_code(self) -> int:
        """The exit code of the whole results file: the highest code of its outcomes."""
        return exit_code(o for o, n in self.outcomes if n)

    @property
    def ok(self) -> bool:
        return self.exit_code == 0

    @property
    def throughput(self) -> float:
        """Tasks per second of wall time in this run."""
        return self.ran / self.seconds if self.seconds > 0 else 0.0

    @property
    def task_seconds(self) -> float:
        """The summed wall time of the recorded tasks themselves (each in its child process)."""
        return sum(row[2] for row in self.stats)

    def table(self) -> str:
        """The summary table printed at the end of ``exactinv batch``.

        Mean seconds per status = summed / count (0.4 / 2 = 0.2 below); a
        judged corpus adds a line of oracle verdicts.

        >>> s = BatchSummary("out.jsonl", 2, 0, 2, 0.5, 1, (("ok", 2, 0.4, 0.3, 50.0),), (("valid", 2),),
        ...                  (("proved", 2),))
        >>> print(s.table())
        status        count    mean s     max s   max MB
        ok                2     0.200     0.300     50.0
        oracle verdicts: valid 2
        outcomes: proved 2 (exit code 0)
        2 problems: 0 already in out.jsonl (skipped), 2 run in 0.5 s on 1 worker (4.00 problems/s); the table covers all 2 records in out.jsonl
        """  # noqa: E501 (doctest output)
        lines = [f"{'status':<10}{'count':>9}{'mean s':>10}{'max s':>10}{'max MB':>9}"]
        for status, n, total, slowest, peak in self.stats:
            if n:
                lines.append(f"{status:<10}{n:>9}{total / n:>10.3f}{slowest:>10.3f}{peak:>9.1f}")
            else:
                lines.append(f"{status:<10}{0:>9}{'-':>10}{'-':>10}{'-':>9}")
        if self.verdicts:
            lines.append("oracle verdicts: " + ", ".join(f"{v} {n}" for v, n in self.verdicts))
        if self.outcomes:
            lines.append("outcomes: " + ", ".join(f"{o} {n}" for o, n in self.outcomes if n)
                         + f" (exit code {self.exit_code})")
        if self.ignored:
            lines.append(f"not read: {len(self.ignored)} file{'' if len(self.ignored) == 1 else 's'} of the inputs "
                         "(" + "; ".join(f"{path}: {why}" for path, why in self.ignored[:3])
                         + ("; ..." if len(self.ignored) > 3 else "") + ")")
        plural = "" if self.total == 1 else "s"
        head = f"{self.total} problem{plural}: {self.skipped} already in {self.out} (skipped), "
        tail = f"; the table covers all {self.records} records in {self.out}"
        if not self.ran:
            lines.append(head + "nothing left to run" + tail)
        else:
            lines.append(head + f"{self.ran} run in {self.seconds:.1f} s on {self.workers} "
                         f"worker{'' if self.workers == 1 else 's'} ({self.throughput:.2f} problems/s)" + tail)
        return "\n".join(lines)


class Tally:
    """Counts records as they arrive; :meth:`summary` freezes them."""

    def __init__(self) -> None:
        self.n: Counter = Counter()
        self.time: Counter = Counter()
        self.slowest: dict[str, float] = {}
        self.peak: dict[str, float] = {}
        self.verdicts: Counter = Counter()
        self.outcomes: Counter = Counter()

    def add(self, record: dict) -> None:
        """Count one result record: its status, seconds, peak MB and oracle verdict (if judged).

        >>> t = Tally()
        >>> t.add({"status": "ok", "seconds": 0.25, "peak_mb": 70.0, "verdict": {"status": "valid"}})
        >>> t.add({"status": "ok", "seconds": 0.5})
        >>> t.n["ok"], t.time["ok"], t.slowest["ok"], t.peak["ok"], dict(t.verdicts)
        (2, 0.75, 0.5, 70.0, {'valid': 1})
        """
        status = str(record.get("status", "error"))
        seconds, peak = float(record.get("seconds", 0.0)), float(record.get("peak_mb", 0.0))
        self.n[status] += 1
        self.time[status] += seconds
        self.slowest[status] = max(self.slowest.get(status, 0.0), seconds)
        self.peak[status] = max(self.peak.get(status, 0.0), peak)
        if isinstance(record.get("verdict"), dict):
            self.verdicts[record["verdict"]["status"]] += 1
        self.outcomes[record_outcome(record)] += 1

    def summary(self, out: str, total: int, skipped: int, ran: int, seconds: float, workers: int,
                ignored: tuple[tuple[str, str], ...] = ()) -> BatchSummary:
        """Freeze the counts: every status of STATUSES in order (unseen ones with count 0), then others.

        >>> t = Tally()
        >>> t.add({"status": "error", "seconds": 0.1})
        >>> s = t.summary("out.jsonl", total=1, skipped=0, ran=1, seconds=0.2, workers=1)
        >>> [row[:2] for row in s.stats], s.ran, s.ok, s.outcomes
        ([('ok', 0), ('rejected', 0), ('error', 1), ('timeout', 0), ('memory', 0)], 1, False, (('error', 1),))
        """
        order = list(STATUSES) + sorted(set(self.n) - set(STATUSES))
        stats = tuple((s, self.n[s], self.time[s], self.slowest.get(s, 0.0), self.peak.get(s, 0.0)) for s in order)
        outcomes = tuple((o, self.outcomes[o]) for o in sorted(self.outcomes, key=CODES.__getitem__))
        return BatchSummary(out, total, skipped, ran, seconds, workers, stats, tuple(sorted(self.verdicts.items())),
                            outcomes, tuple(ignored))
