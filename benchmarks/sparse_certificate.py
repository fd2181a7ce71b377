"""Certificates that scale (issue 24, items 3 and 4): the 1000-gon with 20-40-bit rational vertices, Taylor-4.

The instance: the regular-ish 1000-gon of benchmarks/largest.py (vertices ((1 - s^2)/(1 + s^2),
2s/(1 + s^2)) with s = tan(theta/2) rounded to a denominator <= 10^6: 20-40-bit rationals; its
facet data G, b have 40-80-bit entries), A = [[-1, 1/2], [-1/2, -1]], the Taylor-4 method.  Each
measurement runs in a fresh process (so the peak resident set is its own):

* engine  -- ``certify(problem, check=False)`` and the certificate written as ``exactinv certify -o``
             writes it (indented JSON): seconds, peak RSS (MB), certificate size (MB);
* certify -- the same with the kernel check in the same process (what ``exactinv certify`` does):
             peak RSS;
* kernel  -- ``python -S -m exactinv_check CERT.json`` on the engine's certificate: seconds (CPU of
             the child) and peak RSS; the ratio kernel / engine;
* gamma*  -- ``optimal_gamma`` (certified: every row LP proved in Q) against the float solve of the
             same m row LPs in HiGHS (the engine's float step alone: warm-started, a failed warm
             start retried from a fresh model, nothing verified) and the whole LP in HiGHS
             (benchmarks/gamma.py's "highs"); best of ``--repeat`` runs, taking turns, wall and CPU
             seconds; the float values (their error is not checked: HiGHS' tolerances) and the
             engine's row paths (how each row was proved).

``--tree DIR`` runs the measurements on another source tree (e.g. ``git archive REV | tar -x -C DIR``)
with PYTHONPATH=DIR: the before/after table of benchmarks/README.md comes from one run of each.

Run:  python benchmarks/sparse_certificate.py [--tree DIR] [--sides N] [--repeat 3]
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROT = [[-1, "1/2"], ["-1/2", -1]]


def _problem(sides: int):
    sys.path.insert(0, str(HERE))
    from largest import polygon

    import exactinv as ei
    from exactinv.interfaces.problem import Problem

    return Problem(ei.LinearSystem(ROT), polygon(sides), method=ei.methods.taylor(4), name=f"{sides}-gon")


def _peak_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def child_engine(sides: int, out: str, check: bool) -> dict:
    from exactinv.certificates import dumps
    from exactinv.interfaces.pipeline import certify

    problem = _problem(sides)
    base = _peak_mb()
    t0, c0 = time.perf_counter(), time.process_time()
    report = certify(problem, check=check)
    text = dumps(report.certificate)
    Path(out).write_text(text)
    import exactinv
    return {"seconds": time.perf_counter() - t0, "cpu": time.process_time() - c0, "peak_mb": _peak_mb(),
            "base_mb": base, "bytes": len(text.encode()), "version": report.certificate["version"],
            "ok": bool(report.ok) if check else None, "source": exactinv.__file__}


def time_float_rows(S, P):
    """The float step alone: the m row LPs in HiGHS, warm-started row to row, a row whose warm
    start fails solved again from a fresh model (as the engine does), nothing verified."""
    import flint
    import numpy as np

    from exactinv.lp.backends import HighsHint
    from exactinv.lp.floatlp import FloatLP

    m, n = P.m, P.n
    constraint = flint.fmpq_mat(n + 1, m, P.G_flint.transpose().entries() + P.b_flint.entries())
    GA = np.array([[float(v) for v in r] for r in P.G]) @ np.array([[float(v) for v in r] for r in S.A])
    t0, c0 = time.perf_counter(), time.process_time()
    float_lp = FloatLP(constraint, [True] * n + [False], HighsHint())
    best = -np.inf
    for j in range(m):
        cost = np.zeros(m)
        cost[j] = 1.0
        nonneg = np.arange(m) != j
        hint = float_lp.solve_floats(cost, np.append(GA[j], 0.0), nonneg)
        if hint.status != "optimal":
            hint = float_lp.solve_floats(cost, np.append(GA[j], 0.0), nonneg)
        best = max(best, -hint.x[j] if hint.status == "optimal" else np.inf)
    return time.perf_counter() - t0, time.process_time() - c0, best


def child_gamma(sides: int, repeat: int) -> dict:
    sys.path.insert(0, str(HERE))
    from gamma import time_highs

    import exactinv as ei
    problem = _problem(sides)
    S, P = problem.system, problem.polyhedron
    P.G_flint, P.b_flint, S.A_flint  # noqa: B018 (the exact data, read once outside the timing)
    best = {k: float("inf") for k in ("certified", "highs_rows", "highs_lp", "certified_cpu", "highs_rows_cpu",
                                      "highs_lp_cpu")}
    value = paths = None
    for _ in range(repeat):
        t0, c0 = time.perf_counter(), time.process_time()
        g = ei.optimal_gamma(S, P)
        best["certified"] = min(best["certified"], time.perf_counter() - t0)
        best["certified_cpu"] = min(best["certified_cpu"], time.process_time() - c0)
        value, paths = g.value, g.paths
        wall, cpu, rows_value = time_float_rows(S, P)
        best["highs_rows"], best["highs_rows_cpu"] = min(best["highs_rows"], wall), min(best["highs_rows_cpu"], cpu)
        spent, lp_value = time_highs(S, P)
        best["highs_lp"], best["highs_lp_cpu"] = min(best["highs_lp"], spent), min(best["highs_lp_cpu"], spent.cpu)
    return {**best, "value": str(value), "float_rows_value": rows_value, "float_lp_value": lp_value,
            "paths": {str(k): v for k, v in paths.items()}}


def _run_child(args: list[str], tree: Path) -> dict:
    env = dict(os.environ, PYTHONPATH=str(tree))
    out = subprocess.run([sys.executable, __file__, *args], env=env, capture_output=True, text=True, cwd=str(tree))
    if out.returncode:
        raise RuntimeError(out.stderr[-3000:])
    return json.loads(out.stdout.strip().splitlines()[-1])


_KERNEL = """
import json, resource, sys, time
from exactinv_check import check
t0, c0 = time.perf_counter(), time.process_time()
report = check(sys.argv[1])
print(json.dumps({"seconds": time.perf_counter() - t0, "cpu": time.process_time() - c0, "ok": report.ok,
                  "peak_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, "output": str(report)[-300:]}))
"""


def kernel(tree: Path, cert: str) -> dict:
    """The standalone kernel (python -S, standard library only) on the certificate file, in its own process."""
    out = subprocess.run([sys.executable, "-S", "-c", _KERNEL, cert], cwd=str(tree), capture_output=True, text=True,
                         env=dict(os.environ, PYTHONPATH=str(tree)))
    if out.returncode:
        raise RuntimeError(out.stderr[-3000:])
    return json.loads(out.stdout.strip().splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--tree", default=str(HERE.parent), help="the source tree to measure (default: this one)")
    parser.add_argument("--sides", type=int, default=1000)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--child", choices=["engine", "certify", "gamma"])
    parser.add_argument("--out")
    args = parser.parse_args()
    if args.child == "gamma":
        print(json.dumps(child_gamma(args.sides, args.repeat)))
        return
    if args.child:
        print(json.dumps(child_engine(args.sides, args.out, args.child == "certify")))
        return
    tree = Path(args.tree).resolve()
    with tempfile.TemporaryDirectory() as tmp:
        cert = str(Path(tmp) / "cert.json")
        engine = _run_child(["--child", "engine", "--sides", str(args.sides), "--out", cert], tree)
        check = kernel(tree, cert)
        full = _run_child(["--child", "certify", "--sides", str(args.sides), "--out", str(Path(tmp) / "c2.json")], tree)
    gamma = _run_child(["--child", "gamma", "--sides", str(args.sides), "--repeat", str(args.repeat)], tree)
    result = {"tree": str(tree), "sides": args.sides, "engine": engine, "kernel": check, "certify": full, "gamma": gamma,
              "kernel_over_engine": check["cpu"] / engine["cpu"],
              "gamma_over_rows": gamma["certified"] / gamma["highs_rows"],
              "gamma_over_rows_cpu": gamma["certified_cpu"] / gamma["highs_rows_cpu"],
              "gamma_over_lp": gamma["certified"] / gamma["highs_lp"]}
    print(json.dumps(result, indent=1))


if __name__ == "__main__":
    main()
