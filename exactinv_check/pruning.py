"""Pruned vertex-facet pairs: which conditions a claim may leave unbuilt.

A claim may carry ``"pruning": {"horizon": T, "vertex": k, "order": [...]}``
(polynomial methods only).  The kernel trusts none of it beyond what it proves:

1. Vertex k bounds the set: the valid set of vertex k's own conditions lies
   in [0, T] (for a largest-threshold claim: its first interval ends by T).
   The valid set of all conditions lies inside it, so nothing beyond T counts.
2. On [0, T] a pair (v, j) cannot bind when its slack exceeds a bound on the
   change of A_d(h)v: with A_d(h) = sum_k h^k N_k (N_0 = I),
       |g_j (A_d(h) - I) v| <= ||g_j||_1 beta_v,  beta_v = max_i (M_T |v|)_i,
       M_T = sum_{k>=1} T^k |N_k|  (entrywise absolute values),
   so b_j - g_j v > ||g_j||_1 beta_v proves the condition positive on [0, T].
   The kernel decides this itself for every pair, in integers: coordinates
   are rounded outwards to a grid of step 1/K, so the test may keep more
   pairs than needed, never fewer.  To stay cheap it first tests blocks of
   consecutive vertices along ``order`` (any permutation; a good one keeps
   near vertices together): the box around a block, widened by the block's
   largest beta, inside the open half-space of facet j prunes the whole block.
3. Every surviving pair, all of vertex k's pairs, every ray and line pair are
   built; with 1 and 2 their valid set (or first interval) is that of all pairs.
"""

from fractions import Fraction
from math import gcd, isqrt

from .rationals import integer, rational, require

K = 1 << 40  # the integer grid


def _ceil(x):
    return -((-x.numerator) // x.denominator)


def _floor(x):
    return x.numerator // x.denominator


def parse(record, vertex_count):
    """(T, k, order) from a pruning record, shape-checked."""
    require(isinstance(record, dict) and set(record) == {"horizon", "vertex", "order"},
            "pruning has the keys horizon, vertex, order")
    T = rational(record["horizon"], "pruning horizon")
    require(T >= 0, "the pruning horizon is negative")
    k = integer(record["vertex"], "pruning vertex", 0, vertex_count)
    order = record["order"]
    require(isinstance(order, list) and len(order) == vertex_count
            and all(type(i) is int for i in order) and sorted(order) == list(range(vertex_count)),
            "pruning order is not a permutation of the vertices")
    return T, k, order


def bound_matrix(N, T):
    """M_T = sum_{k>=1} T^k |N_k| (entrywise)."""
    n = len(N[0])
    M = [[Fraction(0)] * n for _ in range(n)]
    for k in range(1, len(N)):
        Tk = T**k
        for i in range(n):
            for l in range(n):
                M[i][l] += Tk * abs(N[k][i][l])
    return M


def _integer_rows(G, b):
    """Each row of (G | b) times a positive integer: (g+, g-, K b, ||g||_1)."""
    rows = []
    for g, beta in zip(G, b):
        d = 1
        for x in list(g) + [beta]:
            d = d * x.denominator // gcd(d, x.denominator)
        gi = [int(x * d) for x in g]
        rows.append(([max(x, 0) for x in gi], [min(x, 0) for x in gi], int(beta * d) * K, sum(map(abs, gi))))
    return rows


def _outside(row, lo, hi, B):
    """True unless the box [lo, hi] / K widened by B / K lies in g x < b (then the pairs are pruned)."""
    gp, gn, Kb, norm = row
    return Kb <= sum(map(int.__mul__, gp, hi)) + sum(map(int.__mul__, gn, lo)) + norm * B


def survivors(G, b, vertices, N, T, order):
    """{vertex index: [facets]} of the pairs the test on [0, T] cannot prune."""
    M = bound_matrix(N, T)
    rows = _integer_rows(G, b)
    lo = [[_floor(x * K) for x in v] for v in vertices]
    hi = [[_ceil(x * K) for x in v] for v in vertices]
    B = [_ceil(max(sum(Mi[l] * abs(v[l]) for l in range(len(v))) for Mi in M) * K) for v in vertices]
    out = {}
    size = max(1, isqrt(len(vertices)))
    for start in range(0, len(order), size):
        block = order[start:start + size]
        blo = [min(lo[i][l] for i in block) for l in range(len(lo[0]))]
        bhi = [max(hi[i][l] for i in block) for l in range(len(hi[0]))]
        bB = max(B[i] for i in block)
        near = [j for j, row in enumerate(rows) if _outside(row, blo, bhi, bB)]
        for i in block:
            out[i] = [j for j in near if _outside(rows[j], lo[i], hi[i], B[i])]
    return out
