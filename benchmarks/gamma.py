"""gamma*: the certified pipeline against a plain float solve and a purely exact solver.

On the same instances, in one run:

* exactinv   -- ``optimal_gamma``: every row LP solved in float by HiGHS, rounded
                (or solved exactly on its basis) and proved optimal in one exact
                integer batch (the certified answer: value, H, the binding row's
                dual).  For a sparse G (at most two nonzeros per row on average,
                e.g. the boxes) all m row LPs are ONE block-diagonal HiGHS LP
                (presolve on); otherwise they are m warm-started HiGHS solves;
* cvxpy hint -- the same certified pipeline with the cvxpy hint backend
                (``exactinv.lp.hint_backend("cvxpy", solver=...)``: each row LP
                a parametrised cvxpy problem, solver ``--hint-solver``, default
                cvxpy's own choice); same exact value, checked;
* cvxpy      -- the whole LP  min{gamma : H + gamma I >= 0, HG = GA, Hb <= 0}
                as one cvxpy problem solved by HiGHS in floating point (no guarantee);
* highs      -- the same whole LP handed to HiGHS directly (highspy, column-wise
                arrays built with numpy and passed as arrays, no modelling layer):
                the fastest float-only solve of gamma*;
* highs rows -- the m row LPs alone, in HiGHS (warm-started, as the engine's
                float step poses them for a dense G): nothing verified;
* pplpy      -- the m row LPs solved by PPL's exact simplex (MIP_Problem), row by row.

Fairness (``--float-only``): every column solves gamma* of the same instance
with HiGHS at its default tolerances (primal/dual feasibility 1e-7); the float
columns start from numpy copies of G, A, b made outside the timing, while the
certified column starts from the exact data (reading it is part of its cost).
Each column is the best of ``--repeat`` runs (default 5), the columns taking
turns run by run (so a change of machine load hits all alike); ``median`` is
the median over the runs of the paired ratio exact/highs (same round); the ``cpu`` columns give the same
two ratios in process CPU time (all threads), which does not count the waits
for a core on a shared machine.  Every float value is
asserted equal to the exact gamma* within 1e-6.  The certified time includes
the exact proof of every row but not the conversion of H to an fmpq matrix or
to JSON (``H_flint``/``certificate`` build it on first use); the column
``+H`` adds that conversion.

Instances: boxes [-1,1]^n (m = 2n) with row-diagonally-dominant A, and random
polytopes {x : Gx <= 1} inside [-1,1]^n with up to 500 facets and
A = -I/2 + R, R small enough that P is invariant.

Run:  python benchmarks/gamma.py [--quick] [--hint-solver CLARABEL] [--float-only [--repeat 5]]
"""

from __future__ import annotations

import argparse
import random
import sys
import time
from fractions import Fraction

import cvxpy as cp
import flint
import highspy
import numpy as np

import exactinv as ei
from exactinv.lp.backends import HighsHint
from exactinv.lp.exact import ppl_maximize
from exactinv.lp.floatlp import FloatLP

PPL_BUDGET = 60.0  # seconds per instance; beyond it the remaining rows are extrapolated


def box_instance(n: int, rng: random.Random):
    A = [[Fraction(rng.randint(-3, 3), rng.randint(1, 4)) if i != j else Fraction(0) for j in range(n)] for i in range(n)]
    for i in range(n):
        A[i][i] = -sum(abs(v) for v in A[i]) - Fraction(rng.randint(0, 5), 2)
    return ei.LinearSystem(A), ei.Polyhedron.box([-1] * n, [1] * n)


def polytope_instance(n: int, m: int, rng: random.Random):
    G = [[int(i == k) for k in range(n)] for i in range(n)] + [[-int(i == k) for k in range(n)] for i in range(n)]
    while len(G) < m:
        row = [rng.randint(-9, 9) for _ in range(n)]
        if any(row):
            G.append(row)
    scale = 18 * n * n
    A = [[Fraction(rng.randint(-100, 100), 100 * scale) - (Fraction(1, 2) if i == j else 0) for j in range(n)] for i in range(n)]
    return ei.LinearSystem(A), ei.Polyhedron(G, [1] * len(G))


class Elapsed(float):
    """Wall-clock seconds (the float value), with the process's CPU seconds (all threads) as ``cpu``:
    on a shared machine CPU time does not count the waits for a core."""

    cpu: float


def clock():
    """A start mark for :func:`elapsed`."""
    return time.perf_counter(), time.process_time()


def elapsed(start):
    """Elapsed since ``start``: wall seconds, ``.cpu`` the CPU seconds."""
    out = Elapsed(time.perf_counter() - start[0])
    out.cpu = time.process_time() - start[1]
    return out


def time_exact(S, P):
    t = clock()
    g = ei.optimal_gamma(S, P)
    return elapsed(t), g


def time_exact_with_H(S, P):
    """optimal_gamma and its H as an fmpq matrix (built on first use)."""
    t = clock()
    g = ei.optimal_gamma(S, P)
    assert g.H_flint is not None
    return elapsed(t), g


def time_exact_cvxpy_hint(S, P, solver):
    t = clock()
    with ei.lp.hint_backend("cvxpy", solver=solver):
        g = ei.optimal_gamma(S, P)
    return elapsed(t), g


def time_cvxpy(S, P):
    G = np.array([[float(v) for v in r] for r in P.G])
    A = np.array([[float(v) for v in r] for r in S.A])
    b = np.array([float(v) for v in P.b])
    m = P.m
    t = clock()
    H = cp.Variable((m, m))
    gamma = cp.Variable()
    problem = cp.Problem(cp.Minimize(gamma), [H + gamma * np.eye(m) >= 0, H @ G == G @ A, H @ b <= 0])
    problem.solve(solver=cp.HIGHS)
    return elapsed(t), problem.value


def time_highs(S, P):
    """min gamma s.t. H + gamma I >= 0 (entrywise), H G = G A, H b <= 0, by highspy directly:
    column-wise data assembled with numpy and passed as arrays (no modelling layer, no
    scipy), HiGHS' defaults (presolve on, tolerances 1e-7) -- the fastest float-only solve."""
    G = np.array([[float(v) for v in r] for r in P.G])
    A = np.array([[float(v) for v in r] for r in S.A])
    b = np.array([float(v) for v in P.b])
    m, n = G.shape
    t = clock()
    # variables: H row-major (column j*m + k is h_jk), then gamma; rows: (HG)_ji at j*n + i,
    # (Hb)_j at m*n + j, h_jj + gamma >= 0 at m*n + m + j
    Bt = np.vstack([G.T, b[None, :]])  # column k of [G^T; b^T]: the entries of h_jk in block j
    ks, rs = np.nonzero(Bt.T)
    vals = Bt.T[ks, rs]
    blocks = np.arange(m)[:, None]
    col = (blocks * m + ks[None, :]).ravel()
    row = np.where(rs[None, :] < n, blocks * n + rs[None, :], m * n + blocks).ravel()
    val = np.tile(vals, m)
    diag = np.arange(m)
    col = np.concatenate([col, diag * (m + 1), np.full(m, m * m)])
    row = np.concatenate([row, m * n + m + diag, m * n + m + diag])
    val = np.concatenate([val, np.ones(2 * m)])
    order = np.argsort(col * (m * n + 2 * m) + row, kind="stable")
    start = np.searchsorted(col[order], np.arange(m * m + 2)).astype(np.int32)
    inf, GA = highspy.kHighsInf, (G @ A).reshape(-1)
    col_lower = np.zeros(m * m + 1)
    col_lower[diag * (m + 1)] = -inf  # diagonal entries and gamma are free
    col_lower[-1] = -inf
    cost = np.zeros(m * m + 1)
    cost[-1] = 1.0
    h = highspy.Highs()
    h.setOptionValue("output_flag", False)
    h.passModel(m * m + 1, m * n + 2 * m, len(order), int(highspy.MatrixFormat.kColwise),
                int(highspy.ObjSense.kMinimize), 0.0, cost, col_lower, np.full(m * m + 1, inf),
                np.concatenate([GA, np.full(m, -inf), np.zeros(m)]), np.concatenate([GA, np.zeros(m), np.full(m, inf)]),
                start, row[order].astype(np.int32), val[order], np.zeros(m * m + 1, np.int32))
    h.run()
    return elapsed(t), h.getInfo().objective_function_value


def time_highs_rows(S, P):
    """The m row LPs of gamma* in HiGHS alone (the certified route's float step, nothing verified)."""
    m, n = P.m, P.n
    constraint = flint.fmpq_mat(n + 1, m, P.G_flint.transpose().entries() + P.b_flint.entries())
    GA = np.array([[float(v) for v in r] for r in P.G]) @ np.array([[float(v) for v in r] for r in S.A])
    t = clock()
    float_lp = FloatLP(constraint, [True] * n + [False], HighsHint())
    model = float_lp.backend.model(float_lp.A, float_lp.equality)
    best = -np.inf
    for j in range(m):
        cost = np.zeros(m)
        cost[j] = 1.0
        hint = model.solve(cost, np.concatenate([GA[j], [0.0]]) * float_lp.row_scale, [k != j for k in range(m)])
        best = max(best, -hint.x[j] if hint.status == "optimal" else np.inf)
    return elapsed(t), best


def time_ppl(S, P):
    m, n = P.m, P.n
    constraint = flint.fmpq_mat(n + 1, m, P.G_flint.transpose().entries() + P.b_flint.entries())
    GA = P.G_flint * S.A_flint
    t = clock()
    best = None
    done = 0
    for j in range(m):
        rhs = flint.fmpq_mat(n + 1, 1, [GA[j, i] for i in range(n)] + [0])
        c = flint.fmpq_mat(m, 1, [int(k == j) for k in range(m)])
        status, x = ppl_maximize(constraint, [True] * n + [False], rhs, c, [k != j for k in range(m)])
        value = -Fraction(int(x[j, 0].p), int(x[j, 0].q)) if status == "optimal" else None
        best = value if best is None or (value is not None and value > best) else best
        done += 1
        if time.perf_counter() - t[0] > PPL_BUDGET:
            break
    spent = time.perf_counter() - t[0]
    return spent * m / done, done < m, best


def paths_text(paths):
    """The routes of the row LPs, e.g. {'float-rounded': 20}."""
    return {str(path): count for path, count in paths.items()}


def interleaved_runs(repeat, fns, *args):
    """For each fn, ``repeat`` runs (time, value), the fns taking turns (round r runs every fn
    once), so that a change of machine load hits all columns alike."""
    runs = [[] for _ in fns]
    for _ in range(repeat):
        for fn, out in zip(fns, runs):
            out.append(fn(*args))
    return runs


def fastest(runs):
    """The fastest run (the machine is shared: the minimum is the least noisy time)."""
    return min(runs, key=lambda r: r[0])


def paired_median(runs, base):
    """The median over rounds of time(run) / time(base run of the same round)."""
    return float(np.median([r[0] / b[0] for r, b in zip(runs, base)]))


def float_only_table(instances, repeat):
    """The certified gamma* against the float-only solves: best of ``repeat`` interleaved runs
    each (wall clock), the median over rounds of the paired ratio exact/highs (same round),
    and the same two ratios in CPU time (not counting the waits for a core of a shared machine)."""
    header = (f"{'instance':<16}{'m':>5}{'exact s':>9}{'+H s':>7}{'cvxpy s':>9}{'highs s':>9}{'rows s':>8}"
              f"{'ex/cvxpy':>9}{'ex/highs':>9}{'median':>7}{'+H/highs':>9}{'ex/rows':>8}"
              f"{'cpu ex/highs':>13}{'cpu median':>11}  route")
    print(header)
    print("-" * len(header))
    for name, S, P in instances:
        runs = interleaved_runs(repeat, (time_exact, time_exact_with_H, time_cvxpy, time_highs, time_highs_rows), S, P)
        (te, g), (tH, _), (tc, vc), (th, vh), (tr, vr) = (fastest(r) for r in runs)
        for v in (vc, vh, vr):
            assert abs(v - float(g.value)) <= 1e-6 * max(1, abs(float(g.value))), (v, g.value)
        cpu_e, cpu_h = (min(r[0].cpu for r in runs[k]) for k in (0, 3))
        cpu_median = float(np.median([e[0].cpu / h[0].cpu for e, h in zip(runs[0], runs[3])]))
        print(f"{name:<16}{P.m:>5}{te:>9.3f}{tH:>7.3f}{tc:>9.3f}{th:>9.3f}{tr:>8.3f}{te / tc:>9.2f}{te / th:>9.2f}"
              f"{paired_median(runs[0], runs[3]):>7.2f}{tH / th:>9.2f}{te / tr:>8.2f}{cpu_e / cpu_h:>13.2f}"
              f"{cpu_median:>11.2f}  {paths_text(g.paths)}")
        sys.stdout.flush()


def main(argv=None):
    parser = argparse.ArgumentParser()
    parser.add_argument("--quick", action="store_true", help="small sizes only (a smoke run)")
    parser.add_argument("--hint-solver", default=None,
                        help="the cvxpy solver of the cvxpy hint backend (default: cvxpy's choice)")
    parser.add_argument("--no-ppl", action="store_true", help="skip the pplpy column")
    parser.add_argument("--float-only", action="store_true",
                        help="only the certified route against the float-only solves (cvxpy, HiGHS whole LP, HiGHS rows)")
    parser.add_argument("--repeat", type=int, default=5, help="--float-only: best of this many runs (default 5)")
    args = parser.parse_args(argv)
    rng = random.Random(20261122)
    instances = []
    sizes = [10, 25] if args.quick else [10, 25, 50, 100, 150, 200]
    for n in sizes:
        instances.append((f"box n={n}", *box_instance(n, rng)))
    poly_sizes = [(5, 50)] if args.quick else [(5, 50), (8, 100), (10, 250), (10, 500)]
    for n, m in poly_sizes:
        instances.append((f"polytope n={n}", *polytope_instance(n, m, rng)))
    if args.float_only:
        float_only_table(instances, args.repeat)
        return
    probe = cp.Variable()
    probe_lp = cp.Problem(cp.Minimize(probe), [probe >= 0])
    probe_lp.solve(solver=args.hint_solver)
    print(f"cvxpy hint backend: solver {probe_lp.solver_stats.solver_name}")
    header = (f"{'instance':<18}{'m':>5}{'exact s':>10}{'hint=cvxpy s':>14}{'hint/exact':>12}{'cvxpy s':>10}"
              f"{'exact/cvxpy':>13}{'pplpy s':>11}{'pplpy/exact':>13}  gamma*  routes (highs | cvxpy hint)")
    print(header)
    print("-" * len(header))
    for name, S, P in instances:
        te, g = time_exact(S, P)
        th, gh = time_exact_cvxpy_hint(S, P, args.hint_solver)
        assert gh.value == g.value, (gh.value, g.value)
        tc, vc = time_cvxpy(S, P)
        if args.no_ppl:
            tp, extrapolated, vp = float("nan"), False, None
        else:
            tp, extrapolated, vp = time_ppl(S, P)
        assert vp is None or extrapolated or vp == g.value, (vp, g.value)
        assert abs(vc - float(g.value)) <= 1e-6 * max(1, abs(float(g.value))), (vc, g.value)
        mark = "~" if extrapolated else " "
        print(f"{name:<18}{P.m:>5}{te:>10.3f}{th:>14.3f}{th / te:>12.1f}{tc:>10.3f}{te / tc:>13.2f}{mark}{tp:>10.2f}"
              f"{tp / te:>13.1f}  {g.value}  {paths_text(g.paths)} | {paths_text(gh.paths)}")
        sys.stdout.flush()
    print("~ = pplpy stopped after its time budget; time extrapolated from the rows it solved")


if __name__ == "__main__":
    main()
