"""Exact valid steplength sets on polygons with many vertices, against a grid of exact checks.

In one run, on the same instances:

* exactinv   -- ``valid_steplengths``: every vertex-facet condition polynomial
                from the products G A^k V, Descartes-filtered, deduplicated,
                roots isolated by FLINT: the exact set of valid steps;
* grid       -- the naive alternative: ``discrete_invariance`` (one exact LP per
                facet) at a grid of rational steps in [0, 2 tau]; it only
                brackets the threshold to the grid's resolution.

Instances: convex polygons with N vertices on the unit circle (exact rational
points ((1-s^2)/(1+s^2), 2s/(1+s^2))), x' = Ax with A = [[-1, 1/2], [-1/2, -1]]
(P is invariant), Taylor methods of order p.

Run:  python benchmarks/largest.py [--quick]
"""

from __future__ import annotations

import argparse
import math
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


def main(argv=None):
    parser = argparse.ArgumentParser()
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args(argv)
    S = ei.LinearSystem([[-1, "1/2"], ["-1/2", -1]])
    sizes = [10, 100] if args.quick else [10, 100, 300, 1000]
    header = f"{'N':>6}{'p':>3}{'pairs':>10}{'kept':>8}{'distinct':>9}{'exact s':>10}{'grid s':>10}{'grid/exact':>12}  largest"
    print(header)
    print("-" * len(header))
    for N in sizes:
        P = polygon(N)
        orders = range(1, 9) if N <= 100 else ((1, 2, 4, 8) if N <= 300 else (1, 2))
        for p in orders:
            method = ei.methods.taylor(p)
            t0 = time.perf_counter()
            V = ei.valid_steplengths(S, P, method)
            te = time.perf_counter() - t0
            first = V.intervals[0].hi
            top = Fraction(2) if first == ei.INF else 2 * (first.upper if isinstance(first, ei.RealAlgebraic) else first)
            tg, extrapolated = grid_check(S, P, method, top)
            mark = "~" if extrapolated else " "
            print(f"{N:>6}{p:>3}{P.m * len(P.vertices):>10}{V.conditions:>8}{V.distinct:>9}{te:>10.3f}{tg:>10.2f}{mark}{tg / te:>11.1f}  {first}")
            sys.stdout.flush()
    print("~ = grid check stopped after its time budget; time extrapolated to all grid points")
    print("N = 10,000 (10^8 vertex-facet pairs) is not run: about 40 us per pair gives over an hour.")


if __name__ == "__main__":
    main()
