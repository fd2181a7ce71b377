"""Pruned vertex-facet pairs: which conditions a claim may leave unbuilt.

A claim may carry ``"pruning": {"horizon": T, "vertex": k, "order": [...]}``
(polynomial methods only).  The kernel trusts none of it beyond what it proves:

1. Vertex k bounds the set: the valid set of vertex k's own conditions lies
   in [0, T] (for a largest-threshold claim: its first interval ends by T).
   The valid set of all conditions lies inside it, so nothing beyond T counts.
2. On [0, T] a pair (v, j) cannot bind when the path A_d(h) v stays strictly
   inside facet j's half-space.  [0, T] is cut into pieces [t, t + d] at the
   nodes T x, x in {0, 1, a/16, 2^-i, 1 - 2^-i : a < 16, i <= 12}; with
   A_d(h) = sum_k h^k N_k (N_0 = I) and s = h - t in [0, d],
       A_d(t + s) = sum_k s^k D_k,  D_k = sum_{i>=k} C(i, k) t^(i-k) N_i,
       A_d(t + s) v = X + s Y + R(s),  X = D_0 v,  Y = D_1 v,
       |R(s)| <= M |v| entrywise,  M = sum_{k>=2} d^k |D_k|,
   so on the piece A_d(h) v lies within rho_v = max_i (M |v|)_i (in every
   coordinate) of the chord from X to Z = X + d Y.  A linear function is
   largest on the chord at an end: both ends, widened by rho_v, inside the
   open half-space g_j x < b_j on every piece prove the condition positive
   on [0, T].  The kernel decides this itself for every pair, in
   integers: coordinates are rounded outwards to a grid of step 1/K, so it
   may keep more pairs than needed, never fewer.  To stay cheap it tests
   boxes around blocks of consecutive vertices along ``order`` (any
   permutation; a good one keeps near vertices together) first over all
   pieces at once, then piece by piece, and only then vertex by vertex.
3. Every surviving pair, all of vertex k's pairs, every ray and line pair are
   built; with 1 and 2 their valid set (or first interval) is that of all pairs.
The horizon is short (numerator and denominator of at most 64 bits): the pieces' exact powers t^i then stay
small; a longer one is rejected before any piece is built.
"""

from fractions import Fraction
from math import comb, gcd, isqrt

from .rationals import integer, rational, require

K = 1 << 40  # the integer grid
HORIZON_BITS = 64  # the horizon's numerator and denominator: the pieces' powers t^i stay short (work budget)


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
    require(max(T.numerator.bit_length(), T.denominator.bit_length()) <= HORIZON_BITS,
            f"over the kernel's work budget: the pruning horizon needs a numerator and denominator of at most "
            f"{HORIZON_BITS} bits (a short upper bound of the set's end)")
    k = integer(record["vertex"], "pruning vertex", 0, vertex_count)
    order = record["order"]
    require(isinstance(order, list) and len(order) == vertex_count
            and all(type(i) is int for i in order) and sorted(order) == list(range(vertex_count)),
            "pruning order is not a permutation of the vertices")
    return T, k, order


def nodes(T):
    """The ends of the pieces of [0, T]."""
    if T == 0:
        return [Fraction(0), Fraction(0)]
    xs = {Fraction(0), Fraction(1)} | {Fraction(a, 16) for a in range(1, 16)}
    xs |= {Fraction(1, 2**i) for i in range(1, 13)} | {1 - Fraction(1, 2**i) for i in range(1, 13)}
    return [T * x for x in sorted(xs)]


def _piece(N, t, d):
    """(D_0, d D_1, M) for the piece [t, t + d]: A_d(t + s) = sum_k s^k D_k with
    D_k = sum_{i>=k} C(i, k) t^(i-k) N_i, and M = sum_{k>=2} d^k |D_k| entrywise."""
    n = len(N[0])
    D = [[[sum(comb(i, k) * t ** (i - k) * N[i][r][c] for i in range(k, len(N))) for c in range(n)] for r in range(n)]
         for k in range(len(N))]
    zero = [[Fraction(0)] * n for _ in range(n)]
    Y = [[d * x for x in row] for row in D[1]] if len(D) > 1 else zero
    M = [[sum(d**k * abs(D[k][r][c]) for k in range(2, len(D))) for c in range(n)] for r in range(n)]
    return D[0], Y, M


def _integer_rows(G, b):
    """Each row of (G | b) times a positive integer: (g+ g- ||g||_1 concatenated, K b)."""
    rows = []
    for g, beta in zip(G, b):
        d = 1
        for x in list(g) + [beta]:
            d = d * x.denominator // gcd(d, x.denominator)
        gi = [int(x * d) for x in g]
        rows.append(([max(x, 0) for x in gi] + [min(x, 0) for x in gi] + [sum(map(abs, gi))], int(beta * d) * K))
    return rows


def _integer_matrix(Q):
    """(Q_int, d) with Q = Q_int / d, d > 0."""
    d = 1
    for row in Q:
        for x in row:
            d = d * x.denominator // gcd(d, x.denominator)
    return [[int(x * d) for x in row] for row in Q], d


def chord_pieces(N, T):
    """(X, Z, M) per piece of [0, T]: the chord ends X = A_d(t), Z = A_d(t + d) and the remainder M."""
    ends = nodes(T)
    out = []
    for t, u in zip(ends, ends[1:]):
        X, Y, M = _piece(N, t, u - t)
        out.append((X, [[x + y for x, y in zip(rx, ry)] for rx, ry in zip(X, Y)], M))
    return out


def _boxes(vertices, pieces):
    """boxes[i][a] = (end X, end Z), each hi + lo + [B]: the integer box around one chord end
    of vertex i on piece a (scaled by K, rounded outwards, so at most one grid step wide),
    widened by B / K >= rho; integer arithmetic only.  The chord's box is their union; a
    linear function is largest on the chord at one of its ends, so a half-space holding
    both widened end boxes holds the whole path on the piece."""
    maps = [(_integer_matrix(X), _integer_matrix(Z), _integer_matrix(M)) for X, Z, M in pieces]
    out = []
    for v in vertices:
        q = 1
        for x in v:
            q = q * x.denominator // gcd(q, x.denominator)
        p = [int(x * q) for x in v]
        ap = [abs(x) for x in p]
        mine = []
        for (Xi, dX), (Zi, dZ), (Mi, dM) in maps:
            x = [sum(map(int.__mul__, row, p)) for row in Xi]  # dX q (X v)
            z = [sum(map(int.__mul__, row, p)) for row in Zi]
            rho = max(sum(map(int.__mul__, row, ap)) for row in Mi)  # dM q rho
            dx, dz = dX * q, dZ * q
            B = [-((-K * rho) // (dM * q))]
            mine.append(([-((-K * a) // dx) for a in x] + [(K * a) // dx for a in x] + B,
                         [-((-K * c) // dz) for c in z] + [(K * c) // dz for c in z] + B))
        out.append(mine)
    return out


def _union(boxes):
    """The box around boxes given as (hi lo B concatenated): coordinate-wise max of hi and B, min of lo."""
    n = (len(boxes[0]) - 1) // 2
    cols = list(zip(*boxes))
    return [max(c) for c in cols[:n]] + [min(c) for c in cols[n:2 * n]] + [max(cols[-1])]


def _outside(row, box):
    """True unless the box [lo, hi] / K widened by B / K lies in g x < b (then the pairs are pruned):
    max over the box of g x is g+ hi + g- lo, and |g (A_d - I) ...| adds at most ||g||_1 B / K."""
    return row[1] <= sum(map(int.__mul__, row[0], box))


def survivors(G, b, vertices, N, T, order):
    """{vertex index: [facets]} of the pairs the test on the pieces of [0, T] cannot prune."""
    return survivors_of_pieces(G, b, vertices, chord_pieces(N, T), order)


def survivors_of_pieces(G, b, vertices, pieces, order):
    """{vertex index: [facets]} of the pairs the chord test cannot prune on the pieces
    given as (X, Z, M): the path of v on a piece lies in the box of X v and Z v widened
    by max_i (M |v|)_i."""
    rows = _integer_rows(G, b)
    boxes = _boxes(vertices, pieces)
    out = {i: [] for i in range(len(vertices))}
    size = max(1, isqrt(len(vertices)))
    for start in range(0, len(order), size):
        block = order[start:start + size]
        per_piece = [_union([end for i in block for end in boxes[i][a]]) for a in range(len(boxes[block[0]]))]
        whole = _union(per_piece)
        near = [j for j, row in enumerate(rows) if _outside(row, whole)]
        for a, box in enumerate(per_piece):
            hits = [j for j in near if _outside(rows[j], box)]
            for i in block:
                x, z = boxes[i][a]
                out[i].extend(j for j in hits if _outside(rows[j], x) or _outside(rows[j], z))
    return {i: sorted(set(f)) for i, f in out.items()}
