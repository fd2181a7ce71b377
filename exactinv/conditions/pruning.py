"""Certified pruning of vertex-facet pairs before any polynomial is built (issue 13).

For a polynomial method A_d(h) = sum_k h^k N_k (N_0 = I), split [0, T] into
pieces [t, t + d] (:func:`nodes`: graded towards both ends, where images
are close to the boundary).  On a piece, with s = h - t in [0, d],

    A_d(t + s) = sum_k s^k D_k,  D_k = sum_{i>=k} C(i, k) t^(i-k) N_i  (exact),
    A_d(t + s) v = X + s Y + R(s),  X = D_0 v,  Y = D_1 v,
    |R(s)| <= M |v| entrywise,  M = sum_{k>=2} d^k |D_k|,

so g_j A_d(h) v <= max(g_j X, g_j Z) + ||g_j||_1 rho_v with Z = X + d Y
and rho_v = max_i (M |v|)_i: the linear part is largest at an end of the
chord.  (Expanding at t, not at 0, keeps the cancellation of alternating
series such as exp(-t): M is small where A_d(h) is.)  A pair whose slacks
b_j - g_j X and b_j - g_j Z both exceed ||g_j||_1 rho_v -- a per-facet norm
times a per-vertex bound, compared with per-vertex slacks -- satisfies its
condition strictly on the piece; a pair that passes on every piece cannot
bind anywhere in [0, T] and is not built.
Rays are never pruned and lines give equalities, which no slack can settle;
both keep every pair.

Which T.  If S is any set of conditions whose valid set V_S lies in [0, T]
(here: every condition of one vertex, whose valid set is bounded for most
methods and vertices), then the valid set V of all conditions satisfies
V = V_{S u U} with U the pairs that survive the test on [0, T]: beyond T
both sides are empty (V is inside V_S), and on [0, T] every pruned condition
is positive.  The same T serves the largest threshold: its value is at most
the first end of S, hence at most T.  The kernel repeats the test exactly
(:mod:`exactinv_check.routes.pruning`); the certificate only names T and the vertex.

The engine's test is vectorised and exact: every quantity is rounded to an
integer grid of step 2^-24 (relative to the points' size; each gridded
coordinate within 2 steps of the exact one, an error the slack test
subtracts), the slacks are products of int64 matrices (numpy, bounded
magnitudes: no overflow) -- first for boxes around blocks of 64 vertices,
then vertex by vertex for the facets a block's box does not clear -- and a
pair survives unless its rounded slack provably exceeds its rounded bound.  Rounding only lets more pairs
survive, never fewer.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace
from fractions import Fraction
from math import comb

import flint
import numpy as np

from exactinv_check.format import HORIZON_BITS  # the kernel's bound on the horizon's numerator and denominator

from ..core.algebraic import upper_bound
from ..core.flintq import fmpq_of, fraction_of
from ..core.float_hint import float_hints
from ..core.intervals import IntervalUnion
from ..core.nonnegative import earliest_first, nonnegative_set
from ..core.nonnegative import first_end as earliest_end
from ..core.scalars import Infinity
from .polyhedron import Kind

__all__ = ["Pruning", "nodes", "piece", "surviving_pairs", "pieces_test", "coarse_above", "vertex_order",
           "bounding_horizon", "prune", "build_survivors"]

_BITS = 24  # the grid: K = 2^24
_BLOCK = 64  # vertices per block of the box test
WORTHWHILE = 0.3  # above this fraction of surviving pairs, build all pairs at once


def coarse_above(x: Fraction, bits: int = 64) -> Fraction:
    """A dyadic rational >= x with about ``bits`` significant bits (0 for x = 0).

    >>> coarse_above(Fraction(1, 3), 8)
    Fraction(171, 512)
    """
    if x == 0:
        return Fraction(0)
    shift = bits - (x.numerator.bit_length() - x.denominator.bit_length())
    if shift > 0:
        return Fraction(-((-x.numerator << shift) // x.denominator), 1 << shift)
    return Fraction(-(-x.numerator // (x.denominator << -shift)) << -shift)


def nodes(T: Fraction) -> list[Fraction]:
    """The ends of the pieces of [0, T]: T x for x in 0, 1, a/16 and 2^-i, 1 - 2^-i (i <= 12).

    >>> nodes(Fraction(0))
    [Fraction(0, 1), Fraction(0, 1)]
    >>> len(nodes(Fraction(1)))
    33
    """
    if T == 0:
        return [Fraction(0), Fraction(0)]
    xs = {Fraction(0), Fraction(1)} | {Fraction(a, 16) for a in range(1, 16)}
    xs |= {Fraction(1, 2**i) for i in range(1, 13)} | {1 - Fraction(1, 2**i) for i in range(1, 13)}
    return [T * x for x in sorted(xs)]


def piece(N: list[flint.fmpq_mat], t: Fraction, d: Fraction):
    """(A_d(t), d A_d'(t), M) for the piece [t, t + d]: with A_d(t + s) = sum_k s^k D_k
    (D_k = sum_{i>=k} C(i, k) t^(i-k) N_i, exact), M = sum_{k>=2} d^k |D_k| bounds the
    remainder |A_d(t + s) - D_0 - s D_1| entrywise for s in [0, d].

    >>> X, Y, M = piece([flint.fmpq_mat([[1]]), flint.fmpq_mat([[-1]]), flint.fmpq_mat([[1, ]])], Fraction(1), Fraction(1))
    >>> X[0, 0], Y[0, 0], M
    (1, 1, [[Fraction(1, 1)]])
    """
    n = N[0].nrows()
    tq, dq = fmpq_of(t), fmpq_of(d)
    D = []
    for k in range(len(N)):
        Dk = N[0] * 0
        for i in range(k, len(N)):
            Dk += N[i] * (comb(i, k) * tq ** (i - k))
        D.append(Dk)
    M = [[Fraction(0)] * n for _ in range(n)]
    for k in range(2, len(D)):
        dk = d**k
        for i in range(n):
            for l in range(n):
                M[i][l] += dk * abs(fraction_of(D[k][i, l]))
    return D[0], (D[1] * dq if len(D) > 1 else D[0] * 0), M


def _grid(Q: flint.fmpq_mat, Wf: flint.fmpz_mat, f: int, e: int, Wn: np.ndarray | None = None) -> np.ndarray:
    """floor(2^(e-f) Q Wf) entrywise as int64, Wf = floor(2^f W): within 1 + 2^(e-f) ||Q||_oo of 2^e Q W.
    ``Wn``: Wf as an int64 array; the product is then taken in int64 whenever every partial sum provably stays below 2^62."""
    Qz, dQ = Q.numer_denom()
    d = int(dQ) << (f - e)
    if Wn is not None:
        Qi = [int(x) for x in Qz.entries()]
        wmax = int(np.abs(Wn).max()) if Wn.size else 0
        if max(map(abs, Qi), default=0) * wmax * Q.ncols() < 2**62 and d < 2**62:
            return np.array(Qi, dtype=np.int64).reshape(Q.nrows(), Q.ncols()) @ Wn // d
    return np.array([int(x) // d for x in (Qz * Wf).entries()], dtype=np.int64).reshape(Q.nrows(), Wf.ncols())


def _norm(Q: flint.fmpq_mat) -> Fraction:
    """||Q||_oo, the largest absolute row sum (so |Q v|_oo <= ||Q||_oo |v|_oo)."""
    return max(sum(abs(fraction_of(Q[i, l])) for l in range(Q.ncols())) for i in range(Q.nrows()))


def _dot(Gt: np.ndarray, U: np.ndarray) -> np.ndarray:
    """Gt @ U for a small inner dimension (int64 matmul has no BLAS: outer products are faster)."""
    out = Gt[:, 0, None] * U[0]
    for l in range(1, Gt.shape[1]):
        out += Gt[:, l, None] * U[l]
    return out


def surviving_pairs(G: flint.fmpq_mat, b: list, W: flint.fmpq_mat, N: list[flint.fmpq_mat],
                    T: Fraction) -> tuple[np.ndarray, np.ndarray]:
    """(facets, vertices): the pairs (j, i) that the test on the pieces of [0, T] cannot prune.

    Every pair not returned has, on every piece, both chord-end slacks above
    ||g_j||_1 rho_v, proved on the integer grid (see the module docstring).

    >>> G, W = flint.fmpq_mat([[1], [-1]]), flint.fmpq_mat([[1, -1]])   # [-1, 1], vertices 1 and -1
    >>> f, v = surviving_pairs(G, [1, 1], W, [flint.fmpq_mat([[1]]), flint.fmpq_mat([[-1]])], Fraction(1, 2))
    >>> sorted(zip(v.tolist(), f.tolist()))   # x' = -x, forward Euler: the far facet of each vertex is pruned
    [(0, 0), (1, 1)]
    """
    ends = nodes(T)
    return pieces_test(G, b, W, [piece(N, t, u - t) for t, u in zip(ends, ends[1:])], vertex_order(W))


def pieces_test(G: flint.fmpq_mat, b: list, W: flint.fmpq_mat, pieces: list, order: list[int]
                ) -> tuple[np.ndarray, np.ndarray]:
    """(facets, vertices) that survive the chord test on the given pieces: each piece is
    (X, Y, M), the path of a point w on it lies in the box of X w and (X + Y) w widened
    by max_i (M |w|)_i.  ``order`` groups the points into blocks (any permutation).

    >>> G, W = flint.fmpq_mat([[1], [-1]]), flint.fmpq_mat([[1, -1]])   # one piece: w -> w/2 exactly
    >>> f, v = pieces_test(G, [1, 1], W, [(flint.fmpq_mat([[1]]), flint.fmpq_mat([[-1, ]]) / 2, [[0]])], [0, 1])
    >>> sorted(zip(v.tolist(), f.tolist()))
    [(0, 0), (1, 1)]
    """
    n, m, V = W.nrows(), G.nrows(), W.ncols()
    K = 1 << _BITS
    maps = [Q for X, Y, _ in pieces for Q in (X, X + Y)] + [pieces[0][0] ** 0]  # the chord ends, then w itself
    Wz, dW = W.numer_denom()
    vmax = Fraction(max((abs(int(x)) for x in Wz.entries()), default=0), int(dW))
    qmax = max(_norm(Q) for Q in maps)
    top = vmax * qmax  # >= every |coordinate| of every point
    r = math.ceil(top).bit_length() if top else 0
    R = Fraction(2) ** r
    e = _BITS - r
    f = max(e, 0) + math.ceil(qmax).bit_length() + 1  # 2^(f-e) >= ||Q||_oo: grid error <= 2
    Wf = flint.fmpz_mat(W.nrows(), W.ncols(), [(x * 2**f).floor() for x in W.entries()])
    big = max((abs(int(x)) for x in Wf.entries()), default=0) >= 2**62
    Wn = None if big else np.array([int(x) for x in Wf.entries()], dtype=np.int64).reshape(n, V)
    grids = [_grid(Q, Wf, f, e, Wn) for Q in maps]
    a = np.abs(grids.pop()) + 2  # >= |v| K / R
    cap = Fraction(2**62, n * (K + 1) * K)
    if n > 64 or any(x > cap for _, _, M in pieces for row in M for x in row):
        return np.repeat(np.arange(m), V), np.tile(np.arange(V), m)  # bounds too large to prune anything
    rho = [(np.array([[math.ceil(x * K) for x in row] for row in M], dtype=np.int64) @ a).max(axis=0)
           for _, _, M in pieces]  # >= K^2 rho_v / R
    Gt, bt = _facet_grid(G, b, K, int(R))
    bt = (bt - ((n + 3) * K + 2 * n))[:, None]  # minus the rounding error E
    return _blocked_test(Gt, bt, grids, rho, np.array(order, dtype=np.int64))


def _facet_grid(G: flint.fmpq_mat, b: list, K: int, R: int) -> tuple[np.ndarray, np.ndarray]:
    """(round(K g_j / ||g_j||_1) half to even, floor(K^2 clamp(b_j / (||g_j||_1 R), -n - 4, n + 4))) per facet,
    in integers: g_j / ||g_j||_1 = a_j / ||a_j||_1 for the integer rows a_j = dG g_j (dG > 0)."""
    n, m = G.ncols(), G.nrows()
    Gz, dG = G.numer_denom()
    a, dG, top = [int(x) for x in Gz.entries()], int(dG), (n + 4) * K * K
    Gt, bt = [], []
    for j in range(m):
        row = a[j * n:(j + 1) * n]
        A = sum(map(abs, row))
        Gt.append([_round_half_even(x * K, A) for x in row])
        bj = fraction_of(b[j])
        bt.append(min(max(bj.numerator * dG * K * K // (bj.denominator * A * R), -top), top))
    return np.array(Gt, dtype=np.int64).reshape(m, n), np.array(bt, dtype=np.int64)


def _round_half_even(x: int, d: int) -> int:
    """round(x / d) for d > 0, ties to even (Python's round of a Fraction)."""
    q, r = divmod(x, d)
    return q + (2 * r > d or (2 * r == d and q % 2 == 1))


def _blocked_test(Gt, bt, grids, rho, order):
    """The surviving (facets, vertices): boxes around blocks of vertices (along ``order``)
    first, then vertex by vertex for the facets a block's box does not clear -- on each
    piece only the facets that block's box does not clear on that piece (a box that
    clears a facet clears it for every vertex of the block: the result is the vertex test)."""
    m, V = Gt.shape[0], grids[0].shape[1]
    size = _BLOCK
    blocks = -(-V // size)
    idx = np.concatenate([order, np.repeat(order[-1:], blocks * size - V)]).reshape(blocks, size)
    Gp, Gn = np.maximum(Gt, 0), np.minimum(Gt, 0)
    near = np.zeros((len(rho), blocks, m), dtype=bool)  # near[k, blk, j]: piece k's box test fails
    for k, bound in enumerate(rho):
        X, Z = grids[2 * k][:, idx], grids[2 * k + 1][:, idx]  # n x blocks x size
        lo, hi = np.minimum(X, Z).min(axis=2), np.maximum(X, Z).max(axis=2)
        near[k] = (bt - _dot(Gp, hi) - _dot(Gn, lo) <= bound[idx].max(axis=1)[None, :]).T
    facets, vertices = [], []
    for blk in range(blocks):
        F = np.nonzero(near[:, blk].any(axis=0))[0]
        if not len(F):
            continue
        cols = np.unique(idx[blk])
        keep = np.zeros((len(F), len(cols)), dtype=bool)
        for k, bound in enumerate(rho):
            rows = np.nonzero(near[k, blk, F])[0]
            if not len(rows):
                continue
            Gk, bk = Gt[F[rows]], bt[F[rows]]
            for U in grids[2 * k: 2 * k + 2]:
                keep[rows] |= bk - _dot(Gk, U[:, cols]) <= bound[None, cols]
        j, i = np.nonzero(keep)
        facets.append(F[j])
        vertices.append(cols[i])
    if not facets:
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    return np.concatenate(facets), np.concatenate(vertices)


def vertex_order(W: flint.fmpq_mat) -> list[int]:
    """A permutation of the vertices that keeps near vertices near (Morton order of
    rounded coordinates): the kernel checks the pruning block by block along it.
    Only a hint -- any permutation is correct, a good one is faster to check.

    >>> vertex_order(flint.fmpq_mat([[0, 5, 1, 4]]))
    [0, 2, 3, 1]
    """
    n, V = W.nrows(), W.ncols()
    dims = min(n, max(1, 48 // 12))
    x = float_hints(W.entries()[: dims * V]).reshape(dims, V)
    x[~np.isfinite(x)] = 0.0  # beyond double range: any order is correct
    lo, hi = x.min(axis=1, keepdims=True), x.max(axis=1, keepdims=True)
    q = ((x - lo) / np.where(hi > lo, hi - lo, 1) * 4095).astype(np.int64)
    key = np.zeros(V, dtype=np.int64)
    for bit in range(11, -1, -1):
        for l in range(dims):
            key = (key << 1) | ((q[l] >> bit) & 1)
    return [int(i) for i in np.argsort(key, kind="stable")]


@dataclass(frozen=True)
class Pruning:
    """How the pairs were pruned: the ``horizon`` T (a rational bound on the valid set,
    or on its first interval, given by vertex ``vertex``), the number of vertex-facet
    ``pairs``, the ``survivors`` built as polynomials, and seconds per stage.
    ``applied`` is False when too many survived (more than :data:`WORTHWHILE` of
    the pairs): then every pair was built by the all-pairs products instead."""

    horizon: Fraction
    vertex: int
    pairs: int
    survivors: int
    order: tuple[int, ...] = field(repr=False)
    seconds: tuple[tuple[str, float], ...] = field(default=(), compare=False)
    applied: bool = True
    variable: dict = field(default_factory=dict)  # rational methods: {"variable", "scale", "pieces"}

    def record(self) -> dict | None:
        """The certificate's pruning record: the kernel recomputes the rest.  For a
        rational method the horizon is in the variable u = h/(s + h) (:mod:`.pruning_rational`).

        >>> Pruning(Fraction(2), 0, 4, 3, (1, 0)).record()      # x' = -x on [-1, 1]: T = 2
        {'horizon': '2', 'vertex': 0, 'order': [1, 0]}
        >>> Pruning(Fraction(1), 0, 4, 2, (0, 1), variable={"variable": "h/(s+h)", "scale": "1", "pieces": 8}).record()
        {'horizon': '1', 'vertex': 0, 'order': [0, 1], 'variable': 'h/(s+h)', 'scale': '1', 'pieces': 8}
        >>> Pruning(Fraction(2), 0, 4, 4, (1, 0), applied=False).record() is None
        True
        """
        if not self.applied:
            return None
        return {"horizon": str(self.horizon), "vertex": self.vertex, "order": list(self.order), **self.variable}

    def finished(self, total: float) -> "Pruning":
        """With the remaining time (roots and intervals) as the last stage.

        >>> p = Pruning(Fraction(2), 0, 4, 3, (0, 1), (("bounding vertex", 0.25), ("bounds and slacks", 0.5)))
        >>> p.finished(1.0).seconds[-1]                          # 1 - 0.25 - 0.5 (binary fractions: exact)
        ('roots and intervals', 0.25)
        """
        rest = total - sum(s for _, s in self.seconds)
        return replace(self, seconds=self.seconds + (("roots and intervals", rest),))


def bounding_horizon(cs, first_end: bool) -> tuple[Fraction | None, list, list, IntervalUnion | None]:
    """(T, conditions of vertex 0, stage times, the valid set of vertex 0): T a rational upper
    bound on the valid set of vertex 0 (or, with ``first_end``, on the end of its first interval;
    then the set is not computed: None); T is None if unbounded.  Earliest conditions first, each
    skipped when proved positive up to the bound so far (:mod:`..core.nonnegative`).

    >>> import exactinv as ei
    >>> from exactinv.conditions.polyhedron import ConditionSet
    >>> cs = ConditionSet(ei.LinearSystem([[-1]]), ei.Polyhedron([[1], [-1]], [1, 1]), ei.methods.taylor(1))
    >>> T, _, _, vertex_zero = bounding_horizon(cs, False)
    >>> T, vertex_zero
    (Fraction(2, 1), [0, 2])
    """
    t0 = time.perf_counter()
    first = cs.pairs(Kind.VERTEX, [(0, j) for j in range(cs.polyhedron.m)])
    union = None
    if first_end:
        end = earliest_end([c.p for c in first])
    else:
        union = nonnegative_set(earliest_first([c.p for c in first]))
        end = union.intervals[-1].hi if union.intervals else Fraction(0)
    T = None if isinstance(end, Infinity) else _short_horizon(upper_bound(end))
    return T, first, [("bounding vertex", time.perf_counter() - t0)], union


def _short_horizon(x: Fraction) -> Fraction | None:
    """A dyadic T >= x with numerator and denominator of at most HORIZON_BITS bits (the kernel's bound: cheap
    pieces), or None when x is too large for one (then nothing is pruned).

    >>> _short_horizon(Fraction(1, 3)), _short_horizon(Fraction(3, 2**80)), _short_horizon(Fraction(2**70))
    (Fraction(699051, 2097152), Fraction(1, 9223372036854775808), None)
    """
    T = coarse_above(x, 20)
    if T.denominator.bit_length() > HORIZON_BITS:  # x < 2^-43: round up on the grid 2^-63 instead
        scale = 1 << (HORIZON_BITS - 1)
        T = Fraction(-(-x.numerator * scale // x.denominator), scale)
    return T if T.numerator.bit_length() <= HORIZON_BITS else None


def prune(cs, T: Fraction, first: list, seconds: list) -> tuple[list, list, Pruning]:
    """(inequalities, equalities, record) for the horizon T: vertex 0's conditions,
    the surviving vertex-facet pairs, every ray pair (inequalities) and line pair.

    >>> import exactinv as ei
    >>> from exactinv.conditions.polyhedron import ConditionSet
    >>> cs = ConditionSet(ei.LinearSystem([[-1]]), ei.Polyhedron([[1], [-1]], [1, 1]), ei.methods.taylor(1))
    >>> T, first, seconds, _ = bounding_horizon(cs, False)
    >>> prune(cs, Fraction(1, 2), first, seconds)[2].survivors   # vertex 0's two pairs, vertex 1's own facet
    3
    """
    t0 = time.perf_counter()
    facets, vertices = surviving_pairs(cs.G, cs.b, cs.W[Kind.VERTEX], cs.N, T)
    return build_survivors(cs, facets, vertices, first, tuple(seconds) + (("bounds and slacks", time.perf_counter() - t0),),
                           Pruning(T, 0, 0, 0, ()))


def build_survivors(cs, facets: np.ndarray, vertices: np.ndarray, first: list, seconds: tuple,
                    template: Pruning) -> tuple[list, list, Pruning]:
    """(inequalities, equalities, record): vertex 0's conditions ``first``, the surviving
    pairs (``facets``, ``vertices``), every ray and line pair; ``template`` gives the
    horizon and the variable, ``seconds`` the stages so far.  If more than
    :data:`WORTHWHILE` of the pairs survive, every pair is built instead (not applied).

    >>> import exactinv as ei
    >>> from exactinv.conditions.polyhedron import ConditionSet
    >>> cs = ConditionSet(ei.LinearSystem([[-1]]), ei.Polyhedron([[1], [-1]], [1, 1]), ei.methods.taylor(1))
    >>> first = cs.pairs(Kind.VERTEX, [(0, 0), (0, 1)])
    >>> build_survivors(cs, np.array([1]), np.array([1]), first, (), Pruning(Fraction(1), 0, 0, 0, ()))[2].survivors
    3
    """
    t1 = time.perf_counter()
    W, m, V = cs.W[Kind.VERTEX], cs.polyhedron.m, cs.count(Kind.VERTEX)
    keep = vertices != 0
    pairs = list(zip(vertices[keep].tolist(), facets[keep].tolist()))
    order = tuple(vertex_order(W))
    if len(pairs) > WORTHWHILE * m * V:  # the all-pairs FLINT products are cheaper
        inequalities, equalities = cs.all()
        stages = seconds + (("all polynomials", time.perf_counter() - t1),)
        return inequalities, equalities, replace(template, pairs=m * V, survivors=m * V, order=order, seconds=stages,
                                                 applied=False)
    inequalities = first + cs.pairs(Kind.VERTEX, pairs)
    inequalities += cs.pairs(Kind.RAY, [(i, j) for i in range(cs.count(Kind.RAY)) for j in range(m)])
    equalities = cs.pairs(Kind.LINE, [(i, j) for i in range(cs.count(Kind.LINE)) for j in range(m)])
    stages = seconds + (("survivor polynomials", time.perf_counter() - t1),)
    return inequalities, equalities, replace(template, pairs=m * V, survivors=len(pairs) + m, order=order,
                                             seconds=stages)
