"""Where a resident sandbox child's CPU per problem goes, against a plain loop on the same
problems (issue 24: "a lone resident child spent 1.17x the loop's CPU per problem").

Every configuration runs the *same function* on the *same problems* (issue corpus of
benchmarks/batch_throughput.py, kernel checks on): ``certify(load_problem(text))``, with
``getrusage(RUSAGE_SELF)`` read around it in the process that runs it.  The configurations
are interleaved in blocks of ``--block`` problems, round after round, so that every
configuration sees the same machine (load, frequency, the other sessions) and the drift of a
shared VM cancels out of the ratios.

Configurations (``--configs``, comma-separated):

* ``loop``: this process, problem after problem (what `batch_throughput.py`'s loop does);
* ``loop-idle``: the same, with a ``--idle`` ms sleep between problems (the child's idle gap
  between jobs, without a child: the "a vCPU that sleeps pays to wake" hypothesis);
* ``child``: a resident :class:`Sandbox` child, one ``run`` per problem (the protocol of
  ``run_chunk`` before branch batch-pipe: the child idles while the parent reads the reply and
  sends the next job);
* ``child-pipe``: the same child, ``run_all`` over the block (job k + 1 sent as soon as job k
  is taken: the child never waits for the parent) -- when the sandbox has ``run_all``;
* ``child-same-cpu`` / ``child-other-cpu``: ``child`` with the child pinned to the parent's
  CPU / to the other one (where it wakes: cache and migration effects).

Per configuration and per problem: the function's CPU (user + system, ms) in the process that
ran it, its minor page faults, voluntary and involuntary context switches; for the child
configurations also the parent's CPU and sleeps (voluntary switches) per problem (this process,
while it waits); the wall time per problem; and the idle gap from the end of one problem to the
start of the next in the process that runs them (``CLOCK_MONOTONIC`` is the machine's clock).
Ratios are against ``loop``, per block of the same problems (paired), and of the sums.  The load average is printed.

Run:  python benchmarks/batch_child_cpu.py [--n 200] [--rounds 4] [--block 25] [--configs ...]
      [--in-dask]   (the whole measurement inside a 1-worker LocalCluster with the batch's
                    settings: the child forked from a Dask worker, Dask's threads in its parent)
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import sys
import time
from typing import Any

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from batch_throughput import generate  # noqa: E402

from exactinv.interfaces.batch.resident import Sandbox  # noqa: E402
from exactinv.interfaces.pipeline import certify  # noqa: E402
from exactinv.interfaces.problem import load_problem  # noqa: E402

FIELDS = ("cpu", "minflt", "nvcsw", "nivcsw")


def _usage() -> tuple[float, int, int, int]:
    u = resource.getrusage(resource.RUSAGE_SELF)
    return u.ru_utime + u.ru_stime, u.ru_minflt, u.ru_nvcsw, u.ru_nivcsw


def solve(text: str) -> dict[str, float]:
    """``certify(load_problem(text))`` and what it cost this process (CPU s, faults, switches)."""
    start, before = time.monotonic(), _usage()
    ok = certify(load_problem(text)).ok
    after, end = _usage(), time.monotonic()
    if not ok:
        raise AssertionError("the kernel rejected a certificate")
    return {**dict(zip(FIELDS, (a - b for a, b in zip(after, before)))), "start": start, "end": end}


def _pin(job: Any) -> Any:
    """In the child: pin it to ``job`` (a CPU number), then nothing else."""
    os.sched_setaffinity(0, {job})
    return os.sched_getaffinity(0) == {job}


def _child_fn(job: Any) -> Any:
    return _pin(job[1]) if job[0] == "pin" else solve(job[1])


def measure(texts: list[str], configs: list[str], rounds: int, block: int, idle: float) -> dict[str, dict]:
    """Per configuration: the per-problem measurements (lists) and the parent's CPU and wall."""
    boxes: dict[str, Sandbox] = {}
    cpus = sorted(os.sched_getaffinity(0))
    mine = cpus[0]
    parent_affinity = os.sched_getaffinity(0)
    for config in configs:
        if config.startswith("child"):
            box = boxes[config] = Sandbox(_child_fn)
            box.run(("warm", texts[0]), timeout=600)
            if config == "child-same-cpu":
                box.run(("pin", mine), timeout=60)
            elif config == "child-other-cpu":
                box.run(("pin", cpus[-1]), timeout=60)
    for text in texts[:3]:
        solve(text)  # warm this process too
    results: dict[str, dict] = {c: {f: [] for f in FIELDS} | {"parent": 0.0, "wakeups": 0, "wall": 0.0, "n": 0} for c in configs}
    for r in range(rounds):
        for start in range(0, len(texts), block):
            part = texts[start:start + block]
            order = configs if (start // block + r) % 2 == 0 else configs[::-1]
            for config in order:
                pin_parent = config in ("child-same-cpu", "child-other-cpu")
                if pin_parent:
                    os.sched_setaffinity(0, {mine})
                t0, u0 = time.perf_counter(), _usage()
                if config in ("loop", "loop-idle"):
                    got = []
                    for text in part:
                        got.append(solve(text))
                        if config == "loop-idle":
                            time.sleep(idle / 1000)
                elif config == "child-pipe":
                    got = [o.value for o in boxes[config].run_all([("solve", t) for t in part], timeout=600)]
                else:
                    got = [boxes[config].run(("solve", t), timeout=600).value for t in part]
                wall, u1 = time.perf_counter() - t0, _usage()
                parent, wakeups = u1[0] - u0[0], u1[2] - u0[2]
                if pin_parent:
                    os.sched_setaffinity(0, parent_affinity)
                res = results[config]
                res.setdefault("blocks", []).append(sum(g["cpu"] for g in got))
                # the idle gap: from the end of one problem to the start of the next, in the process that runs
                # them (CLOCK_MONOTONIC is the machine's: comparable across processes)
                res.setdefault("gaps", []).extend(b["start"] - a["end"] for a, b in zip(got, got[1:]))
                for g in got:
                    for f in FIELDS:
                        res[f].append(g[f])
                if config.startswith("child"):
                    res["parent"] += parent
                    res["wakeups"] += wakeups
                res["wall"] += wall
                res["n"] += len(part)
    for box in boxes.values():
        box.close()
    return results


def report(results: dict[str, dict], header: str) -> str:
    base = sum(results["loop"]["cpu"]) / len(results["loop"]["cpu"]) if "loop" in results else None
    lines = [header, "",
             "| configuration | CPU ms / problem (x loop) | median ms | parent CPU ms / problem | parent sleeps / problem "
             "| wall ms / problem | idle gap between problems, median / mean ms | minor faults / problem "
             "| voluntary / involuntary switches per problem |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for config, res in results.items():
        n = res["n"]
        cpu = sum(res["cpu"]) / n
        ratio = f" ({cpu / base:.3f})" if base else ""
        parent = f"{1000 * res['parent'] / n:.3f}" if config.startswith("child") else "-"
        sleeps = f"{res['wakeups'] / n:.2f}" if config.startswith("child") else "-"
        lines.append(f"| {config} | {1000 * cpu:.2f}{ratio} | {1000 * statistics.median(res['cpu']):.2f} | {parent} | "
                     f"{sleeps} | {1000 * res['wall'] / n:.2f} | {1000 * statistics.median(res['gaps']):.3f} / "
                     f"{1000 * statistics.fmean(res['gaps']):.3f} | {sum(res['minflt']) / n:.1f} | "
                     f"{sum(res['nvcsw']) / n:.2f} / {sum(res['nivcsw']) / n:.2f} |")
    if "loop" in results:
        base_blocks = results["loop"]["blocks"]
        lines.append("")
        for config, res in results.items():
            if config == "loop":
                continue
            ratios = [b / a for a, b in zip(base_blocks, res["blocks"])]
            mean = statistics.fmean(ratios)
            half = 2 * statistics.stdev(ratios) / len(ratios) ** 0.5 if len(ratios) > 1 else float("nan")
            lines.append(f"{config} / loop, paired by block ({len(ratios)} blocks of the same problems): "
                         f"{mean:.3f} +- {half:.3f} (two standard errors)")
    return "\n".join(lines)


def _in_worker(texts: list[str], configs: list[str], rounds: int, block: int, idle: float) -> dict[str, dict]:
    return measure(texts, configs, rounds, block, idle)


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--n", type=int, default=200)
    parser.add_argument("--rounds", type=int, default=4)
    parser.add_argument("--block", type=int, default=25)
    parser.add_argument("--idle", type=float, default=0.15, help="ms slept between problems in loop-idle")
    parser.add_argument("--configs", default="loop,loop-idle,child" + (",child-pipe" if hasattr(Sandbox, "run_all")
                                                                         else ""))
    parser.add_argument("--in-dask", action="store_true")
    args = parser.parse_args()
    texts = [json.dumps(p) for p in generate(args.n)]
    configs = args.configs.split(",")
    load0 = os.getloadavg()
    if args.in_dask:
        import logging

        import dask
        from dask.distributed import Client, LocalCluster

        from exactinv.interfaces.batch import engine
        with dask.config.set(engine.LOCAL_CONFIG), LocalCluster(
                n_workers=1, threads_per_worker=1, processes=True, dashboard_address=None,
                silence_logs=logging.CRITICAL) as cluster, Client(cluster) as client:
            results = client.submit(_in_worker, texts, configs, args.rounds, args.block, args.idle).result()
        where = "inside a 1-worker LocalCluster (the batch's settings)"
    else:
        results = measure(texts, configs, args.rounds, args.block, args.idle)
        where = "in this process"
    load1 = os.getloadavg()
    print(report(results, f"{args.n} problems x {args.rounds} rounds, blocks of {args.block}, interleaved, {where}; "
                          f"{os.cpu_count()} cores; load {load0[0]:.1f} -> {load1[0]:.1f}"))


if __name__ == "__main__":
    main()
