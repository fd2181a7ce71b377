"""Pruned pairs of a rational method: the variable u = h/(s + h).

A pruning record with ``"variable": "h/(s+h)"`` also names a ``scale`` s > 0
and a number of uniform ``pieces``; its ``horizon`` U (0 <= U <= 1) is in u.
With D(h) = det h_r(hA), N(h) = D(h) r(hA) and E = max(deg D, deg N, 1),

    P(u) = (1 - u)^E diag(D, N)(s u/(1 - u))   (a polynomial matrix in u),

and for a vertex v, a facet (g_j, b_j), w = (1, v), g' = (-b_j, g_j):
g' P(u) w = -(1 - u)^E q(h), q(h) = b_j D(h) - g_j N(h) v, h = s u/(1 - u).
The kernel proves, trusting nothing in the record:

1. U < 1: vertex k's own valid set (first interval) ends by T = sU/(1 - U);
   U = 1 covers every h >= 0 (T = oo), and nothing is asked of vertex k.
2. D > 0 on [0, T] (D(0) > 0 and an exact count of no root in (0, T], Descartes isolation).
3. [0, U] is cut at U x, x in {a/pieces} and {2^-i, 1 - 2^-i : i <= 12}; on a
   piece [t, t + d] the Bernstein coefficients B_0..B_E of P(t + d l) give
   P(t + d l) w in the box of B_0 w and B_E w widened by M |w|,
   M = max_k |B_k - (1 - k/E) B_0 - (k/E) B_E| (entrywise; the Bernstein basis
   is nonnegative and sums to 1).  The kernel divides each piece by a power of
   two (the test g' y < 0 is a cone test) and rounds its ends to a grid,
   widening M by the rounding; the box test of :mod:`exactinv_check.routes.pruning`
   with rows g' and right-hand side 0 then leaves a pair out only when
   g' P(u) w < 0 on all of [0, U]: q > 0, and with 2. c = q D > 0, on [0, T].
4. Every other pair is built; a vertex pair other than vertex k's (any vertex
   pair when U = 1) as q itself, whose sign is c's on [0, T] by 2.
"""

from __future__ import annotations

from fractions import Fraction
from math import comb, gcd
from typing import Any

from .. import budget, poly_arithmetic, polys
from ..budget import MAX_RATIONAL_PIECES as MAX_PIECES
from ..budget import PIECES_BUDGET, PIECES_PER_WORD, charge, within_budget
from ..failure import require, require_budget
from ..format import PRUNING_VARIABLE as VARIABLE
from ..rationals import integer, rational
from . import pruning

KEYS = {"horizon", "vertex", "order", "variable", "scale", "pieces"}
_BITS = 44  # piece ends rounded to multiples of 2^-44 after normalisation (the box grid is 2^-40)




def is_rational_record(record: dict[str, list[int] | int | str]) -> bool:
    """True for a record in the variable u (it names one)."""
    return isinstance(record, dict) and "variable" in record


def parse(record: Any, vertex_count: Any, n: Any) -> Any:
    """(s, U, pieces, k, order) from a record in u, shape-checked and priced."""
    require(isinstance(record, dict) and set(record) == KEYS, f"pruning in u has the keys {', '.join(sorted(KEYS))}")
    require(record["variable"] == VARIABLE, f"pruning variable must be {VARIABLE!r}")
    s = rational(record["scale"], "pruning scale")
    require(s > 0 and max(s.numerator.bit_length(), s.denominator.bit_length()) <= budget.HORIZON_BITS,
            "the pruning scale is a positive rational of at most 64-bit numerator and denominator")
    count = integer(record["pieces"], "pruning pieces", 1, MAX_PIECES + 1)
    U, k, order = pruning.parse({key: record[key] for key in ("horizon", "vertex", "order")}, vertex_count)
    require(U <= 1, "the pruning horizon in u = h/(s+h) is at most 1")
    within_budget(vertex_count * (count + 26) * 3 * (n + 1) ** 2, "the pruning test in u")
    return s, U, count, k, order


def horizon(s: Any, U: Any) -> Any:
    """T = sU/(1 - U), the horizon in h (None for U = 1: every h >= 0)."""
    return None if U == 1 else s * U / (1 - U)


def require_positive_determinant(D: Any, T: Any) -> None:
    """D > 0 on [0, T] (T None: on [0, oo)): else q > 0 would not give c = q D > 0."""
    require(poly_arithmetic.evaluate(D, Fraction(0)) > 0 and polys.count_roots(D, Fraction(0), T) == 0,
            f"det h(hA) vanishes in the pruning range [0, {'oo' if T is None else T}]")


def lifted(D: Any, N: Any, s: Any) -> Any:
    """The coefficients (in u) of P(u) = sum_k s^k u^k (1 - u)^(E-k) diag(D_k, N_k)."""
    n = len(N[0])
    E = max(len(D) - 1, len(N) - 1, 1)
    P = [[[Fraction(0)] * (n + 1) for _ in range(n + 1)] for _ in range(E + 1)]
    for k in range(E + 1):
        block = [[Fraction(0)] * (n + 1) for _ in range(n + 1)]
        block[0][0] = D[k] if k < len(D) else Fraction(0)
        for i in range(n):
            for l in range(n):
                block[i + 1][l + 1] = N[k][i][l] if k < len(N) else Fraction(0)
        for i in range(E - k + 1):
            c = (-1) ** i * comb(E - k, i) * s**k
            for r in range(n + 1):
                for l in range(n + 1):
                    P[k + i][r][l] += c * block[r][l]
    return P


def _entry_bernstein(coeffs: Any, t: Any, d: Any) -> Any:
    """(X, Z, M) of one entry on [t, t + d]: its Bernstein coefficients B_0 .. B_E (degree E) give
    X = B_0, Z = B_E and M = max_k |B_k - (1 - k/E) B_0 - (k/E) B_E|, exactly.  Integers throughout
    (integer Horner on a common denominator, then every B_k over the one denominator R = lcm_k C(E, k)
    times the scale): three fractions per entry, whatever the degree and the size of the numbers."""
    E = len(coeffs) - 1
    L = 1
    for c in coeffs:
        L = L * c.denominator // gcd(L, c.denominator)
    a = [int(c * L) for c in coeffs]
    den = t.denominator * d.denominator
    tn, dn = t.numerator * d.denominator, d.numerator * t.denominator  # t = tn/den, d = dn/den
    h = [a[E]]  # den^E p(t + d l) = sum_i a_i (tn + dn l)^i den^(E-i), by Horner in l
    for i in range(E - 1, -1, -1):
        nxt = [x * tn for x in h] + [0]
        for j, x in enumerate(h):
            nxt[j + 1] += x * dn
        nxt[0] += a[i] * den ** (E - i)
        h = nxt
    Q = 1
    for k in range(E + 1):
        Q = Q * comb(E, k) // gcd(Q, comb(E, k))
    b = [sum(comb(E - i, k - i) * h[i] for i in range(k + 1)) * (Q // comb(E, k)) for k in range(E + 1)]  # B_k R
    R = Q * L * den**E
    M = max(abs(E * b[k] - (E - k) * b[0] - k * b[E]) for k in range(E + 1))
    return Fraction(b[0], R), Fraction(b[E], R), Fraction(M, E * R)


def _piece(P: Any, t: Any, d: Any) -> Any:
    """(X, Z, M) of the piece [t, t + d] (module docstring, 3.), normalised and rounded."""
    size, E = len(P[0]), len(P) - 1
    X = [[Fraction(0)] * size for _ in range(size)]
    Z = [[Fraction(0)] * size for _ in range(size)]
    M = [[Fraction(0)] * size for _ in range(size)]
    for r in range(size):
        for c in range(size):
            coeffs = [P[k][r][c] for k in range(E + 1)]
            if any(coeffs):
                X[r][c], Z[r][c], M[r][c] = _entry_bernstein(coeffs, t, d)
    top = max(sum(abs(x) for x in row) for row in X + Z)
    f = Fraction(1) if top == 0 else Fraction(2) ** -(top.numerator.bit_length() - top.denominator.bit_length())
    grid = 1 << _BITS

    def near(x: Any) -> Any:  # nearest multiple of 2^-_BITS: moves by <= 2^-(_BITS+1)
        return Fraction((2 * x.numerator * grid + x.denominator) // (2 * x.denominator), grid)

    def up(x: Any) -> Any:  # a multiple of 2^-_BITS >= x + 2^-(_BITS+1) (the widening by the rounding of X and Z)
        y = x + Fraction(1, 2 * grid)
        return Fraction(-((-y.numerator * grid) // y.denominator), grid)

    return ([[near(x * f) for x in row] for row in X], [[near(x * f) for x in row] for row in Z],
            [[up(x * f) for x in row] for row in M])


def nodes(U: Any, count: Any) -> Any:
    """The ends of the pieces of [0, U]."""
    xs = {Fraction(a, count) for a in range(count + 1)}
    xs |= {Fraction(1, 2**i) for i in range(1, 13)} | {1 - Fraction(1, 2**i) for i in range(1, 13)}
    return [U * x for x in sorted(xs)]


def pieces_cost(D: Any, N: Any, s: Any, ends: Any) -> Any:
    """The price of the Bernstein pieces, by the size of their numbers: per piece and entry of the
    (n + 1) x (n + 1) lifted matrix, (E + 1)^2 products of integers of B bits (Horner, the B_k; a
    product of a big by a small integer runs in C, counted per 512 bits) and three gcds of B-bit
    integers (quadratic, counted per 64-bit word squared).  B: E times the bits of the scale and of
    the piece ends plus E + 1 times those of the lifted coefficients (their common denominator).
    Measured: a genuine Pade(6,6) record on R^6 costs 7e8 here and runs in about a second."""
    E, size = max(len(D) - 1, len(N) - 1, 1), len(N[0]) + 1
    def size_of(x: Any) -> Any:
        return x.numerator.bit_length() + x.denominator.bit_length()

    coefficient_bits = max([size_of(c) for c in D] + [size_of(x) for Nk in N for row in Nk for x in row])
    end_bits = max(size_of(t) for t in ends)
    bits = (E + 1) * coefficient_bits + E * (size_of(s) + 2 * end_bits)
    return (len(ends) - 1) * size**2 * ((E + 1) ** 2 * (1 + bits // 512) + 3 * (1 + bits // 64) ** 2)


def survivors(G: Any, b: Any, vertices: Any, D: Any, N: Any, s: Any, U: Any, count: Any) -> Any:
    """{vertex index: [facets]} of the pairs the lifted test on [0, U] cannot prune."""
    ends = nodes(U, count)
    cost = pieces_cost(D, N, s, ends)
    require_budget(cost <= PIECES_BUDGET, f"over the kernel's work budget: the Bernstein pieces of the pruning test in u "
            f"(estimated {cost:.2e} > {PIECES_BUDGET:.0e})")
    charge(cost // PIECES_PER_WORD, "the Bernstein pieces of the pruning test in u")
    P = lifted(D, N, s)
    pieces = [_piece(P, t, u - t) for t, u in zip(ends, ends[1:])]
    rows = [[-beta] + list(g) for g, beta in zip(G, b)]
    lifted_vertices = [[Fraction(1)] + list(v) for v in vertices]
    return pruning.survivors_of_pieces(rows, [Fraction(0)] * len(G), lifted_vertices, pieces)
