"""The kernel's ellipsoid linear algebra: fraction-free (current) against
Fraction elimination (the route before the red-team fix), in the same run.

* psd(Q), Q dense with one-digit off-diagonal entries and diagonal 10 n:
  symmetric Gaussian elimination in Fractions against the kernel's
  fraction-free (Bareiss) elimination on the integer matrix.
* the forward-Euler conditions c_k (A dense, one-digit off-diagonal entries,
  diagonal -3n; Q = I): Hessenberg characteristic polynomials in Fractions at
  the n + 1 points against the kernel's condition_polynomials (integer
  coefficient matrices, Berkowitz over Z), checked equal up to a positive factor.

Run: python benchmarks/kernel_ellipsoid.py [--max-n 30]
"""

import argparse
import random
import time
from fractions import Fraction

from exactinv_check import poly_arithmetic, resultants
from exactinv_check.ellipsoids import condition_polynomials, psd
from exactinv_check.failure import CheckFailure
from exactinv_check.linalg import characteristic_polynomial


def fraction_psd(M):
    """The previous kernel route: elimination in Fractions on positive pivots."""
    S = [list(r) for r in M]
    rest = list(range(len(S)))
    while rest:
        k = next((i for i in rest if S[i][i] > 0), None)
        if k is None:
            return all(S[i][j] == 0 for i in rest for j in rest), False
        rest.remove(k)
        for a in rest:
            f = S[a][k] / S[k][k]
            if f:
                for b in rest:
                    S[a][b] -= f * S[k][b]
    return True, True


def fraction_conditions(A):
    """Forward Euler, Q = I: M' = -(A^T + A) - h A^T A; the c_k by Hessenberg in Fractions."""
    n = len(A)
    AtA = [[sum(A[k][i] * A[k][j] for k in range(n)) for j in range(n)] for i in range(n)]
    values = []
    for t in range(n + 1):
        Mt = [[-(A[i][j] + A[j][i]) - t * AtA[i][j] for j in range(n)] for i in range(n)]
        p = characteristic_polynomial(Mt)
        values.append([(-1) ** k * p[n - k] for k in range(1, n + 1)])
    points = [Fraction(t) for t in range(n + 1)]
    return [poly_arithmetic.trim([Fraction(0)] + resultants.interpolate(points, [row[k] for row in values])) for k in range(n)]


def _timed(f, *args):
    start = time.perf_counter()
    try:
        out = f(*args)
    except CheckFailure as exc:
        out = f"rejected ({str(exc)[:40]}...)"
    return out, time.perf_counter() - start


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--max-n", type=int, default=30)
    args = parser.parse_args()
    print("psd(Q), dense Q\n| n | Fractions (s) | fraction-free (s) | ratio |\n| --- | --- | --- | --- |")
    for n in (20, 40, 80, 120):
        rng = random.Random(5)
        Q = [[Fraction(0)] * n for _ in range(n)]
        for i in range(n):
            for j in range(i):
                Q[i][j] = Q[j][i] = Fraction(rng.randint(-9, 9))
            Q[i][i] = Fraction(10 * n)
        new, t_new = _timed(psd, Q)
        old, t_old = _timed(fraction_psd, Q) if n <= 80 else (new, float("nan"))
        assert old == new
        print(f"| {n} | {t_old:.3f} | {t_new:.3f} | {t_old / t_new:.1f} |")
    print("\nforward-Euler conditions c_k, dense A, Q = I\n| n | Fractions (s) | Berkowitz over Z (s) | ratio |\n"
          "| --- | --- | --- | --- |")
    for n in (5, 10, 15, 20, 30):
        if n > args.max_n:
            break
        rng = random.Random(4)
        A = [[Fraction(rng.randint(-3, 3) - (3 * n if i == j else 0)) for j in range(n)] for i in range(n)]
        Q = [[Fraction(int(i == j)) for j in range(n)] for i in range(n)]
        (_, new), t_new = _timed(condition_polynomials, A, Q, [Fraction(1), Fraction(1)], [Fraction(1)])
        old, t_old = _timed(fraction_conditions, A)
        for a, b in zip(old, new):  # equal up to a positive factor per condition
            assert all(x * b[-1] == y * a[-1] for x, y in zip(a, b)) and a[-1] * b[-1] > 0
        print(f"| {n} | {t_old:.2f} | {t_new:.2f} | {t_old / t_new:.1f} |")


if __name__ == "__main__":
    main()
