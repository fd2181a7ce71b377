"""Batch overhead on small problems (issue 24, item 1): a plain loop over
`interfaces.pipeline.certify` against `exactinv batch` with 1 and 2 local
workers, in the same run, on the same corpus.

Corpus: N (default 1000) seeded 2-D problems of a few milliseconds each --
x' = Ax with A a small integer matrix (diagonally dominant for 85% of them, so
most sets are invariant), on boxes and on small integer polygons; methods
Taylor 1-6, backward Euler, Pade(1,2), RK4.  Every run certifies and
kernel-checks every problem.

Each batch configuration is measured twice:
* "end to end": `run_batch(..., workers=k)` as `exactinv batch --workers k`
  runs it, starting (and closing) its LocalCluster -- the seconds include the
  cluster's start, about 2-4 s here;
* "on a running cluster": `run_batch(..., scheduler=...)` on a LocalCluster
  of k single-threaded workers started (and warmed: exactinv imported)
  before the clock starts -- the steady-state cost per problem.

The plain loop runs in this process (no Dask, no isolation, no limits).
CPU (user + system), which depends far less on the machine's load than wall
time: the loop's is this process's; a batch's on a running cluster is the
workers' own CPU (Dask, the sandbox's parent side) plus the CPU its records
report for the problems (the sandbox children) plus this process's (the
client, the results file).
Ratios: batch wall / loop wall (1 worker; target <= 1.2 on a running
cluster) and 1-worker wall / 2-worker wall (target >= 1.7).  The load
average is printed with each row: on a shared machine the 2-worker speed-up
is bounded by the free cores.

The script uses only `run_batch`, `certify` and `load_problem`, so the same
file measures an older checkout: `PYTHONPATH=/path/to/old python benchmarks/batch_throughput.py`.

Run:  python benchmarks/batch_throughput.py [--n 1000] [--repeat 1] [--modes e2e,running]
"""

from __future__ import annotations

import argparse
import json
import logging
import os
import random
import sys
import tempfile
import time

from dask.distributed import Client, LocalCluster

import exactinv
from exactinv.interfaces.batch import run_batch
from exactinv.interfaces.pipeline import certify
from exactinv.interfaces.problem import load_problem

METHODS = [{"taylor": k} for k in range(1, 7)] + ["backward_euler", {"pade": [1, 2]}, "rk4"]


def generate(count: int, seed: int = 24) -> list[dict]:
    """``count`` seeded 2-D problems (see the module docstring)."""
    rng = random.Random(seed)
    problems = []
    for i in range(count):
        A = [[rng.randint(-2, 2) for _ in range(2)] for _ in range(2)]
        if rng.random() < 0.85:
            for r in range(2):
                A[r][r] = -(abs(A[r][1 - r]) + rng.randint(1, 3))
        if rng.random() < 0.5:
            poly = {"G": [[1, 0], [-1, 0], [0, 1], [0, -1]], "b": [rng.randint(1, 4) for _ in range(4)]}
        else:
            poly = {"vertices": [[4, 4], [-4, -4], [4, -4], [-4, 4]] + [[rng.randint(-5, 5), rng.randint(-5, 5)]
                                                                      for _ in range(2)]}
        problems.append({"name": f"t{i:05d}", "system": {"A": A}, "polyhedron": poly,
                         "method": METHODS[i % len(METHODS)]})
    return problems


def _cpu() -> float:
    t = os.times()
    return t.user + t.system


def plain_loop(problems: list[dict]) -> tuple[float, float, int]:
    start, cpu, ok = time.perf_counter(), _cpu(), 0
    for p in problems:
        ok += certify(load_problem(json.dumps(p))).ok
    return time.perf_counter() - start, _cpu() - cpu, ok


def _records_cpu(out: str) -> float:
    with open(out) as fh:
        return sum(json.loads(line).get("cpu_seconds", 0.0) for line in fh)


def _warm() -> str:
    import exactinv.interfaces.batch  # noqa: F401  (what a batch worker imports)
    return exactinv.__version__


def batch(corpus: str, work: str, label: str, client: Client | None = None, **where) -> tuple[float, float, int]:
    """(wall s, CPU s or nan, verified) of one batch; CPU only on a running cluster (``client``)."""
    out = os.path.join(work, f"{label}.jsonl")
    workers0 = sum(client.run(_cpu).values()) if client is not None else 0.0
    start, cpu = time.perf_counter(), _cpu()
    summary = run_batch([corpus], out, progress=False, **where)
    seconds, cpu = time.perf_counter() - start, _cpu() - cpu
    if client is None:
        return seconds, float("nan"), summary.count("ok")
    workers = sum(client.run(_cpu).values()) - workers0
    return seconds, cpu + workers + _records_cpu(out), summary.count("ok")


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--n", type=int, default=1000)
    parser.add_argument("--repeat", type=int, default=1, help="repeat the whole comparison")
    parser.add_argument("--modes", default="e2e,running",
                        help="which batch runs: e2e (end to end), running (on a running cluster), or both")
    args = parser.parse_args()
    modes = set(args.modes.split(","))
    problems = generate(args.n)
    work = tempfile.mkdtemp(prefix="exactinv-throughput-")
    corpus = os.path.join(work, "corpus.jsonl")
    with open(corpus, "w") as fh:
        fh.write("".join(json.dumps(p) + "\n" for p in problems))
    print(f"exactinv {exactinv.__version__} from {os.path.dirname(exactinv.__file__)}; {args.n} problems; "
          f"{os.cpu_count()} cores")
    for rep in range(args.repeat):
        rows = []
        load0 = os.getloadavg()[0]
        loop, loop_cpu, ok = plain_loop(problems)
        rows.append(("plain loop", loop, loop_cpu, ok, load0))
        walls = {}
        for k in (1, 2):
            if "e2e" in modes:
                load = os.getloadavg()[0]
                seconds, cpu, ok = batch(corpus, work, f"e2e-{k}-{rep}", workers=k)
                rows.append((f"batch --workers {k} (end to end)", seconds, cpu, ok, load))
                walls[("e2e", k)] = seconds
            if "running" not in modes:
                continue
            with LocalCluster(n_workers=k, threads_per_worker=1, processes=True, dashboard_address=None,
                              silence_logs=logging.CRITICAL) as cluster, Client(cluster) as client:
                client.run(_warm)
                load = os.getloadavg()[0]
                seconds, cpu, ok = batch(corpus, work, f"run-{k}-{rep}", client, scheduler=cluster.scheduler_address)
            rows.append((f"batch, {k} worker{'s' * (k > 1)} (running cluster)", seconds, cpu, ok, load))
            walls[("run", k)] = seconds
        print("\n| run | wall s | problems/s | ms / problem | wall x loop | CPU s | CPU x loop | verified | load |")
        print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
        for label, seconds, cpu, ok, load in rows:
            cpus = "-" if cpu != cpu else f"{cpu:.2f} | {cpu / loop_cpu:.2f}"
            print(f"| {label} | {seconds:.2f} | {args.n / seconds:.0f} | {1000 * seconds / args.n:.2f} | "
                  f"{seconds / loop:.2f} | {cpus if cpu == cpu else '- | -'} | {ok} | {load:.1f} |")
        for mode, name in (("run", "running cluster"), ("e2e", "end to end")):
            if (mode, 1) in walls:
                print(f"{name}: 1 worker / loop {walls[mode, 1] / loop:.2f}; "
                      f"2 workers speed-up over 1 {walls[mode, 1] / walls[mode, 2]:.2f}")
        sys.stdout.flush()


if __name__ == "__main__":
    main()
