"""The trusted kernel against the engine: time to check a certificate / time to make it.

In one run, on the same instances, for what `exactinv certify` computes on a
problem with a method (gamma*, forward Euler, the paper's threshold, the
largest threshold and the valid set):

* engine -- exactinv (FLINT, PPL, HiGHS) computing the results and writing
            the certificate;
* kernel -- exactinv_check (Python standard library only) re-proving every
            claim from the problem and the certificate: generators proved
            complete, every condition polynomial rebuilt, every root isolated.

Families: hypercubes [-1, 1]^n (2^n vertices, 2n facets), polygons with N
rational vertices on the unit circle (N facets), Taylor 1, 4, 8 and the
rational methods backward Euler, trapezoid and Pade(2, 2).

Run:  python benchmarks/kernel.py [--quick]
"""

from __future__ import annotations

import argparse
import random
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))

from largest import cube_system, polygon  # noqa: E402

import exactinv as ei  # noqa: E402
from exactinv.certificates import certificate  # noqa: E402
from exactinv_check import check  # noqa: E402

ROT = ei.LinearSystem([[-1, "1/2"], ["-1/2", -1]])


def engine(S, P, m):
    results = [ei.optimal_gamma(S, P), ei.forward_euler_threshold(S, P), ei.steplength_threshold(S, P, m),
               ei.largest_threshold(S, P, m), ei.valid_steplengths(S, P, m)]
    return certificate(S, P, m, results)


def row(label, S, P, m):
    t0 = time.perf_counter()
    cert = engine(S, P, m)
    te = time.perf_counter() - t0
    t0 = time.perf_counter()
    report = check(cert)
    tk = time.perf_counter() - t0
    verdict = "ok" if report.ok else "REJECTED"
    print(f"{label:<14}{len(P.vertices):>7}{P.m:>6}  {m.name:<16}{te:>9.3f}{tk:>9.3f}{tk / te:>8.2f}  {verdict}")
    sys.stdout.flush()
    return tk / te


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    rng = random.Random(1)
    M = ei.methods
    polynomial = [M.taylor(1), M.taylor(4), M.taylor(8)]
    rational = [M.backward_euler(), M.trapezoid(), M.pade(2, 2)]
    print(f"{'instance':<14}{'verts':>7}{'facets':>6}  {'method':<16}{'engine s':>9}{'kernel s':>9}{'ratio':>8}")
    ratios = []
    for n in ([2, 4] if args.quick else [2, 4, 6, 8]):
        S, P = cube_system(n, rng), ei.Polyhedron.box([-1] * n, [1] * n)
        for m in polynomial + rational[: 2 if n <= 4 else 0]:
            ratios.append(row(f"cube n={n}", S, P, m))
    for N in ([10, 50] if args.quick else [10, 50, 100, 200]):
        P = polygon(N)
        for m in polynomial + (rational if N <= 50 else []):
            ratios.append(row(f"{N}-gon", ROT, P, m))
    ratios.sort()
    print(f"\nkernel/engine time: median {ratios[len(ratios) // 2]:.2f}, max {ratios[-1]:.2f} over {len(ratios)} instances")


if __name__ == "__main__":
    main()
