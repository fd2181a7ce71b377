"""First sign change: FLINT isolation against the paper's Sturm bisection and sympy.

In one run, on the same polynomials (f(0) = 1, degrees 5..60, coefficients of
16..256 bits, each with a positive root):

* exactinv  -- ``first_sign_change`` (Descartes filter, FLINT factorisation and
               certified Arb isolation; an exact algebraic number);
* paper     -- the paper's Steps 0-5 (Sturm sequence + bisection) in exact
               arithmetic, to width 2^-53 (the repaired bound, erratum E3);
* sympy     -- ``Poly.intervals()`` (sympy's exact real root isolation) and the
               first positive odd-multiplicity root read off.

Run:  python benchmarks/roots.py [--quick]
"""

from __future__ import annotations

import argparse
import random
import time
from fractions import Fraction

import sympy

from exactinv.core.roots import first_sign_change
from exactinv.thresholds.bisection import paper_bisection


def instance(degree: int, bits: int, rng: random.Random) -> list[int]:
    """1 + a_1 t + ... + a_d t^d with random signed coefficients and a root near 1."""
    while True:
        coeffs = [1] + [rng.randint(-(2**bits), 2**bits) for _ in range(degree)]
        total = sum(coeffs)
        coeffs[-1] -= total + rng.randint(1, 2**bits)  # f(1) < 0 < f(0): a sign change in (0, 1)
        if coeffs[-1] != 0:
            return coeffs


def sympy_first(coeffs):
    x = sympy.Symbol("x")
    poly = sympy.Poly(list(reversed(coeffs)), x)
    for (a, b), m in poly.intervals():
        if b > 0 and m % 2:
            return a, b
    return None


def timed(fn, repeat=1):
    t = time.perf_counter()
    for _ in range(repeat):
        out = fn()
    return (time.perf_counter() - t) / repeat, out


def main(argv=None):
    parser = argparse.ArgumentParser()
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args(argv)
    rng = random.Random(7)
    degrees = [5, 20] if args.quick else [5, 10, 20, 40, 60]
    bit_sizes = [16, 64] if args.quick else [16, 64, 256]
    header = f"{'deg':>4}{'bits':>6}{'exactinv ms':>13}{'paper ms':>11}{'sympy ms':>11}{'paper/ours':>12}{'sympy/ours':>12}"
    print(header)
    print("-" * len(header))
    for d in degrees:
        for bits in bit_sizes:
            coeffs = instance(d, bits, rng)
            alphas = [Fraction(c) for c in coeffs]
            te, ours = timed(lambda c=coeffs: first_sign_change(c), repeat=3)
            tp, paper = timed(lambda a=alphas: paper_bisection(a, epsilon=Fraction(1, 2**53), repaired=True))
            ts, interval = timed(lambda c=coeffs: sympy_first(c))
            assert paper.t_l <= ours <= paper.t_r or paper.tau == ours, (paper, ours)
            a, b = interval
            assert sympy.Rational(ours.lower if hasattr(ours, "lower") else ours) <= b
            print(f"{d:>4}{bits:>6}{te * 1e3:>13.2f}{tp * 1e3:>11.1f}{ts * 1e3:>11.1f}{tp / te:>12.0f}{ts / te:>12.1f}")


if __name__ == "__main__":
    main()
