"""`exactinv batch` beyond one machine, shown on localhost: the test starts a
real multi-process Dask cluster -- `dask scheduler` and two `dask worker`
processes, each its own process like a node of a cluster -- runs
`exactinv batch --scheduler tcp://127.0.0.1:PORT`, kills one worker (SIGKILL)
mid-run, and checks that every problem is recorded exactly once with exactly
the values of a plain loop over `interfaces.pipeline.certify`."""

from __future__ import annotations

import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import threading
import time

import pytest

distributed = pytest.importorskip("dask.distributed")

from exactinv.interfaces.cli import main  # noqa: E402
from exactinv.interfaces.pipeline import certify  # noqa: E402
from exactinv.interfaces.problem import load_problem  # noqa: E402

N = 40
STARTUP = 90  # seconds for the scheduler and both workers to come up (imports on a loaded machine)


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _problems() -> list[dict]:
    """N small problems (tens of milliseconds each with the kernel check): 2-D systems on hexagons
    with integer vertices, Taylor 1-4, RK4, backward Euler, Pade(1,2); some sets are not invariant."""
    import math
    methods = [{"taylor": 1}, {"taylor": 2}, {"taylor": 3}, {"taylor": 4}, "rk4", "backward_euler", {"pade": [1, 2]}]
    out = []
    for i in range(N):
        pts = [[round(10 * math.cos(2 * math.pi * j / 6 + i / 7)), round(10 * math.sin(2 * math.pi * j / 6 + i / 7))]
               for j in range(6)]
        a, b = 1 + i % 4, i % 3
        out.append({"name": f"c{i:03d}", "system": {"A": [[-a, b], [-b, -a + (i % 5 == 0) * 6]]},
                    "polyhedron": {"vertices": pts}, "method": methods[i % len(methods)]})
    return out


def _dask_cli() -> list[str]:
    exe = shutil.which("dask", path=os.path.dirname(sys.executable)) or shutil.which("dask")
    return [exe] if exe else [sys.executable, "-m", "distributed.cli.dask_spec"]


def _start(args: list[str], log) -> subprocess.Popen:
    return subprocess.Popen(_dask_cli() + args, stdout=log, stderr=subprocess.STDOUT, start_new_session=True)


def _stop(proc: subprocess.Popen) -> None:
    if proc.poll() is None:
        os.killpg(proc.pid, signal.SIGKILL)  # its own session: the process and anything it started
    proc.wait(timeout=30)


def _lines(path) -> int:
    try:
        with open(path) as fh:
            return sum(1 for _ in fh)
    except FileNotFoundError:
        return 0


def test_a_killed_worker_on_a_real_cluster_loses_nothing(tmp_path):
    if _dask_cli()[0] == sys.executable:
        pytest.skip("the dask command-line tool is not installed")
    problems = _problems()
    corpus = tmp_path / "corpus.jsonl"
    corpus.write_text("".join(json.dumps(p) + "\n" for p in problems))
    out = tmp_path / "results.jsonl"
    port = _free_port()
    address = f"tcp://127.0.0.1:{port}"
    log = open(tmp_path / "cluster.log", "w")
    procs: list[subprocess.Popen] = []
    try:
        procs.append(_start(["scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard"], log))
        for _ in range(2):
            procs.append(_start(["worker", address, "--nthreads", "1", "--no-nanny", "--no-dashboard",
                                 "--death-timeout", "60"], log))
        with distributed.Client(address, timeout=STARTUP) as client:
            client.wait_for_workers(2, timeout=STARTUP)
            victim_address = next(addr for addr, pid in client.run(os.getpid).items() if pid == procs[1].pid)
        killed = {}

        def kill_mid_run() -> None:
            """Once a fifth of the corpus is recorded and the victim is running a chunk, SIGKILL it."""
            deadline = time.monotonic() + 120
            with distributed.Client(address, timeout=30) as watcher:
                while time.monotonic() < deadline:
                    busy = watcher.processing(workers=[victim_address]).get(victim_address, ())
                    if _lines(out) >= N // 5 and busy:
                        break
                    time.sleep(0.02)
                killed["lines"], killed["busy"] = _lines(out), len(busy)
                os.kill(procs[1].pid, signal.SIGKILL)

        killer = threading.Thread(target=kill_mid_run, daemon=True)
        killer.start()
        code = main(["batch", str(corpus), "-o", str(out), "--scheduler", address, "--timeout", "60"])
        killer.join(timeout=30)
        assert procs[1].wait(timeout=30) == -signal.SIGKILL
        assert N // 5 <= killed["lines"] < N and killed["busy"] >= 1  # killed mid-run, with a chunk in flight
        with distributed.Client(address, timeout=30) as client:  # the scheduler saw it go
            assert victim_address not in client.scheduler_info()["workers"]
    finally:
        for proc in procs:
            _stop(proc)
        log.close()
    records = [json.loads(line) for line in out.read_text().splitlines()]
    assert sorted(r["id"] for r in records) == sorted(p["name"] for p in problems)  # complete, each once
    outcomes = set()
    for p in problems:
        record = next(r for r in records if r["id"] == p["name"])
        report = certify(load_problem(json.dumps(p)))  # the plain loop, in this process
        assert record["status"] == "ok" and record["outcome"] == report.outcome
        assert record["values"] == json.loads(json.dumps(report.values())), p["name"]
        outcomes.add(report.outcome)
    assert outcomes == {"proved", "refuted"}
    assert code == 1  # a refuted problem is the highest outcome: the batch reports every record
