"""The long-lived sandbox of `exactinv batch` (exactinv/interfaces/batch/resident.py):
one forked child runs argument after argument; a run that breaches its time
or memory limit (Python's MemoryError, FLINT's abort, glibc's exit 127) or
crashes is recorded as such, the child is replaced, and the next run
completes; each run's limit and measurements are its own."""

from __future__ import annotations

import fcntl
import gc
import os
import signal
import time
from fractions import Fraction

import flint
import pytest

from exactinv.interfaces.batch.resident import Sandbox

_kept: list = []  # what a run leaves behind in the child (a long-lived process's growth)


def _work(job):
    """One job per kind: the sandbox's function is fixed, the argument says what to do."""
    kind, x = job
    if kind == "square":
        return str(flint.fmpq(*x) ** 2)
    if kind == "pid":
        return os.getpid()
    if kind == "forever":  # FLINT multiplications that never return to Python for long
        y = flint.fmpz(3) ** 100000
        while True:
            y = (y * y) % (flint.fmpz(10) ** 200000 + 7)
    if kind == "bytes":  # Python's allocation of x bytes
        return len(bytearray(x))
    if kind == "keep":  # x bytes kept in the child after the run
        _kept.append(bytearray(x))
        return sum(len(b) for b in _kept)
    if kind == "flint":  # 3^x: FLINT/GMP abort when the allocation fails
        return str(flint.fmpz(3) ** x)[:3]
    if kind == "tls":  # glibc's exit on failed thread-local allocation (dl-tls.c)
        os.write(2, b"cannot allocate memory for thread-local data: ABORT\n")
        os._exit(127)
    if kind == "segv":
        os.kill(os.getpid(), signal.SIGSEGV)
    if kind == "raise":
        raise ZeroDivisionError(x)
    if kind == "object":
        return object()
    if kind == "gc":  # what the child's collector walks, and who watches it
        return [gc.get_freeze_count(), len(gc.callbacks), len(gc.get_objects())]
    if kind == "len":
        return len(x)
    if kind == "deaf":  # close the child's end of the jobs pipe: it replies, then cannot read the next job
        for fd in map(int, os.listdir("/proc/self/fd")):
            try:
                pipe = os.readlink(f"/proc/self/fd/{fd}").startswith("pipe:")
                if fd > 2 and pipe and fcntl.fcntl(fd, fcntl.F_GETFL) & os.O_ACCMODE == os.O_RDONLY:
                    os.close(fd)
            except OSError:
                pass
        return os.getpid()
    if kind == "spin":  # about x seconds of CPU
        end = time.process_time() + x
        while time.process_time() < end:
            pass
        return x
    if kind == "nap":  # x seconds of wall time, no CPU (a clock that a loaded machine does not stretch)
        time.sleep(x)
        return x
    raise AssertionError(kind)


@pytest.fixture
def box():
    """A sandbox running `_work`, closed after the test (its child forks at the first run, so a test may
    monkeypatch the module first)."""
    sandbox = Sandbox(_work)
    yield sandbox
    sandbox.close()


def test_one_child_runs_job_after_job(box):
    pids = {box.run(("pid", None), timeout=30).value for _ in range(20)}
    assert len(pids) == 1 and os.getpid() not in pids and box.forks == 1
    assert [box.run(("square", (k, 3)), timeout=30).value for k in range(1, 4)] == ["1/9", "4/9", "1"]


def test_a_timeout_mid_sequence_kills_the_child_and_the_next_job_runs_in_a_new_one(box):
    first = box.run(("pid", None), timeout=30).value
    out = box.run(("forever", None), timeout=1)
    assert out.status == "timeout" and "1 s" in out.message and out.seconds >= 1
    with pytest.raises(ChildProcessError):
        os.waitpid(first, os.WNOHANG)  # reaped: the old child is gone
    after = box.run(("square", (2, 5)), timeout=30)
    assert after.status == "ok" and after.value == "4/25" and box.forks == 2


def test_memory_breaches_mid_sequence_are_memory_outcomes_and_the_rest_completes(box):
    outcomes = [box.run(job, timeout=60, memory_mb=200) for job in (
        ("bytes", 10**7), ("bytes", 2 * 10**9), ("square", (1, 2)), ("flint", 10**10), ("square", (1, 3)),
        ("tls", None), ("square", (1, 4)))]
    assert [o.status for o in outcomes] == ["ok", "memory", "ok", "memory", "ok", "memory", "ok"]
    assert outcomes[1].message == "MemoryError (the --memory limit of 200 MB)" and "SIGABRT" in outcomes[3].message
    assert "code 127" in outcomes[5].message and "thread-local" in outcomes[5].message
    assert [o.value for o in outcomes[::2]] == [10**7, "1/4", "1/9", "1/16"]
    assert box.forks == 4  # the first child, then one after each breach


def test_the_memory_limit_is_counted_from_where_each_run_starts(box):
    for k in range(1, 4):  # 150 MB kept per run: 450 MB in all, each run within its own 200 MB
        out = box.run(("keep", 150 * 2**20), timeout=60, memory_mb=200)
        assert out.status == "ok" and out.value == k * 150 * 2**20
    assert box.forks == 1
    assert box.run(("bytes", 300 * 2**20), timeout=60, memory_mb=200).status == "memory"


def test_crashes_are_reported_and_never_raised(box):
    raised = box.run(("raise", "1/0 in the child"), timeout=30)
    assert raised.status == "crash" and raised.message == "ZeroDivisionError: 1/0 in the child"
    died = box.run(("segv", None), timeout=30)
    assert died.status == "crash" and "SIGSEGV" in died.message
    odd = box.run(("object", None), timeout=30)
    assert odd.status == "crash" and "not JSON-able" in odd.message
    unlimited = box.run(("tls", None), timeout=30)  # without a memory limit glibc's exit is a crash
    assert unlimited.status == "crash" and "thread-local" in unlimited.message
    assert box.run(("square", (3, 1)), timeout=30).value == "9"


def test_measurements_are_per_run(box):
    big = box.run(("bytes", 400 * 2**20), timeout=60)
    small = box.run(("square", (1, 2)), timeout=60)
    assert big.peak_mb >= 400 and small.peak_mb < big.peak_mb - 300  # the high-water mark is reset per run
    spin = box.run(("spin", 0.3), timeout=60)
    assert spin.cpu_seconds >= 0.29 and box.run(("square", (1, 2)), timeout=60).cpu_seconds < spin.cpu_seconds


def test_the_child_is_renewed_after_many_runs(monkeypatch, box):
    from exactinv.interfaces.batch import resident

    monkeypatch.setattr(resident, "RENEW_AFTER", 5)
    pids = [box.run(("pid", None), timeout=30).value for _ in range(12)]
    assert pids[:5] == [pids[0]] * 5 and pids[5:10] == [pids[5]] * 5 and len(set(pids)) == 3


def _state(pid: int) -> str:
    with open(f"/proc/{pid}/stat", encoding="ascii") as fh:
        return fh.read().rsplit(") ", 1)[1][0]


def _kill_idle(box: Sandbox, how: str) -> int:
    """Kill the idle child between two runs: left a zombie for the sandbox to notice, also reaped
    by someone else (a waitpid in this process, as a test or a library might), or just killed (it
    may still hold the pipes when the next job is sent: dying as the job arrives)."""
    pid = box.pid
    os.kill(pid, signal.SIGKILL)
    if how == "reaped elsewhere":
        os.waitpid(pid, 0)
    elif how == "zombie":
        while _state(pid) != "Z":  # dead, not yet reaped
            time.sleep(0.01)
    return pid


@pytest.mark.parametrize("how", ["zombie", "reaped elsewhere", "just killed"])
def test_an_idle_child_killed_between_runs_is_replaced_and_the_next_job_runs(how, box):
    first = box.run(("pid", None), timeout=30).value
    assert _kill_idle(box, how) == first
    after = box.run(("square", (2, 7)), timeout=30)  # the job is not lost to the dead child
    assert (after.status, after.value, box.forks) == ("ok", "4/49", 2)
    assert box.run(("pid", None), timeout=30).value not in (first, os.getpid())


def test_a_child_that_dies_while_running_is_still_the_jobs_crash(box):
    box.run(("pid", None), timeout=30)
    died = box.run(("segv", None), timeout=30)
    assert died.status == "crash" and "SIGSEGV" in died.message
    assert box.run(("square", (1, 5)), timeout=30).value == "1/25" and box.forks == 2


def test_a_fork_of_the_parent_never_kills_the_parents_child(box):
    child = box.run(("pid", None), timeout=30).value
    pid = os.fork()
    if pid == 0:  # a fork of this process (a Dask worker forked from the batch's process) drops the box
        try:
            box.close()
            os._exit(0 if box.pid is None else 1)
        finally:
            os._exit(2)
    assert os.waitpid(pid, 0)[1] == 0
    assert box.run(("pid", None), timeout=30).value == child and box.forks == 1  # still alive, still used


def test_a_chunk_after_the_resident_child_died_is_exact_and_complete():
    """batch.task.run_chunk on this thread's resident sandbox: the child is killed between two
    chunks (as between two Dask tasks); the second chunk's records are those of each task run
    alone (exact values; only the measurements differ), none an error."""
    import json

    from exactinv.interfaces.batch.corpus import Task
    from exactinv.interfaces.batch.task import Limits, chunk_sandbox, run_chunk, run_task

    def decay(c: int, taylor: int) -> Task:  # x' = -cx on [-1, 1]; Taylor-1 and -2: the largest threshold is 2/c
        return Task(f"d{c}-{taylor}", "certify", text=json.dumps({
            "system": {"A": [[-c]]}, "polyhedron": {"G": [[1], [-1]], "b": [1, 1]}, "method": {"taylor": taylor}}))

    limits = Limits(timeout=60)
    first = run_chunk([decay(1, 1), decay(2, 2)], limits)
    box = chunk_sandbox()
    forks = box.forks
    _kill_idle(box, "just killed")
    second = [decay(3, 1), decay(4, 2), decay(5, 2)]
    records = run_chunk(second, limits)
    assert box.forks == forks + 1
    assert [r["status"] for r in first + records] == ["ok"] * 5, [r.get("error") for r in first + records]
    assert [r["values"]["largest_threshold"] for r in records] == ["2/3", "1/2", "2/5"]
    drop = ("seconds", "cpu_seconds", "peak_mb")
    assert [{k: v for k, v in r.items() if k not in drop} for r in records] == [
        {k: v for k, v in run_task(t, limits).items() if k not in drop} for t in second]


def test_the_inherited_heap_is_frozen_in_the_child_and_the_parents_gc_callbacks_dropped():
    # a parent with 50,000 tracked objects of its own (a corpus of tasks) and a GC callback (Dask's
    # worker registers one): the child's collector walks neither those objects nor calls that callback
    corpus = [[k] for k in range(50_000)]
    seen: list = []
    gc.callbacks.append(seen.append)
    box = Sandbox(_work)
    try:
        frozen, callbacks, walked = box.run(("gc", None), timeout=30).value
        assert frozen >= len(corpus) and callbacks == 0 and walked < len(corpus)
        assert box.run(("square", (2, 3)), timeout=30).value == "4/9"
    finally:
        gc.callbacks.remove(seen.append)
        box.close()
    assert gc.get_freeze_count() == 0  # the parent's own collector is untouched


def test_a_child_that_cannot_take_its_first_job_is_a_crash_not_a_loop(monkeypatch, box):
    from exactinv.interfaces.batch import resident

    monkeypatch.setattr(resident, "_settle", lambda: os._exit(7))  # every fresh child dies at once
    out = box.run(("square", (1, 2)), timeout=30, memory_mb=100)
    assert out.status == "crash" and "code 7" in out.message and box.forks == 1


# --- run_all: the pipelined protocol (job k + 1 in the pipe while job k runs) ---------------------

def test_run_all_is_run_one_by_one_in_one_child(box):
    jobs = [("square", (k, 7)) for k in range(1, 30)] + [("pid", None)] * 5
    outcomes = box.run_all(jobs, timeout=30)
    assert [o.value for o in outcomes[:29]] == [str(Fraction(k, 7) ** 2) for k in range(1, 30)]
    assert len({o.value for o in outcomes[29:]}) == 1 and box.forks == 1
    assert all(o.status == "ok" and o.seconds > 0 for o in outcomes)


def test_a_queued_job_that_fails_at_once_keeps_its_stderr(monkeypatch, box):
    """Found by CI (stage 3, a loaded machine): glibc's thread-local abort queued behind a job was decoded as a
    plain crash ("code 127 without a result"), because the parent took the stderr size where the queued job's
    output starts after reading the previous reply, by which time the child had already taken the job and
    written.  A parent slowed after each reply makes that order certain; the size is now taken before the
    job is queued."""
    from exactinv.interfaces.batch import resident

    read_frame = resident._Reader.read_frame

    def slow(self, deadline):
        frame = read_frame(self, deadline)
        time.sleep(0.3)  # the child takes the queued job and writes meanwhile
        return frame

    monkeypatch.setattr(resident._Reader, "read_frame", slow)
    outcomes = box.run_all([("square", (1, 2)), ("tls", None), ("square", (1, 3))], timeout=30, memory_mb=200)
    assert [o.status for o in outcomes] == ["ok", "memory", "ok"], [o.message for o in outcomes]
    assert "thread-local" in outcomes[1].message


@pytest.mark.parametrize("culprit, memory_mb, status", [
    (("forever", None), None, "timeout"), (("bytes", 2 * 10**9), 200, "memory"), (("flint", 10**10), 200, "memory"),
    (("tls", None), 200, "memory"), (("segv", None), None, "crash"), (("raise", "x"), 200, "crash")])
def test_a_breach_mid_pipeline_is_the_culprits_and_the_queued_job_runs_in_a_fresh_child(culprit, memory_mb, status, box):
    """The culprit is the job the child had taken (its one-byte answer); the job queued behind it
    in the pipe was never taken by the dead child, so it is resent, and the rest completes."""
    jobs = [("pid", None), ("square", (1, 2)), culprit, ("pid", None), ("square", (2, 3)), ("pid", None)]
    outcomes = box.run_all(jobs, timeout=2, memory_mb=memory_mb)
    assert [o.status for o in outcomes] == ["ok", "ok", status, "ok", "ok", "ok"], [o.message for o in outcomes]
    assert outcomes[1].value == "1/4" and outcomes[4].value == "4/9"
    assert outcomes[0].value != outcomes[3].value == outcomes[5].value and box.forks == 2


def test_a_child_that_dies_before_taking_the_queued_job_never_has_it_recorded_against_it(box):
    """'deaf' replies, then the child cannot read its pipe and exits: the job queued behind it was
    never taken (no one-byte answer), so it runs in a fresh child and is ok."""
    outcomes = box.run_all([("deaf", None), ("square", (3, 4)), ("pid", None)], timeout=30)
    assert [(o.status, o.message) for o in outcomes] == [("ok", "")] * 3
    assert outcomes[1].value == "9/16" and outcomes[2].value != outcomes[0].value and box.forks == 2


def test_each_pipelined_job_has_its_own_clock(box):
    """Three jobs of 0.6 s (asleep) under a 1 s limit: the queued job's clock starts when the child
    is free to take it, not when it was written to the pipe (0.6 s earlier, which would put it at
    1.2 s).  Sleeping, not spinning: the machine's load does not stretch the jobs' wall time."""
    outcomes = box.run_all([("nap", 0.6)] * 3, timeout=1.0)
    assert [o.status for o in outcomes] == ["ok"] * 3 and box.forks == 1, [o.message for o in outcomes]
    assert all(0.55 < o.seconds < 1.0 for o in outcomes)


def test_each_pipelined_job_has_its_own_cpu_account(box):
    """Three jobs of 0.3 s of CPU: each is charged its own CPU, not the previous job's too."""
    outcomes = box.run_all([("spin", 0.3)] * 3, timeout=60)
    assert [o.status for o in outcomes] == ["ok"] * 3 and box.forks == 1
    assert all(0.29 <= o.cpu_seconds < 0.55 for o in outcomes), [o.cpu_seconds for o in outcomes]


def test_jobs_larger_than_the_pipe_are_sent_when_the_child_is_free(box):
    big = "x" * (box_capacity() * 3)
    outcomes = box.run_all([("len", big), ("len", big), ("len", "abc")], timeout=30)
    assert [o.value for o in outcomes] == [len(big), len(big), 3] and box.forks == 1


def box_capacity() -> int:
    read, write = os.pipe()
    try:
        return fcntl.fcntl(write, fcntl.F_GETPIPE_SZ)
    finally:
        os.close(read)
        os.close(write)


def test_run_all_renews_the_child_after_many_runs(monkeypatch, box):
    from exactinv.interfaces.batch import resident

    monkeypatch.setattr(resident, "RENEW_AFTER", 5)
    pids = [o.value for o in box.run_all([("pid", None)] * 12, timeout=30)]
    assert pids[:5] == [pids[0]] * 5 and pids[5:10] == [pids[5]] * 5 and len(set(pids)) == 3


def test_an_interrupt_in_the_parent_mid_pipeline_leaves_no_child_holding_a_job():
    """Ctrl-C (here a SIGALRM handler raising KeyboardInterrupt) while the parent waits on a job with
    another queued behind it: the child is killed and reaped, and the next runs start afresh --
    no stale reply or one-byte answer of the interrupted jobs is ever read as theirs."""
    def interrupt(signum, frame):
        raise KeyboardInterrupt

    box = Sandbox(_work)
    old = signal.signal(signal.SIGALRM, interrupt)
    try:
        first = box.run(("pid", None), timeout=30).value
        signal.setitimer(signal.ITIMER_REAL, 0.3)
        with pytest.raises(KeyboardInterrupt):
            box.run_all([("spin", 2.0), ("square", (1, 2)), ("spin", 2.0)], timeout=30)
        assert box.pid is None
        with pytest.raises(ChildProcessError):
            os.waitpid(first, os.WNOHANG)  # killed and reaped
        outcomes = box.run_all([("square", (5, 6)), ("pid", None)], timeout=30)
        assert [o.value for o in outcomes][0] == "25/36" and outcomes[1].value != first and box.forks == 2
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)
        box.close()


def test_pipelined_the_parent_wakes_once_per_job_one_by_one_twice(box):
    """The child that finds the next job waiting writes its reply and the next job's one-byte answer
    in one write, so the parent sleeps (a voluntary context switch) once per job; run one by one,
    it sleeps for the answer and again for the reply.  Jobs of 20 ms of CPU: the parent is asleep
    long before each reply."""
    import resource

    def sleeps() -> int:
        return resource.getrusage(resource.RUSAGE_SELF).ru_nvcsw

    box.run(("pid", None), timeout=30)
    before = sleeps()
    piped = box.run_all([("spin", 0.02)] * 40, timeout=30)
    pipelined = (sleeps() - before) / 40
    before = sleeps()
    single = [box.run(("spin", 0.02), timeout=30) for _ in range(40)]
    one_by_one = (sleeps() - before) / 40
    assert [o.status for o in piped + single] == ["ok"] * 80 and box.forks == 1
    assert pipelined <= 1.3 and one_by_one >= 1.7, (pipelined, one_by_one)
