"""Certified pruning for rational methods: the variable u = h/(s + h) (issue 13).

For r = g/h_r let D(h) = det h_r(hA) and N(h) = D(h) r(hA) (polynomials,
:func:`.conditions.method_matrices`).  The pair (vertex v, facet j) holds at h
iff c(h) = q(h) D(h) >= 0 with q(h) = b_j D(h) - g_j N(h) v.  A valid set of
a rational method is often unbounded ([0, oo) for A-stable methods on
contractive systems), so no finite horizon in h exists.  Substitute

    h = s u/(1 - u),  u = h/(s + h) in [0, 1)  (s > 0 a scale),
    P(u) = (1 - u)^E diag(D, N)(s u/(1 - u)),  E >= deg D, deg N (E >= 1),

a polynomial (n+1) x (n+1) matrix with P(0) = I.  With w = (1, v) and the
lifted facet row g' = (-b_j, g_j), g' P(u) w = -(1 - u)^E q(h): so if
g' P(u) w < 0 for every u in [0, U], then q > 0 on [0, sU/(1 - U)] (on
[0, oo) when U = 1).  If moreover D > 0 there, c = q D > 0: the pair cannot
bind on that range.  This is the polynomial chord test of :mod:`.pruning` in
R^(n+1) with b' = 0 (a cone, so each piece may be rescaled by any positive
number -- the pieces are normalised, since P(u) shrinks by orders of
magnitude along [0, 1]).  Its remainder is Bernstein's: on a piece
[t, t + d], P(t + d l) = sum_k B_k b_k(l) (Bernstein basis of degree E), so

    P(t + d l) w - ((1 - l) B_0 + l B_E) w = sum_k b_k(l) (B_k - L_k) w,
    L_k = (1 - k/E) B_0 + (k/E) B_E,   |...| <= M |w|,  M = max_k |B_k - L_k|,

entrywise (the b_k(l) >= 0 sum to 1): the path lies in the box of its chord
widened by max_i (M|w|)_i.  (The Taylor remainder of the polynomial route
loses a factor e^(2Ed) to cancellation at degree E = 36; Bernstein's does not.)

The horizon: U = 1 when vertex 0's own valid set (or first interval) is
unbounded, else a short dyadic U >= T/(s + T) for its end T.  Pruning needs
D > 0 on the whole range (else q > 0 does not give c > 0), so a method whose
det h_r(hA) has a root there is not pruned.  The scale s is a power of two
near |D(0)/D_top|^(1/deg D), where D's growth turns over: any s > 0 is
sound, a good one keeps P(u) of one size across [0, 1].  The kernel repeats
all of it exactly (:mod:`exactinv_check.routes.pruning_rational`).
"""

from __future__ import annotations

import time
from fractions import Fraction
from math import comb

import flint

from exactinv_check.format import PRUNING_VARIABLE

from ..core.flintq import fmpq_of, fraction_of
from ..core.float_hint import log2_hint
from ..core.intervals import IntervalUnion
from ..core.roots import positive_roots
from .polyhedron import Kind
from .pruning import Pruning, bounding_horizon, build_survivors, coarse_above, pieces_test, vertex_order

_BITS = 28  # piece ends are rounded to multiples of 2^-_BITS (after normalisation to size ~1)
VARIABLE = PRUNING_VARIABLE  # the record's name of the substitution u = h/(s + h) (the format's)

__all__ = ["VARIABLE", "scale_of", "lifted", "rational_nodes", "bernstein_piece", "rational_survivors",
           "rational_horizon", "prune_rational"]


def scale_of(D: flint.fmpq_poly) -> Fraction:
    """A power of two near |D(0)/D_top|^(1/deg D) (1 for a constant D): the h where D's top term
    overtakes its constant one.  Only a hint -- any s > 0 is sound.

    >>> scale_of(flint.fmpq_poly([1, 0, flint.fmpq(1, 64)]))      # 1 + h^2/64: turns over at h = 8
    Fraction(8, 1)
    """
    c = D.coeffs()
    if len(c) < 2 or c[-1] == 0:
        return Fraction(1)
    if c[0] == 0:
        return Fraction(1)
    return Fraction(2) ** round((log2_hint(c[0]) - log2_hint(c[-1])) / (len(c) - 1))  # never overflows


def lifted(D: flint.fmpq_poly, N: list[flint.fmpq_mat], s: Fraction) -> list[flint.fmpq_mat]:
    """The coefficients P_0, ..., P_E (in u) of P(u) = (1 - u)^E diag(D, N)(s u/(1 - u)),
    E = max(deg D, deg N, 1), exactly: P(u) = sum_k s^k u^k (1 - u)^(E-k) diag(D_k, N_k).

    >>> P = lifted(flint.fmpq_poly([1, 1]), [flint.fmpq_mat([[1]])], Fraction(2))   # backward Euler, A = -1
    >>> [p.entries() for p in P]                        # (1 - u) (1 + 2u/(1-u), 1) = (1 + u, 1 - u)
    [[1, 0, 0, 1], [1, 0, 0, -1]]
    """
    n = N[0].nrows()
    E = max(D.degree(), len(N) - 1, 1)
    Dc = D.coeffs()
    out = [flint.fmpq_mat(n + 1, n + 1) for _ in range(E + 1)]
    sq = fmpq_of(s)
    for k in range(E + 1):
        block = flint.fmpq_mat(n + 1, n + 1)
        block[0, 0] = Dc[k] if k < len(Dc) else 0
        if k < len(N):
            for i in range(n):
                for l in range(n):
                    block[i + 1, l + 1] = N[k][i, l]
        block *= sq**k
        for i in range(E - k + 1):
            out[k + i] += block * ((-1) ** i * comb(E - k, i))
    return out


def rational_nodes(U: Fraction, count: int) -> list[Fraction]:
    """The ends of the pieces of [0, U]: U x for x in a/count and 2^-i, 1 - 2^-i (i <= 12).

    >>> rational_nodes(Fraction(1), 2)[:4], len(rational_nodes(Fraction(1), 2))
    ([Fraction(0, 1), Fraction(1, 4096), Fraction(1, 2048), Fraction(1, 1024)], 25)
    """
    xs = {Fraction(a, count) for a in range(count + 1)}
    xs |= {Fraction(1, 2**i) for i in range(1, 13)} | {1 - Fraction(1, 2**i) for i in range(1, 13)}
    return [U * x for x in sorted(xs)]


def _bernstein_matrix(E: int) -> flint.fmpq_mat:
    """Power coefficients on [0, 1] -> Bernstein coefficients: b_k = sum_{i<=k} C(k,i)/C(E,i) a_i."""
    return flint.fmpq_mat(E + 1, E + 1, [flint.fmpq(comb(k, i), comb(E, i)) if i <= k else 0
                                         for k in range(E + 1) for i in range(E + 1)])


def bernstein_piece(C: flint.fmpq_mat, bern: flint.fmpq_mat, t: Fraction, d: Fraction, size: int):
    """(X, Y, M) of the piece [t, t + d] for the matrix polynomial whose coefficients are
    the rows of C (each a flattened size x size matrix): X = P(t), X + Y = P(t + d) and
    M = max_k |B_k - L_k| (module docstring), all divided by the same power of two
    (about max(||X||, ||X + Y||): the test is a cone test, any positive factor is sound);
    X and X + Y then rounded to multiples of 2^-28, and M widened by the rounding (2^-29 each).

    >>> C = flint.fmpq_mat(3, 1, [0, 0, 1])              # P(u) = u^2 on [0, 1]: B = (0, 0, 1), L = (0, 1/2, 1)
    >>> X, Y, M = bernstein_piece(C, _bernstein_matrix(2), Fraction(0), Fraction(1), 1)
    >>> X[0, 0], Y[0, 0], M[0][0] - Fraction(1, 2**29)
    (0, 1, Fraction(1, 2))
    """
    E = C.nrows() - 1
    tq, dq = fmpq_of(t), fmpq_of(d)
    shift = flint.fmpq_mat(E + 1, E + 1, [comb(i, k) * tq ** (i - k) * dq**k if i >= k else 0
                                          for k in range(E + 1) for i in range(E + 1)])
    B = bern * (shift * C)
    ends = flint.fmpq_mat(2, C.ncols(), [B[0, c] for c in range(C.ncols())] + [B[E, c] for c in range(C.ncols())])
    chord = flint.fmpq_mat(E + 1, 2, [x for k in range(E + 1) for x in (flint.fmpq(E - k, E), flint.fmpq(k, E))])
    Dz, den = (B - chord * ends).numer_denom()
    entries = Dz.entries()
    width = C.ncols()
    dev = [max(abs(int(entries[k * width + c])) for k in range(E + 1)) for c in range(width)]
    X = flint.fmpq_mat(size, size, ends.entries()[:width])
    Z = flint.fmpq_mat(size, size, ends.entries()[width:])
    top = max(_norm(X), _norm(Z))
    factor = Fraction(1) if top == 0 else Fraction(2) ** -(top.numerator.bit_length() - top.denominator.bit_length())
    X, Z = _dyadic(X * fmpq_of(factor)), _dyadic(Z * fmpq_of(factor))  # each entry moves by <= 2^-(_BITS+1)
    slack = Fraction(1, 2 ** (_BITS + 1))  # ... so the chord ends move by <= slack * sum |w|: added to M
    M = [[Fraction(dev[i * size + l], int(den)) * factor + slack for l in range(size)] for i in range(size)]
    return X, Z - X, M


def _dyadic(Q: flint.fmpq_mat) -> flint.fmpq_mat:
    """Q rounded entrywise to the nearest multiple of 2^-_BITS (short numbers for the grid products)."""
    Qz, d = Q.numer_denom()
    scale, d = 1 << _BITS, int(d)
    return flint.fmpq_mat(Q.nrows(), Q.ncols(), [flint.fmpq((2 * int(x) * scale + d) // (2 * d), scale)
                                                 for x in Qz.entries()])


def _norm(Q: flint.fmpq_mat) -> Fraction:
    return max(sum(abs(fraction_of(Q[i, l])) for l in range(Q.ncols())) for i in range(Q.nrows()))


def rational_survivors(cs, s: Fraction, U: Fraction, count: int):
    """(facets, vertices) of the pairs the lifted chord test on the pieces of [0, U] in u
    cannot prune (every other pair has q > 0 on [0, sU/(1 - U)]).

    >>> import exactinv as ei
    >>> from exactinv.conditions.polyhedron import ConditionSet
    >>> cs = ConditionSet(ei.LinearSystem([[-1]]), ei.Polyhedron([[1], [-1]], [1, 2]), ei.methods.backward_euler())
    >>> f, v = rational_survivors(cs, Fraction(1), Fraction(1), 4)   # x -> x/(1 + h): never the far facet
    >>> cs.polyhedron.vertices, sorted(zip(v.tolist(), f.tolist()))  # only each vertex on its own facet
    (((Fraction(-2, 1),), (Fraction(1, 1),)), [(0, 1), (1, 0)])
    """
    n = cs.polyhedron.n
    P = lifted(cs.D, cs.N, s)
    size = n + 1
    C = flint.fmpq_mat(len(P), size * size, [x for Pk in P for x in Pk.entries()])
    bern = _bernstein_matrix(len(P) - 1)
    ends = rational_nodes(U, count)
    pieces = [bernstein_piece(C, bern, t, u - t, size) for t, u in zip(ends, ends[1:])]
    G = flint.fmpq_mat(cs.G.nrows(), size, [x for j in range(cs.G.nrows())
                                              for x in [-cs.b[j]] + [cs.G[j, l] for l in range(n)]])
    W = cs.W[Kind.VERTEX]
    lifted_W = flint.fmpq_mat(size, W.ncols(), [1] * W.ncols() + W.entries())
    return pieces_test(G, [0] * G.nrows(), lifted_W, pieces, vertex_order(W))


def rational_horizon(cs, first_end: bool) -> tuple[Fraction, Fraction, list, list, IntervalUnion | None] | None:
    """(s, U, vertex 0's conditions, stage times, vertex 0's valid set as from
    :func:`~.pruning.bounding_horizon`), or None when D = det h_r(hA) has a root
    in (0, sU/(1 - U)] (then c = qD can change sign without q: nothing is pruned).

    >>> import exactinv as ei
    >>> from exactinv.conditions.polyhedron import ConditionSet
    >>> cs = ConditionSet(ei.LinearSystem([[-1]]), ei.Polyhedron([[1], [-1]], [1, 1]), ei.methods.backward_euler())
    >>> rational_horizon(cs, False)[:2]                 # D = 1 + h; the valid set is [0, oo): U = 1
    (Fraction(1, 1), Fraction(1, 1))
    """
    T, first, seconds, vertex_zero = bounding_horizon(cs, first_end)
    s = scale_of(cs.D)
    U = Fraction(1) if T is None else min(Fraction(1), coarse_above(T / (s + T), 20))
    roots = positive_roots(cs.D)
    if roots and (U == 1 or not roots[0][0] > s * U / (1 - U)):
        return None
    return s, U, first, seconds, vertex_zero


def prune_rational(cs, first_end: bool):
    """(inequalities, equalities, record, vertex 0's valid set or None) of a rational method
    pruned in u = h/(s + h), or None when D vanishes in the range (then every pair is built by the caller).

    >>> import exactinv as ei
    >>> from exactinv.conditions.polyhedron import ConditionSet
    >>> cs = ConditionSet(ei.LinearSystem([[-1]]), ei.Polyhedron([[1], [-1]], [1, 2]), ei.methods.backward_euler())
    >>> inequalities, equalities, record, _ = prune_rational(cs, False)
    >>> record.record()["variable"], record.survivors, inequalities   # 2 of 4 pairs built, none binds
    ('h/(s+h)', 3, [])
    """
    found = rational_horizon(cs, first_end)
    if found is None:
        return None
    s, U, first, seconds, vertex_zero = found
    t0 = time.perf_counter()
    count = _piece_count(cs)
    facets, vertices = rational_survivors(cs, s, U, count)
    seconds = tuple(seconds) + (("bounds and slacks", time.perf_counter() - t0),)
    template = Pruning(U, 0, 0, 0, (), variable={"variable": VARIABLE, "scale": str(s), "pieces": count})
    return (*build_survivors(cs, facets, vertices, first, seconds, template), vertex_zero)


def _piece_count(cs) -> int:
    """Uniform pieces on [0, U]: about 4E/3 for P(u) of degree E (a Bernstein deviation of a
    degree-E piece of length d is about (Ed)^2/8 of its size; on the R^6 family, Pade(6,6),
    E = 36: 24 pieces leave 71% of the pairs, 36 pieces 9%, 48 pieces 6.2%, 72 pieces 6.0%)."""
    E = max(cs.D.degree(), len(cs.N) - 1, 1)
    return max(8, E + E // 3)
