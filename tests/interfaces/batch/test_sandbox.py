"""The per-task sandbox of `exactinv batch` (exactinv/interfaces/batch/sandbox.py):
a runaway FLINT computation is really stopped, an allocation past the memory
limit ends the child (Python's MemoryError, FLINT's and GMP's abort), and
whatever else goes wrong in the child is reported, never raised or hung."""

from __future__ import annotations

import os
import signal

import flint

from exactinv.interfaces.batch.sandbox import run_limited


def _flint_forever(_):
    """A computation that never returns to Python for long: FLINT multiplications, forever."""
    x = flint.fmpz(3) ** 100000
    while True:
        x = (x * x) % (flint.fmpz(10) ** 200000 + 7)


def _child_pid(_):
    return os.getpid()


def test_the_result_comes_back_from_a_forked_child():
    out = run_limited(_child_pid, None, timeout=30, memory_mb=100)
    assert out.status == "ok" and out.value != os.getpid() and out.peak_mb > 0
    assert run_limited(lambda q: [str(flint.fmpq(1, 3) * q), {"k": True}], 6).value == ["2", {"k": True}]


def test_a_runaway_flint_loop_is_killed_at_the_timeout():
    out = run_limited(_flint_forever, None, timeout=1)
    assert out.status == "timeout" and "1 s" in out.message
    assert out.seconds >= 1


def test_python_allocation_past_the_limit_is_a_memory_outcome():
    out = run_limited(lambda n: len(bytearray(n)), 2 * 10**9, timeout=30, memory_mb=100)
    assert out.status == "memory" and "MemoryError" in out.message
    assert run_limited(lambda n: len(bytearray(n)), 10**7, timeout=30, memory_mb=100).value == 10**7


def test_a_flint_allocation_past_the_limit_is_a_memory_outcome():
    # 3^(10^10) has about 1.6e10 bits = 2 GB: FLINT/GMP abort the child when the allocation fails
    out = run_limited(lambda e: str(flint.fmpz(3) ** e)[:3], 10**10, timeout=60, memory_mb=200)
    assert out.status == "memory" and "SIGABRT" in out.message


def test_exceptions_and_fatal_signals_in_the_child_are_reported():
    def boom(_):
        raise ZeroDivisionError("1/0 in the child")

    out = run_limited(boom, None)
    assert out.status == "crash" and out.message == "ZeroDivisionError: 1/0 in the child"
    died = run_limited(lambda _: os.kill(os.getpid(), signal.SIGSEGV), None)
    assert died.status == "crash" and "SIGSEGV" in died.message
    unserialisable = run_limited(lambda _: object(), None)
    assert unserialisable.status == "crash" and "exited with code 3" in unserialisable.message


def _glibc_tls_abort(_):
    """What glibc does when it cannot allocate a thread's or a dlopen'ed library's thread-local
    storage (dl-tls.c, ``oom``): one line on standard error, then ``_exit(127)`` -- no signal, no
    Python exception.  Seen once in CI, when the R^20 cross-polytope of tests/test_batch.py hit the
    200 MB limit under the lowest declared versions."""
    os.write(2, b"cannot allocate memory for thread-local data: ABORT\n")
    os._exit(127)


def _exit_with_words(_):
    os.write(2, b"something else went wrong\n")
    os._exit(5)


def test_glibc_giving_up_on_memory_is_a_memory_outcome_only_under_a_memory_limit():
    limited = run_limited(_glibc_tls_abort, None, timeout=30, memory_mb=200)
    assert limited.status == "memory" and "code 127" in limited.message and "thread-local" in limited.message
    unlimited = run_limited(_glibc_tls_abort, None, timeout=30)
    assert unlimited.status == "crash" and "thread-local" in unlimited.message


def test_an_exit_without_a_result_is_a_crash_quoting_the_childs_last_words():
    out = run_limited(_exit_with_words, None, timeout=30, memory_mb=200)
    assert out.status == "crash" and "code 5" in out.message and out.message.endswith("something else went wrong")
