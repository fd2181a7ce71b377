"""The LP route (issue 23) against float LP bisection, in one run on the same instances.

Family: P = {Gx <= 1}, G's entries uniform integers in [-5, 5] (a zero row is
redrawn), A = -I + N/(10 n) with N's entries uniform integers in [-3, 3] (the
scale 10 n keeps P invariant for x' = Ax, so the valid sets are not just {0}).

Columns, on each instance:

* engine  -- exactinv's ``largest_threshold`` and ``valid_steplengths`` with
             ``route="lp"`` (one shared ConditionSet): the exact valid set and
             the exact largest threshold, with their certificate;
* kernel  -- ``exactinv_check.check`` of that certificate (both claims);
* float   -- what a user would write instead (MPT3 or a hand-written
             cvxpy/HiGHS script): per facet i, the float LP
             max g_i A_d(h) x over P in HiGHS (one model per instance,
             warm-started, default tolerances), doubling h from 1/16 while the
             facet is kept (up to 2^12), then 40 bisection steps; the threshold
             is the least over the facets.  A float answer, no certificate, and
             it only brackets the first interval's end.

``load`` is the 1-minute load average at the end of the row (the machine is shared).
``float vs exact`` compares the float threshold with the exact largest
threshold (relative difference; absolute when that is 0).  Times are CPU seconds of this process
(``time.process_time``, HiGHS' threads included): the project machine is
shared, and wall-clock times there move with the other jobs' load.

Two unbounded families whose valid sets are not trivial (``--family``):

* ``cone``  -- P = {x >= -1, g x <= 1} with g's entries uniform integers in
              [-5, 0] (m - n such rows): P is pointed with recession cone the
              orthant, and A = -I + N/(10 n) with N's off-diagonal entries in
              [0, 3] (Metzler) keeps the orthant for small h, so the facets have
              ray pieces only where r(hA) stops being nonnegative;
* ``lines`` -- P = Q x R^2 sheared: G = [G_Q, G_Q M] with G_Q the bounded family
              in R^(n-2) and M an integer (n-2) x 2 shear, so ker G (two lines)
              is {(-M z, z)}; A = T^-1 [[A_Q, 0], [C, A_L]] T (T = [[I, M], [0, I]])
              maps ker G into itself, so the facets see the quotient A_Q on Q
              (the LP route on P with lines, exactinv/validset/lp_lines.py).

Run:  python benchmarks/lp_route.py [--quick] [--methods taylor4,pade22] [--sizes 10x40,20x200]
      [--unbounded | --family cone | --family lines]
      (methods: taylor1 ... taylor8, pade11, pade22, backward_euler)
"""

from __future__ import annotations

import argparse
import math
import os
import random
import sys
import time
from fractions import Fraction

import highspy
import numpy as np

import exactinv as ei
import exactinv_check
from exactinv.conditions.polyhedron import ConditionSet
from exactinv.lp.highs import silent_highs
from exactinv.model.record import certificate
from exactinv.validset import lp_route as engine_lp

SIZES = [(6, 12), (6, 36), (6, 60), (8, 16), (8, 32), (8, 48), (10, 40), (12, 60), (16, 100), (20, 200)]
QUICK = [(6, 12), (8, 32), (10, 40)]
METHODS = {**{f"taylor{k}": ei.methods.taylor(k) for k in range(1, 9)},
           "pade11": ei.methods.pade(1, 1), "pade22": ei.methods.pade(2, 2),
           "backward_euler": ei.methods.backward_euler()}


def family(n: int, m: int, seed: int = 1, unbounded: bool = False) -> tuple[ei.LinearSystem, ei.Polyhedron]:
    """The random family; ``unbounded``: every row g has g . (1, .., 1) < 0 (a row with g . 1 > 0 is
    negated, one with g . 1 = 0 redrawn), so (1, .., 1) is a ray of P -- P is unbounded (and pointed:
    rank G = n) -- and the LP route's facets may have ray pieces."""
    rng = random.Random(seed * 1000 + n * 7 + m)
    G = []
    while len(G) < m:
        row = [rng.randint(-5, 5) for _ in range(n)]
        if unbounded:
            s = sum(row)
            if s == 0:
                continue
            row = row if s < 0 else [-v for v in row]
        if any(row):
            G.append(row)
    D = 10 * n
    A = [[Fraction(-1 if i == j else 0) + Fraction(rng.randint(-3, 3), D) for j in range(n)] for i in range(n)]
    return ei.LinearSystem(A), ei.Polyhedron(G, [1] * m)


def cone_family(n: int, m: int, seed: int = 1) -> tuple[ei.LinearSystem, ei.Polyhedron]:
    """P = {x >= -1, g x <= 1 (g <= 0)}: pointed, recession cone the orthant; A = -I + N/(10 n) Metzler."""
    rng = random.Random(seed * 1000 + n * 7 + m)
    G = [[-int(i == j) for j in range(n)] for i in range(n)]
    while len(G) < m:
        row = [rng.randint(-5, 0) for _ in range(n)]
        if any(row):
            G.append(row)
    D = 10 * n
    A = [[Fraction(-1 if i == j else 0) + Fraction(rng.randint(-3 if i == j else 0, 3), D) for j in range(n)]
         for i in range(n)]
    return ei.LinearSystem(A), ei.Polyhedron(G, [1] * m)


def lines_family(n: int, m: int, seed: int = 1) -> tuple[ei.LinearSystem, ei.Polyhedron]:
    """P = Q x R^2 sheared (two lines), A keeping ker G: the module docstring's ``lines`` family."""
    k = 2
    q = n - k
    SQ, Q = family(q, m, seed)
    rng = random.Random(seed * 2000 + n * 7 + m)
    M = [[rng.randint(-1, 1) for _ in range(k)] for _ in range(q)]
    G = [list(g) + [sum(g[i] * M[i][j] for i in range(q)) for j in range(k)] for g in Q.G]
    T = [[Fraction(int(i == j)) for j in range(n)] for i in range(n)]
    Tinv = [row[:] for row in T]
    for i in range(q):
        for j in range(k):
            T[i][q + j], Tinv[i][q + j] = Fraction(M[i][j]), Fraction(-M[i][j])
    Ay = [[Fraction(0)] * n for _ in range(n)]
    for i in range(q):
        for j in range(q):
            Ay[i][j] = SQ.A[i][j]
    for i in range(q, n):
        for j in range(n):
            Ay[i][j] = Fraction(-1 if i == j else 0) + Fraction(rng.randint(-3, 3), 10 * n)
    A = [[sum(Tinv[i][a] * Ay[a][c] * T[c][j] for a in range(n) for c in range(n)) for j in range(n)]
         for i in range(n)]
    return ei.LinearSystem(A), ei.Polyhedron(G, list(Q.b))


FAMILIES = {"cone": cone_family, "lines": lines_family}


# ------------------------------------------------------------------ the float anchor


def _float_Ad(A: np.ndarray, method: ei.Method, h: float) -> np.ndarray:
    """r(hA) in floats: g(hA) solved against h_r(hA)."""
    n = A.shape[0]
    M = h * A

    def poly(coeffs):
        out, power = np.zeros((n, n)), np.eye(n)
        for c in coeffs:
            out += float(c) * power
            power = power @ M
        return out

    num = poly(method.numerator)
    if method.is_polynomial:
        return num
    return np.linalg.solve(poly(method.denominator), num)


def float_bisection(S: ei.LinearSystem, P: ei.Polyhedron, method: ei.Method) -> tuple[float, int]:
    """(threshold, LPs solved): per facet doubling then 40 bisection steps, one HiGHS LP per step."""
    G = np.array([[float(v) for v in row] for row in P.G])
    b = np.array([float(v) for v in P.b])
    A = np.array([[float(v) for v in row] for row in S.A])
    m, n = G.shape
    h = silent_highs()
    h.setOptionValue("output_flag", False)
    lp = highspy.HighsLp()
    lp.num_col_, lp.num_row_ = n, m
    lp.col_cost_, lp.col_lower_, lp.col_upper_ = np.zeros(n), np.full(n, -highspy.kHighsInf), np.full(n, highspy.kHighsInf)
    lp.row_lower_, lp.row_upper_ = np.full(m, -highspy.kHighsInf), b
    lp.a_matrix_.format_ = highspy.MatrixFormat.kColwise
    lp.a_matrix_.start_ = np.arange(0, m * n + 1, m, dtype=np.int32)
    lp.a_matrix_.index_ = np.tile(np.arange(m, dtype=np.int32), n)
    lp.a_matrix_.value_ = G.T.reshape(-1).copy()
    h.passModel(lp)
    lps = 0
    idx = np.arange(n, dtype=np.int32)

    def kept(i: int, step: float) -> bool:
        nonlocal lps
        c = G[i] @ _float_Ad(A, method, step)
        h.changeColsCost(n, idx, -c)  # HiGHS minimizes
        h.run()
        lps += 1
        if h.getModelStatus() != highspy.HighsModelStatus.kOptimal:
            return False
        return -h.getInfo().objective_function_value <= b[i] + 1e-9

    best = math.inf
    for i in range(m):
        lo, hi = 0.0, 1.0 / 16
        while kept(i, hi) and hi < 2.0 ** 12:
            lo, hi = hi, 2 * hi
        if hi >= 2.0 ** 12 and kept(i, hi):
            continue
        for _ in range(40):
            mid = (lo + hi) / 2
            if kept(i, mid):
                lo = mid
            else:
                hi = mid
        best = min(best, lo)
    return best, lps


# ------------------------------------------------------------------ the run


def row(n: int, m: int, name: str, method: ei.Method, unbounded: bool = False, kind: str | None = None,
        duals: bool = True, skip_float: bool = False) -> dict:
    S, P = FAMILIES[kind](n, m) if kind else family(n, m, unbounded=unbounded)
    engine_lp.DUAL_POLICY = engine_lp.DualPolicy() if duals else None
    t0 = time.process_time()
    cs = ConditionSet(S, P, method)
    L = ei.largest_threshold(S, P, method, conditions=cs, route="lp")
    V = ei.valid_steplengths(S, P, method, conditions=cs, route="lp")
    engine = time.process_time() - t0
    cert = certificate(S, P, method, [L, V])
    t0 = time.process_time()
    report = exactinv_check.check(cert)
    kernel = time.process_time() - t0
    t0 = time.process_time()
    tau, lps = (math.nan, 0) if skip_float else float_bisection(S, P, method)
    flt = time.process_time() - t0 if not skip_float else math.nan
    exact = float(L.value) if L.value != ei.INF else math.inf
    if not math.isfinite(exact):
        agree = 0.0 if tau == math.inf else 1.0
    else:  # relative difference; absolute when the exact threshold is 0 (P not invariant)
        agree = abs(tau - exact) / (abs(exact) if exact else 1.0)
    return {"n": n, "m": m, "method": name, "pieces": V.lp.pieces, "rays": V.lp.rays, "duals": V.lp.duals,
            "lps": V.lp.float_lps + V.lp.exact_lps,
            "engine": engine, "kernel": kernel, "float": flt, "float_lps": lps, "ok": report.ok,
            "tau": L.value, "set": V.intervals, "agree": agree, "load": os.getloadavg()[0]}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--methods", default="taylor4")
    parser.add_argument("--sizes", default=None, help="e.g. 10x40,20x200")
    parser.add_argument("--unbounded", action="store_true", help="the unbounded variant of the family (ray pieces)")
    parser.add_argument("--family", choices=sorted(FAMILIES), default=None,
                        help="an unbounded family with a non-trivial valid set (module docstring)")
    parser.add_argument("--duals", choices=("on", "off", "both"), default="on",
                        help="dual pieces in the engine (both: each row without, then with them, in the same run)")
    args = parser.parse_args(argv)
    print(f"load average before: {' '.join(f'{v:.2f}' for v in os.getloadavg())}")
    sizes = QUICK if args.quick else SIZES
    if args.sizes:
        sizes = [tuple(int(v) for v in s.split("x")) for s in args.sizes.split(",")]
    print("| n | facets | method | pieces basis/dual | engine LPs | engine s | kernel s | float s (LPs) | engine/float | "
          "kernel/engine | kernel | tau (exact) | float vs exact | load |" + (" valid set |" if args.family else ""))
    print("|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---|---|---:|---:|" + ("---|" if args.family else ""))
    modes = {"on": [True], "off": [False], "both": [False, True]}[args.duals]
    for name in args.methods.split(","):
        for n, m in sizes:
            for duals in modes:
                _print_row(row(n, m, name, METHODS[name], args.unbounded, args.family, duals), args)
    print(f"load average after: {' '.join(f'{v:.2f}' for v in os.getloadavg())}")
    return 0


def _print_row(r: dict, args: argparse.Namespace) -> None:
    pieces = f"{r['pieces'] - r['duals']}/{r['duals']}" + (f" ({r['rays']} rays)" if args.unbounded or args.family else "")
    print(f"| {r['n']} | {r['m']} | {r['method']} | {pieces} | {r['lps']} | {r['engine']:.2f} | "
          f"{r['kernel']:.2f} | {r['float']:.2f} ({r['float_lps']}) | {r['engine'] / r['float']:.2f} | "
          f"{r['kernel'] / r['engine']:.2f} | {'ok' if r['ok'] else 'REJECTED'} | "
          f"{r['tau'] if isinstance(r['tau'], Fraction) else format(float(r['tau']), '.6g')} | "
          f"{r['agree']:.1e} | {r['load']:.2f} |" + (f" {r['set']} |" if args.family else ""), flush=True)

if __name__ == "__main__":
    sys.exit(main())
