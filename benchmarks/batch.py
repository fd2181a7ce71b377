"""`exactinv batch` on a generated corpus: throughput on 1 and 2 local Dask
workers, on an existing cluster (--scheduler), a resumed run and a poisoned
corpus, against the plain alternative measured in the same run: a Python loop
calling `certify` in this process (no Dask, no sandbox, no limits).

Corpus: N small problems (default 1000), seeded: x' = Ax with A a random
integer matrix whose diagonal dominates (so most sets are invariant) or a
random one (so some are not), on random 2-D and 3-D polytopes (boxes,
integer polygons and polytopes by vertices); methods Taylor 1-4, Pade (1,1),
(1,2), (2,2), the theta-method 1/2, backward Euler, Heun, RK4.  Every run
certifies and kernel-checks every problem.

Poisoned corpus: the same N problems plus 2% bad input (a JSON float, a
line that is not JSON, an unknown key, a ragged matrix), 0.5% that run past
the time limit (Pade(40, 40)) and 0.5% that run past the memory limit
(Taylor 1000); limits --timeout 2 --memory 300.

Per-problem costs by family (`--costs`): CPU seconds and peak memory of one
task in the sandbox (certify + kernel check) for larger families than the
corpus -- regular polygons with 50 and 200 vertices (Taylor-4), hypercubes
in R^4 and R^6 (Pade(2,2)) and random 3-D polytopes (RK4) -- the numbers
behind the 10^5-problem estimate in docs/scale.md.

Run:  python benchmarks/batch.py [--n 1000] [--quick] [--costs]
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

from dask.distributed import LocalCluster

from exactinv.interfaces.batch import run_batch
from exactinv.interfaces.batch.corpus import Task
from exactinv.interfaces.batch.task import Limits, run_task
from exactinv.interfaces.pipeline import certify
from exactinv.interfaces.problem import load_problem

METHODS = [{"taylor": 1}, {"taylor": 2}, {"taylor": 3}, {"taylor": 4}, {"pade": [1, 1]}, {"pade": [1, 2]},
           {"pade": [2, 2]}, {"theta": "1/2"}, "backward_euler", "heun", "rk4"]


def _matrix(rng: random.Random, n: int) -> list[list[int]]:
    A = [[rng.randint(-2, 2) for _ in range(n)] for _ in range(n)]
    if rng.random() < 0.8:  # diagonal dominance: invariant boxes, mostly invariant polytopes
        for i in range(n):
            A[i][i] = -(sum(abs(A[i][j]) for j in range(n) if j != i) + rng.randint(1, 3))
    return A


def _polytope(rng: random.Random, n: int) -> dict:
    if rng.random() < 0.4:
        return {"G": [[(1 if j == i else 0) * s for j in range(n)] for i in range(n) for s in (1, -1)],
                "b": [rng.randint(1, 4) for _ in range(2 * n)]}
    corners = [[s * 5 for s in signs] for signs in ([1] * n, [-1] * n)]
    corners.append([5] + [-5] * (n - 1))
    corners.append([-5] + [5] * (n - 1))
    k = rng.randint(n + 1, 4 + 2 * n)
    return {"vertices": corners + [[rng.randint(-4, 4) for _ in range(n)] for _ in range(k)]}


def generate(count: int, seed: int = 2026) -> list[dict]:
    rng = random.Random(seed)
    problems = []
    for i in range(count):
        n = 2 if rng.random() < 0.6 else 3
        problems.append({"name": f"gen-{i:05d}", "system": {"A": _matrix(rng, n)}, "polyhedron": _polytope(rng, n),
                         "method": rng.choice(METHODS)})
    return problems


def poison(problems: list[dict], seed: int = 7) -> list[str]:
    rng = random.Random(seed)
    lines = [json.dumps(p) for p in problems]
    n = len(problems)
    seg = {"G": [[1], [-1]], "b": [1, 1]}
    bad = []
    for k in range(max(n // 50, 4)):
        kind = k % 4
        if kind == 0:
            bad.append('{"name": "bad-float-%d", "system": {"A": [[-0.5]]}, "polyhedron": {"G": [[1], [-1]], "b": [1, 1]}}' % k)
        elif kind == 1:
            bad.append("not json at all %d" % k)
        elif kind == 2:
            bad.append(json.dumps({"name": f"bad-key-{k}", "system": {"A": [[-1]]}, "polyhedron": seg, "methd": "rk4"}))
        else:
            bad.append(json.dumps({"name": f"bad-ragged-{k}", "system": {"A": [[-1, 0], [1]]}, "polyhedron": seg}))
    for k in range(max(n // 200, 1)):
        bad.append(json.dumps({"name": f"slow-{k}", "system": {"A": [[-1]]}, "polyhedron": seg, "method": {"pade": [40, 40]}}))
        bad.append(json.dumps({"name": f"hog-{k}", "system": {"A": [[-1]]}, "polyhedron": seg, "method": {"taylor": 1000}}))
    for line in bad:
        lines.insert(rng.randrange(len(lines) + 1), line)
    return lines


def _cpu() -> float:
    t = os.times()
    return t.user + t.system


def plain_loop(problems: list[dict]) -> tuple[float, float, int]:
    """(wall s, CPU s, verified) of a loop calling `certify` in this process."""
    t0, c0, ok = time.perf_counter(), _cpu(), 0
    for p in problems:
        ok += certify(load_problem(json.dumps(p))).ok
    return time.perf_counter() - t0, _cpu() - c0, ok


def _task_cpu(out: str, skip: int = 0) -> float:
    """The summed CPU time of the records of ``out`` after its first ``skip`` lines (torn lines ignored)."""
    total = 0.0
    with open(out) as fh:
        for line in list(fh)[skip:]:
            try:
                total += json.loads(line).get("cpu_seconds", 0.0)
            except ValueError:
                pass
    return total


def row(label: str, s, base: float, base_cpu: float, out: str, extra: str = "", skip: int = 0) -> None:
    """One table row; the speed-up: the loop's wall time for as many problems as this run ran, over its wall time."""
    statuses = " ".join(f"{k} {s.count(k)}" for k in ("ok", "rejected", "error", "timeout", "memory") if s.count(k))
    print(f"| {label} | {s.total} | {s.skipped} | {s.ran} | {s.seconds:.1f} | {s.throughput:.1f} | "
          f"{base * s.ran / BASE_N / s.seconds:.2f} | {_task_cpu(out, skip):.1f} | {statuses} | {os.getloadavg()[0]:.1f} "
          f"| {extra} |")
    sys.stdout.flush()


BASE_N = 0


def main() -> None:
    global BASE_N
    parser = argparse.ArgumentParser()
    parser.add_argument("--n", type=int, default=1000)
    parser.add_argument("--quick", action="store_true", help="100 problems")
    parser.add_argument("--costs", action="store_true", help="only the per-problem costs of larger families")
    args = parser.parse_args()
    if args.costs:
        return family_costs()
    n = BASE_N = 100 if args.quick else args.n
    problems = generate(n)
    work = tempfile.mkdtemp(prefix="exactinv-batch-bench-")
    corpus = os.path.join(work, "corpus.jsonl")
    with open(corpus, "w") as fh:
        fh.write("\n".join(json.dumps(p) for p in problems) + "\n")
    print(f"{n} generated problems in {corpus}; machine: {os.cpu_count()} cores, load {os.getloadavg()[0]:.1f}")

    base, base_cpu, ok = plain_loop(problems)
    print(f"plain loop, in process: {base:.1f} s wall, {base_cpu:.1f} s CPU, {n / base:.1f} problems/s, {ok} verified\n")
    print("| run | problems | skipped | run | wall s | problems/s | speed-up vs loop (wall) | task CPU s "
          "| statuses | load | notes |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---|---:|---|")
    print(f"| plain loop (`certify` in process) | {n} | 0 | {n} | {base:.1f} | {n / base:.1f} | 1.00 | {base_cpu:.1f} "
          f"| ok {ok} | {os.getloadavg()[0]:.1f} | no isolation, no limits |")

    w1, w2 = os.path.join(work, "w1.jsonl"), os.path.join(work, "w2.jsonl")
    one = run_batch([corpus], w1, workers=1, progress=False)
    row("LocalCluster, 1 worker", one, base, base_cpu, w1, f"task CPU / loop CPU {_task_cpu(w1) / base_cpu:.2f}")
    two = run_batch([corpus], w2, workers=2, progress=False)
    row("LocalCluster, 2 workers", two, base, base_cpu, w2, f"speed-up vs 1 worker {one.seconds / two.seconds:.2f}")

    with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None, silence_logs=logging.ERROR) as cluster:
        ext_out = os.path.join(work, "ext.jsonl")
        ext = run_batch([corpus], ext_out, scheduler=cluster.scheduler_address, progress=False)
        row("existing LocalCluster (--scheduler)", ext, base, base_cpu, ext_out, "cluster already up")

        half = os.path.join(work, "half.jsonl")
        with open(w2) as src, open(half, "w") as dst:
            lines = src.readlines()
            dst.writelines(lines[: len(lines) // 2])
            dst.write(lines[len(lines) // 2][:40])  # the torn line of an interrupted run
        res = run_batch([corpus], half, scheduler=cluster.scheduler_address, progress=False)
        row("resumed after half (--scheduler)", res, base, base_cpu, half, "torn last line redone",
            skip=len(lines) // 2 + 1)

        bad = os.path.join(work, "poisoned.jsonl")
        with open(bad, "w") as fh:
            fh.write("\n".join(poison(problems)) + "\n")
        bad_out = os.path.join(work, "poisoned-out.jsonl")
        poi = run_batch([bad], bad_out, scheduler=cluster.scheduler_address, timeout=2, memory_mb=300, progress=False)
        row("poisoned, --timeout 2 --memory 300", poi, base, base_cpu, bad_out, f"{poi.total - n} poisoned")
    print()
    print(two.table())
    print()
    print(poi.table())
    _costs(w2)


def _costs(path: str) -> None:
    """Per-problem costs of the 2-worker run, for docs/scale.md."""
    with open(path) as fh:
        records = [json.loads(line) for line in fh]
    secs = sorted(r["seconds"] for r in records)
    peaks = sorted(r["peak_mb"] for r in records)
    q = lambda xs, f: xs[min(int(f * len(xs)), len(xs) - 1)]  # noqa: E731
    cpus = sorted(r["cpu_seconds"] for r in records)
    print(f"\nper problem (2-worker run): wall mean {sum(secs) / len(secs):.3f} s, median {q(secs, .5):.3f} s, "
          f"p99 {q(secs, .99):.3f} s, max {secs[-1]:.3f} s; CPU mean {sum(cpus) / len(cpus):.3f} s, "
          f"p99 {q(cpus, .99):.3f} s, max {cpus[-1]:.3f} s; peak RSS median {q(peaks, .5):.0f} MB, max {peaks[-1]:.0f} MB")


ROT = [[-1, "1/2"], ["-1/2", -1]]


def _families(rng: random.Random) -> dict[str, list[dict]]:
    sys.path.insert(0, os.path.dirname(__file__))
    from largest import cube_system, polygon

    def poly(N):
        return {"vertices": [[str(x) for x in v] for v in polygon(N).vertices]}

    def cube(n):
        A = cube_system(n, rng).A
        return {"A": [[str(x) for x in r] for r in A]}, {"G": [[(1 if j == i else 0) * s for j in range(n)]
                                                             for i in range(n) for s in (1, -1)], "b": [1] * (2 * n)}
    fam = {
        "generated (the corpus above)": generate(20, seed=99),
        "polygon N=50, Taylor-4": [{"system": {"A": ROT}, "polyhedron": poly(50), "method": {"taylor": 4}}] * 3,
        "polygon N=200, Taylor-4": [{"system": {"A": ROT}, "polyhedron": poly(200), "method": {"taylor": 4}}] * 2,
        "hypercube R^4, Pade(2,2)": [dict(zip(("system", "polyhedron"), cube(4)), method={"pade": [2, 2]})
                                     for _ in range(3)],
        "hypercube R^6, Pade(2,2)": [dict(zip(("system", "polyhedron"), cube(6)), method={"pade": [2, 2]})
                                     for _ in range(2)],
    }
    fam["polygon N=1000, Taylor-4"] = [{"system": {"A": ROT}, "polyhedron": poly(1000), "method": {"taylor": 4}}]
    fam["hypercube R^10, Taylor-4 (box route)"] = [dict(zip(("system", "polyhedron"), cube(10)), method={"taylor": 4})
                                                  for _ in range(2)]
    from scale import r6
    S6, P6 = r6()
    fam["R^6, 100 random facets, Taylor-6"] = [{"system": {"A": [[str(x) for x in r] for r in S6.A]},
                                                "polyhedron": {"G": [[str(x) for x in r] for r in P6.G],
                                                               "b": [str(x) for x in P6.b]},
                                                "method": {"taylor": 6}}]
    fam["random 3-D polytope, 20 points, RK4"] = [
        {"system": {"A": _matrix(rng, 3)}, "polyhedron": {"vertices": [[rng.randint(-9, 9) for _ in range(3)]
                                                                       for _ in range(20)]}, "method": "rk4"}
        for _ in range(5)]
    return fam


def family_costs() -> None:
    print("| family | problems | CPU s / problem (mean) | max | peak RSS MB (max) | statuses |")
    print("|---|---:|---:|---:|---:|---|")
    for label, problems in _families(random.Random(5)).items():
        recs = [run_task(Task(f"{label}-{k}", "certify", text=json.dumps(p)), Limits(timeout=600))
                for k, p in enumerate(problems)]
        cpus = [r["cpu_seconds"] for r in recs]
        statuses = sorted({r["status"] for r in recs})
        print(f"| {label} | {len(recs)} | {sum(cpus) / len(cpus):.3f} | {max(cpus):.3f} | "
              f"{max(r['peak_mb'] for r in recs):.0f} | {', '.join(statuses)} |")
        sys.stdout.flush()


if __name__ == "__main__":
    main()
