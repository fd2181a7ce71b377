"""Chunked tasks of `exactinv batch` (exactinv/interfaces/batch/chunks.py and
task.run_chunk): chunk sizes follow the measured durations and always cover
the corpus exactly; a chunk's records are exactly the records of its tasks
run one by one (only the measurements differ); a limit that fires mid-chunk
records the right problem and the rest of the chunk completes."""

from __future__ import annotations

import json
import random

from hypothesis import given, settings
from hypothesis import strategies as st

from exactinv.interfaces.batch.chunks import FIRST, FLOOR_SECONDS, SHARE, TARGET_SECONDS, ChunkSizer
from exactinv.interfaces.batch.corpus import Task
from exactinv.interfaces.batch.task import Limits, run_chunk, run_task

MEASUREMENTS = ("seconds", "cpu_seconds", "peak_mb")
SEGMENT = {"G": [[1], [-1]], "b": [1, 1]}


@settings(max_examples=200, deadline=None)
@given(total=st.integers(1, 5000), threads=st.integers(1, 64),
       durations=st.lists(st.floats(0, 100, allow_nan=False), max_size=30))
def test_chunks_cover_the_corpus_and_respect_the_fair_share(total, threads, durations):
    sizer = ChunkSizer()
    sizer.observe({"seconds": d} for d in durations)
    mean = max(sum(durations) / len(durations), 1e-4) if durations else None
    remaining, sizes = total, []
    while remaining:
        size = sizer.next_size(remaining, threads)
        assert 1 <= size <= remaining
        if mean is None:
            assert size == min(FIRST, remaining)
        else:
            fair = -(-remaining // (threads * SHARE))
            floor = max(int(FLOOR_SECONDS / mean), 1)
            # never more than the fair share of what is left, unless that is under the floor's length
            assert size <= max(fair, floor)
            assert size == remaining or size >= floor  # never under the floor while more is left
            assert size * mean <= TARGET_SECONDS or size == 1  # about two seconds at most
        sizes.append(size)
        remaining -= size
    assert sum(sizes) == total


def test_the_tail_of_a_corpus_goes_in_chunks_of_a_quarter_second_not_one_by_one():
    sizer = ChunkSizer()
    sizer.observe([{"seconds": 0.02}] * 10)  # 20 ms problems: the floor is 12 of them
    remaining, sizes = 1000, []
    while remaining:
        sizes.append(sizer.next_size(remaining, 2))
        remaining -= sizes[-1]
    assert sizes[0] == 100 and min(sizes[:-1]) == 12 and sizes[-1] >= 1  # 2 s chunks first, never one by one
    assert len(sizes) <= 30 and sizes == sorted(sizes, reverse=True)


def test_chunk_size_follows_the_measured_duration():
    sizer = ChunkSizer()
    assert sizer.next_size(10**6, 2) == 2  # nothing measured
    sizer.observe([{"seconds": 0.01}] * 10)
    assert sizer.next_size(10**6, 2) == 200  # 200 problems of 10 ms: two seconds
    sizer.observe([{"seconds": 0.19}] * 10)  # the mean is now 0.1 s
    assert sizer.next_size(10**6, 2) == 20
    sizer.observe([{"seconds": "x"}, {}, {"seconds": float("inf")}])  # no measurement: ignored
    assert sizer.count == 20


def _problem(i: int, rng: random.Random) -> dict:
    a, b = rng.randint(1, 4), rng.randint(0, 3)
    methods = [{"taylor": 1}, {"taylor": 3}, {"pade": [1, 2]}, "backward_euler", "rk4", {"theta": "1/2"}]
    if i % 2:
        poly = {"G": [[1, 0], [-1, 0], [0, 1], [0, -1]], "b": [rng.randint(1, 3) for _ in range(4)]}
    else:
        poly = {"vertices": [[rng.randint(-4, 4), rng.randint(-4, 4)] for _ in range(5)] + [[5, 5], [-5, -5], [5, -5]]}
    return {"name": f"p{i}", "system": {"A": [[-a, b], [-b, -a + (i % 3 == 0) * 5]]}, "polyhedron": poly,
            "method": methods[i % len(methods)]}


def _exact(record: dict) -> dict:
    return {k: v for k, v in record.items() if k not in MEASUREMENTS}


def test_a_chunk_gives_exactly_the_records_of_its_tasks_run_one_by_one():
    rng = random.Random(24)
    tasks = [Task(f"p{i}", "certify", text=json.dumps(_problem(i, rng)), source="corpus.jsonl") for i in range(24)]
    tasks.append(Task("unread", "certify", error="unread.json: cannot read"))
    tasks.append(Task("typo", "certify", text='{"system": {"A": [[-1]]}, "polyhedron": {"G": [[1], [-1]], "b": [1, 1]}, '
                                              '"methd": "rk4"}'))
    limits = Limits(timeout=120, keep_certificate=True)
    chunked = run_chunk(tasks, limits) + run_chunk(tasks[::-1], limits)  # the same sandbox, reused, any order
    single = [run_task(t, limits) for t in tasks]
    assert [_exact(r) for r in chunked] == [_exact(r) for r in single] + [_exact(r) for r in single[::-1]]
    statuses = [r["status"] for r in single]
    assert statuses.count("ok") == 24 and statuses[-2:] == ["error", "error"]
    outcomes = {r["outcome"] for r in single[:24]}
    assert outcomes == {"proved", "refuted"}  # both kinds of answer are compared, not only one
    assert all(r["certificate_json"].startswith("{") for r in single[:24] if r["status"] == "ok")


def _slow() -> dict:
    """Taylor-45 on a dense 4 x 4 system and 24 random facets: tens of seconds (tests/test_batch.py)."""
    rng = random.Random(3)
    A = [[-30 if i == j else rng.randint(-9, 9) for j in range(4)] for i in range(4)]
    G = [[rng.randint(-9, 9) for _ in range(4)] for _ in range(24)]
    return {"name": "slow", "system": {"A": A}, "polyhedron": {"G": G, "b": [rng.randint(5, 20) for _ in G]},
            "method": {"taylor": 45}}


def _hog(n: int = 20) -> dict:
    """The cross-polytope of R^20 by its 40 vertices: 2^20 facets exhaust 200 MB (tests/test_batch.py)."""
    unit = [[1 if i == j else 0 for j in range(n)] for i in range(n)]
    return {"name": "hog", "system": {"A": [[-x for x in row] for row in unit]},
            "polyhedron": {"vertices": unit + [[-x for x in row] for row in unit]}, "method": {"taylor": 2}}


def _decay(c: int) -> Task:
    """x' = -cx on [-1, 1], Taylor-2: the largest threshold is 2/c."""
    return Task(f"decay-{c}", "certify", text=json.dumps({"system": {"A": [[-c]]}, "polyhedron": SEGMENT,
                                                           "method": {"taylor": 2}}))


def test_limits_firing_mid_chunk_record_the_culprit_and_the_rest_completes():
    # Two chunks, each with its own limits: the slow problem takes about 6 s of CPU (over 2 s on any
    # machine), the hog about 1 s of CPU to pass 200 MB (within 120 s on any load).
    slow = [_decay(1), Task("slow", "certify", text=json.dumps(_slow())), _decay(2)]
    hog = [_decay(3), Task("hog", "certify", text=json.dumps(_hog())), _decay(4)]
    records = run_chunk(slow, Limits(timeout=2, memory_mb=200)) + run_chunk(hog, Limits(timeout=120, memory_mb=200))
    assert [r["id"] for r in records] == [t.id for t in slow + hog]
    assert [r["status"] for r in records] == ["ok", "timeout", "ok", "ok", "memory", "ok"]
    assert "2 s" in records[1]["error"] and records[1]["outcome"] == "error" and records[4]["outcome"] == "error"
    assert [r["values"]["largest_threshold"] for r in records if r["status"] == "ok"] == ["2", "1", "2/3", "1/2"]
