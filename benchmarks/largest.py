"""Exact valid steplength sets on polytopes with 10 ... 16,384 vertices, against a grid of exact checks.

In one run, on the same instances:

* exactinv   -- ``valid_steplengths``: every vertex-facet condition polynomial
                from the products G A^k V, Descartes-filtered, deduplicated,
                roots isolated exactly: the exact set of valid steps;
* grid       -- the naive alternative: ``discrete_invariance`` (one exact LP per
                facet) at 16 rational steps in [0, 2 tau]; it only brackets tau.

Two families:

* hypercubes [-1, 1]^n, n = 4 ... 14 (16 ... 16,384 vertices, 2n facets), A row-
  diagonally dominant (P invariant) -- many vertices, few facets;
* polygons with N vertices on the unit circle (exact rational points), A =
  [[-1, 1/2], [-1/2, -1]] -- as many facets as vertices, the quadratic worst case.

Run:  python benchmarks/largest.py [--quick]
"""

from __future__ import annotations

import argparse
import math
import random
import sys
import time
from fractions import Fraction

import exactinv as ei

GRID_POINTS = 16
GRID_BUDGET = 30.0  # seconds per instance; then extrapolated


def polygon(N: int) -> ei.Polyhedron:
    pts = {(Fraction(-1), Fraction(0))}
    k = 0
    while len(pts) < N:
        theta = -math.pi + 2 * math.pi * (k + 0.5) / N
        s = Fraction(math.tan(theta / 2)).limit_denominator(10**6)
        pts.add(((1 - s * s) / (1 + s * s), 2 * s / (1 + s * s)))
        k += 1
    return ei.Polyhedron.from_vertices(sorted(pts))


def cube_system(n: int, rng: random.Random) -> ei.LinearSystem:
    A = [[Fraction(rng.randint(-2, 2), 4) if i != j else Fraction(0) for j in range(n)] for i in range(n)]
    for i in range(n):
        A[i][i] = -sum(abs(v) for v in A[i]) - 1
    return ei.LinearSystem(A)


def grid_check(S, P, method, top):
    t0 = time.perf_counter()
    done = 0
    for k in range(1, GRID_POINTS + 1):
        ei.discrete_invariance(S, P, method, top * Fraction(k, GRID_POINTS))
        done += 1
        if time.perf_counter() - t0 > GRID_BUDGET:
            break
    elapsed = time.perf_counter() - t0
    return elapsed * GRID_POINTS / done, done < GRID_POINTS


def run(label, S, P, orders, grid=True):
    for p in orders:
        method = ei.methods.taylor(p)
        t0 = time.perf_counter()
        V = ei.valid_steplengths(S, P, method)
        te = time.perf_counter() - t0
        first = V.intervals[0].hi
        if grid:
            top = Fraction(2) if first == ei.INF else 2 * (first.upper if isinstance(first, ei.RealAlgebraic) else first)
            tg, extrapolated = grid_check(S, P, method, top)
            grid_text = f"{tg:>10.2f}{'~' if extrapolated else ' '}{tg / te:>11.2f}"
        else:
            grid_text = f"{'-':>10} {'-':>11}"
        print(f"{label:<10}{len(P.vertices):>7}{P.m:>6}{p:>3}{P.m * len(P.vertices):>10}{V.distinct:>9}{te:>10.3f}"
              f"{grid_text}  {first}")
        sys.stdout.flush()


def main(argv=None):
    parser = argparse.ArgumentParser()
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args(argv)
    rng = random.Random(20261122)
    header = (f"{'family':<10}{'verts':>7}{'facets':>6}{'p':>3}{'pairs':>10}{'distinct':>9}{'exact s':>10}{'grid s':>11}"
              f"{'grid/exact':>11}  first interval ends at")
    print(header)
    print("-" * len(header))
    cubes = [4, 7] if args.quick else [4, 7, 10, 12, 13, 14]
    for n in cubes:
        orders = range(1, 9) if n <= 10 else (1, 2, 4, 8)
        run(f"cube n={n}", cube_system(n, rng), ei.Polyhedron.box([-1] * n, [1] * n), orders)
    S = ei.LinearSystem([[-1, "1/2"], ["-1/2", -1]])
    polygons = [10] if args.quick else [10, 100, 300, 1000]
    for N in polygons:
        orders = range(1, 9) if N <= 10 else ((1, 2, 4, 8) if N <= 300 else (1,))
        run(f"{N}-gon", S, polygon(N), orders, grid=N < 1000)
    print("~ = grid stopped after its time budget; time extrapolated to all 16 points")
    print("1000-gon: no grid (one exact check of 1000 facet LPs takes ~12 s; 16 would take ~3 minutes)")


if __name__ == "__main__":
    main()
