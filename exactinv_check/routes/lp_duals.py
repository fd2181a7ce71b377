"""A *dual piece* of an ``lp`` record: the paper's own certificate (Theorem 2.2) on a piece [a, e], proved.

A dual piece of facet i on [a, e] (a rational, e an exact real or oo) carries
vectors y_0, ..., y_K >= 0 indexed by the rows of G' (G with the record's
``lines`` appended as rows with right-hand side 0), and stands for

    y(h) = sum_k (h - a)^k y_k,

a vector of polynomials that is >= 0 for every h >= a, term by term.  The kernel
proves (docs/design.md, "Dual pieces"):

1. every entry of every y_k is > 0 (the record lists the nonzero entries only);
2. the polynomial identity G'^T y(h) = D(h) N(h)^T g_i, coefficient by
   coefficient in powers of (h - a): G'^T y_k is the k-th Taylor coefficient at
   a of D N^T g_i (D = det h_r(hA), N = D r(hA), rebuilt by the kernel), for
   k = 0, ..., W - 1 (W - 1 the degree bound of D N; y_k = 0 beyond K);
3. q(h) = D(h)^2 b_i - y(h)^T b' >= 0 on the closed piece [a, e] (exact root
   counting: the caller's :func:`exactinv_check.routes.lp_pieces` check).

Then for every x in P' (G' x <= b') and h in [a, e] with D(h) != 0:
D(h) g_i N(h) x = y(h)^T G' x <= y(h)^T b' <= D(h)^2 b_i, so dividing by D(h)^2 > 0,
g_i A_d(h) x <= b_i: facet i is valid at h for P' -- and for P wherever the line
equalities g_i N(h) l_j = 0 hold (P = P' + ker G).  A dual piece adds no condition.

This module parses a dual piece and builds q after proving 1 and 2; everything in
integers (one common denominator per vector), every step charged.
"""

from __future__ import annotations

from fractions import Fraction
from math import gcd
from operator import mul
from typing import Any

from .. import poly_arithmetic
from ..budget import (
    FRACTION_WEIGHT,
    MAX_DEGREE,
    MAX_LP_DUAL_ENTRIES,
    PARSE_ENTRY,
    PYTHON_OP,
    charge,
    content_cost,
    words,
)
from ..failure import CheckFailure, require
from ..rationals import integer, rational


class DualPiece:
    """The vectors y_0, ..., y_K of a dual piece, each a list of (row, value > 0), rows increasing."""

    __slots__ = ("ys",)

    def __init__(self, ys: list[list[tuple[int, Fraction]]]) -> None:
        self.ys = ys

    @property
    def entries(self) -> int:
        return sum(len(y) for y in self.ys)


def parse_dual(data: Any, rows_of_G: int, what: str, room: int) -> DualPiece:
    """A dual piece's ``dual`` list, shape-checked: 1 to MAX_DEGREE + 1 vectors, each a list of [row, value]
    with rows strictly increasing in [0, rows_of_G) and values positive rationals; at most ``room`` entries
    in all, counted before any number is parsed (the record's bound :data:`MAX_LP_DUAL_ENTRIES`)."""
    require(isinstance(data, list) and 1 <= len(data) <= MAX_DEGREE + 1,
            f"{what}: a dual piece is {{\"dual\": [y_0, ..., y_K]}}, at least one vector")
    require(all(isinstance(y, list) for y in data) and sum(len(y) for y in data) <= room,
            f"{what}: vectors y_k are lists, and the record's dual pieces have at most {MAX_LP_DUAL_ENTRIES} "
            "entries in all")
    charge(PARSE_ENTRY * sum(len(y) for y in data), "parsing a dual piece")
    ys = []
    for k, y in enumerate(data):
        require(isinstance(y, list) and len(y) <= rows_of_G, f"{what} y_{k}: a list of [row, value], at most "
                f"{rows_of_G} entries")
        out: list[tuple[int, Fraction]] = []
        last = -1
        for entry in y:
            require(isinstance(entry, list) and len(entry) == 2, f"{what} y_{k}: an entry is [row, value]")
            r = integer(entry[0], f"{what} y_{k} row", 0, rows_of_G)
            require(r > last, f"{what} y_{k}: the rows are not strictly increasing")
            v = rational(entry[1], f"{what} y_{k} value")
            require(v > 0, f"{what} y_{k}: the entry of row {r} is not positive (y >= 0 is needed, zeros are omitted)")
            out.append((r, v))
            last = r
        ys.append(out)
    return DualPiece(ys)


def common_denominator(values: Any, what: str) -> int:
    """The least positive common denominator of some rationals, each step charged before it runs (a gcd and
    a product of the denominator so far by the next one: quadratic in the words, budget.content_cost).

    Found (red team rt-dual): y_0 with 244 entries 1/d_r, the d_r distinct 3990-digit numbers (a 987 KB
    certificate), made a common denominator of 3.2 million bits uncharged -- its gcds, then each entry times
    it and y_0^T b in Fractions: 50 s of CPU before the first charge (past the kernel's clock, which is read
    only at a charge).  The same for G' (G with the record's lines, each line one 1/d_j: 220 lines in a 988 KB
    certificate).  Now the first few dozen steps overdraw the account."""
    den = 1
    for v in values:
        d = v.denominator
        if d != 1:
            charge(content_cost(1, den.bit_length(), d.bit_length()), what)
            den = den * d // gcd(den, d)
    return den


def _scaling_cost(values: Any, den: int, each: int) -> int:
    """The price of x * den for each rational x (den a multiple of its denominator: one exact quotient of
    den's words by x's, one product) plus ``each`` per value; and of their sum, which has den as its
    common denominator (each Fraction sum a gcd of the same sizes)."""
    w = words(den.bit_length())
    return sum(each + 3 * w * words(x.numerator.bit_length() + x.denominator.bit_length()) for x in values)


def _shift(ints: list[int], u: int, v: int) -> list[int]:
    """v^(W-1) p(u/v + y) in powers of y, for p of W integer coefficients (zeros on top allowed): Horner,
    r <- r (u + v y) + c_k v^(W-1-k), exact."""
    W = len(ints)
    q = [ints[-1]]
    for k in range(W - 2, -1, -1):
        q = [u * q[0]] + [u * q[i] + v * q[i - 1] for i in range(1, len(q))] + [v * q[-1]]
        q[0] += ints[k] * v ** (W - 1 - k)
    return q


class DualChecker:
    """G' (common denominator), b', D and N of one problem; per facet the target D N^T g_i, built once."""

    def __init__(self, G: Any, b: Any, D: Any, N: Any) -> None:
        self.b = list(b)
        self.bbits = max(_bits(x) for x in self.b)
        # G' holds the record's lines: their denominators are the record's, charged like y's (common_denominator)
        self.dG = common_denominator((x for row in G for x in row), "the common denominator of G' (G and the lines)")
        charge(_scaling_cost((x for row in G for x in row if x), self.dG, PYTHON_OP), "G' in integers")
        self.Gc = [[int(x * self.dG) for x in row] for row in G]
        self.G = G
        self.D = [Fraction(c) for c in D]
        self.N = N
        self.n = len(G[0])
        self.targets: dict[int, tuple[int, list[list[int]]]] = {}

    def target(self, i: int) -> tuple[int, list[list[int]]]:
        """(f, T): D(h) N(h)^T g_i = T / f, T an n x W integer matrix (row l: component l's coefficients
        from h^0 up, W = len(D) + len(N) - 1 for every row), f > 0."""
        if i not in self.targets:
            n, g = self.n, self.G[i]
            L, W = len(self.N), len(self.N) + len(self.D) - 1
            bits = max(_bits(x) for Nk in self.N for row in Nk for x in row) + max(_bits(x) for x in g)
            # a Fraction product and sum per (column, power, row of g != 0), then per (column, power, coefficient
            # of D): charged as Fraction operations (red team rt-chain: n^2 L PYTHON_OP was 54 times under the
            # CPU time for n = 200, tests/kernel/test_lp_duals_attacks.py)
            nonzero = sum(1 for x in g if x)
            charge(n * L * (nonzero + len(self.D)) * (2 * FRACTION_WEIGHT + words(bits) ** 2),
                   "a dual piece's target D N^T g_i")
            rows = []
            for col in range(n):
                c = [sum(g[r] * Nk[r][col] for r in range(n) if g[r]) for Nk in self.N]
                rows.append(poly_arithmetic.mul(c, self.D) if any(c) else [Fraction(0)])
            rows = [list(r) + [Fraction(0)] * (W - len(r)) for r in rows]
            f = common_denominator((x for row in rows for x in row), "the common denominator of D N^T g_i")
            self.targets[i] = f, [[int(x * f) for x in row] for row in rows]
        return self.targets[i]

    def q(self, i: int, b_i: Fraction, dual: DualPiece, a: Fraction, what: str) -> list[Fraction]:
        """q(h) = D(h)^2 b_i - y(h)^T b' as coefficients from h^0 up, after proving G'^T y_k = the k-th Taylor
        coefficient at a of D N^T g_i for every k (CheckFailure otherwise)."""
        f, T = self.target(i)
        W = len(T[0])
        K1 = len(dual.ys)
        require(K1 <= W, f"{what}: {K1} vectors y_k, but D N^T g_i has only {W} Taylor coefficients")
        u, v = a.numerator, a.denominator
        tbits = max(abs(x).bit_length() for row in T for x in row) + W * _bits(a)
        charge(self.n * W * W * (PYTHON_OP + words(tbits) * words(_bits(a))), "a dual piece's Taylor shift")
        shifted = [_shift(row, u, v) for row in T]  # v^(W-1) T_l(a + y)
        scale = f * v ** (W - 1)
        gbits = max(abs(x).bit_length() for row in self.Gc for x in row)
        betas = []
        for k in range(W):
            y = dual.ys[k] if k < K1 else []
            e = common_denominator((val for _, val in y), f"{what}: the common denominator of y_{k}")
            charge(_scaling_cost((val for _, val in y), e, 2 * FRACTION_WEIGHT + words(self.bbits)),
                   f"{what}: y_{k} in integers and y_{k}^T b")
            Y = [(r, int(val * e)) for r, val in y]
            ybits = max((abs(val).bit_length() for _, val in Y), default=1)
            charge((len(Y) + 1) * self.n * (PYTHON_OP + words(ybits + gbits) * words(scale.bit_length())),
                   "a dual piece's identity G'^T y_k")
            right = e * self.dG
            for col in range(self.n):
                left = sum(Yr * self.Gc[r][col] for r, Yr in Y)
                if left * scale != shifted[col][k] * right:
                    raise CheckFailure(f"{what}: G'^T y_{k} is not the Taylor coefficient {k} at the piece's start "
                                       f"of D(h) N(h)^T g_i (component {col})")
            betas.append(sum(map(mul, (val for _, val in y), (self.b[r] for r, _ in y))) if y else Fraction(0))
        # y(h)^T b' = sum_k beta_k (h - a)^k, expanded in powers of h (Horner in Fractions, W^2 steps)
        charge(W * W * (PYTHON_OP + words(max(_bits(x) for x in betas) + W * _bits(a)) ** 2),
               "a dual piece's y(h)^T b")
        p: list[Fraction] = [betas[-1]]
        for k in range(W - 2, -1, -1):
            p = [betas[k] - a * p[0]] + [p[j] - a * p[j + 1] for j in range(len(p) - 1)] + [p[-1]]
        q: list[Fraction] = poly_arithmetic.sub(poly_arithmetic.scale(poly_arithmetic.mul(self.D, self.D), b_i), p)
        return q


def _bits(x: Any) -> int:
    q = Fraction(x)
    return int(q.numerator.bit_length() + q.denominator.bit_length())
