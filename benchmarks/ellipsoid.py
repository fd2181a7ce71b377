"""Exact valid steplength sets on ellipsoids, n = 2 ... 20, against a float anchor.

In one run, on the same instances (x' = Ax, E = {x : x^T Q x <= 1} invariant,
A = (J - R) Q with J skew, R diagonal > 0, Q = I + C^T C, all small rationals):

* exact   -- ``valid_steplengths``: the coefficient polynomials q_k(h) of
             H^T Q H - G^T Q G (FLINT charpolys at integer points, one exact
             interpolation), every positive root isolated: the exact set;
* kernel  -- ``exactinv.check`` of its certificate (standard library only),
             where the conditions' degree n (2s - 1) <= KERNEL_DEGREE;
* float   -- the anchor: a grid of GRID float eigenvalue checks
             min eig(Q - A_d^T Q A_d) >= -1e-12 on (0, 2.1 tau] (numpy); it only
             brackets tau between two grid points, with a tolerance.

Run:  python benchmarks/ellipsoid.py [--quick]
"""

from __future__ import annotations

import argparse
import random
import sys
import time
from fractions import Fraction

import numpy as np

import exactinv as ei

GRID = 64
KERNEL_DEGREE = 32  # the kernel's Sturm sequences grow fast with the degree (measured up to 60: see README)


def instance(n: int, rng: random.Random) -> tuple[ei.LinearSystem, ei.Ellipsoid]:
    C = [[Fraction(rng.randint(-1, 1), 2) for _ in range(n)] for _ in range(n)]
    Q = [[sum(C[k][i] * C[k][j] for k in range(n)) + (i == j) for j in range(n)] for i in range(n)]
    U = [[Fraction(rng.randint(-2, 2), 2) for _ in range(n)] for _ in range(n)]
    JR = [[(U[i][j] if i < j else -U[j][i]) if i != j else -Fraction(rng.randint(1, 4), 2) for j in range(n)]
          for i in range(n)]
    A = [[sum(JR[i][k] * Q[k][j] for k in range(n)) for j in range(n)] for i in range(n)]
    return ei.LinearSystem(A), ei.Ellipsoid(Q)


def _float_Ad(A: np.ndarray, method: ei.Method, h: float) -> np.ndarray:
    n = len(A)

    def poly(coeffs):
        out = np.zeros((n, n))
        for c in reversed(coeffs):
            out = out @ (h * A) + float(c) * np.eye(n)
        return out
    return np.linalg.solve(poly(method.denominator), poly(method.numerator))


def float_grid(S, E, method, top: float) -> tuple[float, float, float]:
    """(seconds, last grid point that passed before the first failure, first failure)."""
    A = np.array([[float(v) for v in r] for r in S.A])
    Q = np.array([[float(v) for v in r] for r in E.Q])
    t0 = time.perf_counter()
    last, fail = 0.0, float("inf")
    for h in np.linspace(0, top, GRID + 1)[1:]:
        Ad = _float_Ad(A, method, h)
        if np.linalg.eigvalsh(Q - Ad.T @ Q @ Ad).min() >= -1e-12:
            if fail == float("inf"):
                last = h
        elif fail == float("inf"):
            fail = h
    return time.perf_counter() - t0, last, fail


def run(n: int, method: ei.Method, S, E) -> str:
    t0 = time.perf_counter()
    V = ei.valid_steplengths(S, E, method)
    te = time.perf_counter() - t0
    tau = V.intervals[0].hi
    s = max(len(method.numerator), len(method.denominator)) - 1
    tk = "-"
    if n * (2 * s - 1) <= KERNEL_DEGREE:
        t0 = time.perf_counter()
        ok = ei.check(V.certificate).ok
        tk = f"{time.perf_counter() - t0:.2f}" + ("" if ok else " REJECTED")
    top = 2.1 * float(tau) if tau != ei.INF else 10.0
    tf, last, fail = float_grid(S, E, method, top)
    inside = tau == ei.INF and fail == float("inf") or (tau != ei.INF and last <= float(tau) <= fail)
    bracket = f"[{last:.4g}, {fail:.4g}]" + ("" if inside else " WRONG")
    value = "oo" if tau == ei.INF else f"{float(tau):.6g}"
    return (f"| n={n} | {method.name} | {len(V)} | {value} | {te:.3f} | {tk} | {tf:.4f} | {te / tf:.2g} | {bracket} |")


def main(argv=None) -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args(argv)
    rng = random.Random(20261122)
    sizes = [2, 4] if args.quick else [2, 4, 8, 12, 16, 20]
    print(f"| n | method | intervals | tau | exact s | kernel s | float grid s ({GRID} pts) | exact/float | float bracket |")
    print("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | --- |")
    for n in sizes:
        S, E = instance(n, rng)
        orders = (1, 2, 3, 4, 5, 6, 7, 8) if n <= 4 else (1, 2, 4, 8)
        methods = [ei.methods.taylor(p) for p in orders] + [ei.methods.pade(1, 1), ei.methods.pade(2, 2),
                                                            ei.methods.pade(0, 2), ei.methods.theta("1/4")]
        for method in methods:
            print(run(n, method, S, E))
            sys.stdout.flush()


if __name__ == "__main__":
    main()
