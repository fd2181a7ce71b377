"""Ctrl-C in a real `exactinv batch` (issue 21, item 3): SIGINT sent to the
whole process group -- as a terminal sends it -- once some records are
written, on a local cluster and on an existing cluster (--scheduler).  The
batch ends with exactly one line "interrupted: N done, resumable", exit 130,
no traceback from any process; the results file holds N whole records, and
running the same command again completes the corpus without doing any of
them twice.  (Problems: Taylor-4 on 24-gons, about a second each.)"""

from __future__ import annotations

import json
import math
import os
import signal
import subprocess
import sys
import time

import pytest

distributed = pytest.importorskip("dask.distributed")

from exactinv.interfaces.batch.signals import CtrlC, sigint_ignored  # noqa: E402

N = 10


def _corpus(path) -> None:
    path.mkdir()
    for i in range(N):
        pts = [[round(1000 * math.cos(2 * math.pi * j / 24 + i / 100)), round(1000 * math.sin(2 * math.pi * j / 24 + i / 100))]
               for j in range(24)]
        problem = {"name": f"poly-{i}", "system": {"A": [[-1 - i % 3, 1], [-1, -1 - i % 3]]},
                   "polyhedron": {"vertices": pts}, "method": {"taylor": 4}}
        (path / f"p{i:02d}.json").write_text(json.dumps(problem))


def _lines(out) -> list[str]:
    return out.read_text().splitlines() if out.exists() else []


def _batch(args: list[str], cwd) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-m", "exactinv", "batch", *args], cwd=cwd, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, start_new_session=True)


def _interrupt_then_resume(tmp_path, where: list[str]) -> None:
    _corpus(tmp_path / "corpus")
    out = tmp_path / "results.jsonl"
    args = ["corpus", "-o", str(out), *where]
    proc = _batch(args, tmp_path)
    deadline = time.monotonic() + 300
    while len(_lines(out)) < 2 and proc.poll() is None and time.monotonic() < deadline:
        time.sleep(0.05)
    assert proc.poll() is None, "the batch ended before it could be interrupted"
    os.killpg(proc.pid, signal.SIGINT)  # what a terminal's Ctrl-C does: the whole process group
    stdout, stderr = proc.communicate(timeout=300)
    assert "Traceback" not in stdout + stderr, stderr
    assert proc.returncode == 130, (proc.returncode, stderr)
    lines = stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("interrupted: ") and lines[0].endswith(" done, resumable"), stderr
    done = int(lines[0].split()[1])
    records = [json.loads(line) for line in _lines(out)]  # every line whole
    assert 2 <= done == len(records) < N and all(r["status"] == "ok" for r in records)
    assert out.read_bytes().endswith(b"\n")
    kept = out.read_bytes()
    proc = _batch(args, tmp_path)
    stdout, stderr = proc.communicate(timeout=600)
    assert proc.returncode == 0 and "Traceback" not in stdout + stderr, stderr
    assert out.read_bytes().startswith(kept)  # appended to, never rewritten
    ids = [json.loads(line)["id"] for line in _lines(out)]
    assert sorted(ids) == sorted(f"p{i:02d}.json" for i in range(N))  # each problem once
    assert f"{N} problems: {done} already in" in stdout and f"all {N} records" in stdout


def test_ctrl_c_on_the_local_cluster(tmp_path):
    _interrupt_then_resume(tmp_path, ["--workers", "2"])


def test_ctrl_c_with_an_existing_scheduler(tmp_path):
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address="127.0.0.1:0",
                                  silence_logs=40) as cluster:
        _interrupt_then_resume(tmp_path, ["--scheduler", cluster.scheduler_address])


def test_a_deferred_ctrl_c_arrives_after_the_block():
    """Inside CtrlC.deferred (a record and its certificate being written) Ctrl-C waits for the end of
    the block -- even with other threads running, as the Dask client's are; sigint_ignored drops it."""
    import threading

    stop = threading.Event()
    other = threading.Thread(target=stop.wait)
    other.start()
    steps = []
    try:
        with CtrlC() as ctrl_c:
            with pytest.raises(KeyboardInterrupt):
                with ctrl_c.deferred():
                    os.kill(os.getpid(), signal.SIGINT)
                    time.sleep(0.05)
                    steps.append("whole")
            with pytest.raises(KeyboardInterrupt):
                os.kill(os.getpid(), signal.SIGINT)
                time.sleep(0.5)
    finally:
        stop.set()
        other.join()
    assert steps == ["whole"]
    before = signal.getsignal(signal.SIGINT)
    with sigint_ignored():
        os.kill(os.getpid(), signal.SIGINT)
        time.sleep(0.05)
    assert signal.getsignal(signal.SIGINT) is before
