"""The extreme rays of a polyhedral cone {d : A d <= 0}, in integers.

Fraction-free elimination (with an optional augmented part, Gauss-Jordan),
the edge directions of a simplicial cone from one solve, and the
double-description method with the algebraic adjacency test for a degenerate
vertex (more active rows than the rank), bounded by MAX_CONE_PAIRS adjacency
tests and MAX_CONE_RAYS rays held at once.  Vectors are Python integers: a
rational vector is scaled once to (integers, denominator), a direction is kept
primitive (divided by the gcd of its entries, a positive factor).
"""

from __future__ import annotations

from fractions import Fraction
from math import gcd, lcm
from typing import Any, Sequence

from .budget import MAX_CONE_PAIRS, MAX_CONE_RAYS, PYTHON_OP, charge, words
from .failure import CheckFailure, require


def scaled_integers(v: Sequence[Fraction]) -> tuple[list[int], int]:
    """(integer vector p, denominator q > 0) with v = p / q."""
    q = lcm(*(x.denominator for x in v)) if v else 1
    return [x.numerator * (q // x.denominator) for x in v], q


def primitive(v: Any) -> Any:
    """v divided by the gcd of its entries (a positive factor); None if v = 0."""
    g = gcd(*v)
    if g == 0:
        return None
    return [x // g for x in v] if g != 1 else list(v)


# ----------------------------------------------------------------------------
# integer linear algebra


def reduce_rows(rows: Sequence[list[int]], ncols: int, aug: Sequence[list[int]] | None = None) -> tuple[int,
                list[int], list[int], list[list[Any]], list[list[Any]] | None]:
    """Fraction-free elimination of integer rows.

    Returns (rank, pivot columns, original indices of the pivot rows, reduced
    pivot rows, their augmented parts).  The pivot rows are a maximal
    independent subset of ``rows``.  With ``aug`` (one augmented row per row)
    it is Gauss-Jordan and every row operation is applied to the augmented
    part too, so reduced = T * rows and augmented = T * aug for one invertible T.
    """
    work = [list(r) for r in rows]
    ext = [list(a) for a in aug] if aug is not None else None
    order = list(range(len(work)))
    rank, cols = 0, []
    for c in range(ncols):
        if rank == len(work):
            break
        pr = next((i for i in range(rank, len(work)) if work[i][c]), None)
        if pr is None:
            continue
        work[rank], work[pr] = work[pr], work[rank]
        order[rank], order[pr] = order[pr], order[rank]
        if ext is not None:
            ext[rank], ext[pr] = ext[pr], ext[rank]
        prow, pv = work[rank], work[rank][c]
        targets = range(len(work)) if ext is not None else range(rank + 1, len(work))
        width = len(prow) + (len(ext[rank]) if ext is not None else 0)
        for i in targets:
            f = work[i][c]
            if i == rank or not f:
                continue
            # each row operation charged by its numbers' sizes, as it runs (the entries are minors of about the
            # pivot's size): a 400 x 200 G ran minutes uncharged here (tests/kernel/test_claims_control.py)
            w = words(2 * max(abs(pv).bit_length(), abs(f).bit_length()))
            charge(width * (PYTHON_OP + 2 * w * w), "a fraction-free elimination step (a rank)")
            row = [pv * x - f * y for x, y in zip(work[i], prow)]
            if ext is not None:
                e = [pv * x - f * y for x, y in zip(ext[i], ext[rank])]
                g = gcd(*row, *e)
                if g > 1:
                    row = [x // g for x in row]
                    e = [x // g for x in e]
                ext[i] = e
            else:
                g = gcd(*row)
                if g > 1:
                    row = [x // g for x in row]
            work[i] = row
        cols.append(c)
        rank += 1
    return rank, cols, order[:rank], work[:rank], (ext[:rank] if ext is not None else None)


def integer_rank(rows: Sequence[list[int]], ncols: int) -> Any:
    """The rank of integer rows of length ``ncols`` (fraction-free elimination, charged as it runs)."""
    return reduce_rows(rows, ncols)[0] if rows else 0


def basis_rays(B: Any, ncols: Any) -> Any:
    """Edge directions of a simplicial cone.

    For integer rows B (k of them, length ncols): None if they are dependent;
    otherwise (cols, ys) with k independent columns ``cols`` and, for each row
    b, an integer y_b in Q^k such that the vector d_b with d_b[cols] = y_b and
    zeros elsewhere has B d_b = -c_b e_b, c_b > 0.  So d_b is tight on every
    row of B but b, and the d_b are the extreme rays of {d : B d <= 0}
    modulo its lineality space {d : B d = 0}.
    """
    k = len(B)
    identity = [[int(i == j) for j in range(k)] for i in range(k)]
    rank, cols, _, R, T = reduce_rows(B, ncols, identity)
    if rank != k:
        return None
    # Gauss-Jordan: R = T B with R[i][cols[i']] = 0 for i != i'; so with
    # c_i = R[i][cols[i]] and y_b[i] = -T[i][b] M / c_i (M = lcm |c_i| > 0),
    # R d_b = -M T e_b, hence B d_b = T^{-1} R d_b = -M e_b.
    c = [R[i][cols[i]] for i in range(k)]
    M = lcm(*(abs(x) for x in c))
    ys = [primitive([-T[i][b] * (M // c[i]) for i in range(k)]) for b in range(k)]  # type: ignore[index]
    return cols, ys


def cone_rays(A: Any, basis: Any, r: Any) -> list[list[int]]:
    """The extreme rays of the pointed cone {y in Q^r : A y <= 0} (A integer,
    rank r, ``basis`` the indices of r independent rows), by the
    double-description method with the algebraic adjacency test."""
    if r == 0:
        return []
    S = [A[i] for i in basis]
    full = 0
    for i in basis:
        full |= 1 << i
    _, initial = basis_rays(S, r)  # S is square and nonsingular: its columns are 0..r-1
    rays = [(y, full & ~(1 << basis[k])) for k, y in enumerate(initial)]
    in_basis = set(basis)
    pairs = 0
    for j, a in enumerate(A):
        if j in in_basis:
            continue
        bit = 1 << j
        pos, neg, kept = [], [], []
        for y, Z in rays:
            v = sum(x * z for x, z in zip(a, y))
            if v > 0:
                pos.append((v, y, Z))
            elif v < 0:
                neg.append((v, y, Z))
                kept.append((y, Z))
            else:
                kept.append((y, Z | bit))
        charge(len(pos) * len(neg) * PYTHON_OP * (4 + r * r), "the adjacency tests at a degenerate vertex")
        for vp, p, Zp in pos:
            for vq, q, Zq in neg:
                pairs += 1
                Z = Zp & Zq
                if Z.bit_count() < r - 2:
                    continue
                tight = []
                while Z:
                    low = Z & -Z
                    tight.append(A[low.bit_length() - 1])
                    Z ^= low
                if integer_rank(tight, r) != r - 2:
                    continue
                # vp > 0 > vq: a positive combination with a.y = 0
                y = primitive([vp * qi - vq * pi for pi, qi in zip(p, q)])
                if y is not None:
                    kept.append((y, (Zp & Zq) | bit))
            if pairs > MAX_CONE_PAIRS:
                raise CheckFailure(
                    f"a degenerate vertex needs more than {MAX_CONE_PAIRS} adjacency tests to enumerate its edges"
                )
        require(
            len(kept) <= MAX_CONE_RAYS,
            f"a degenerate vertex has more than {MAX_CONE_RAYS} intermediate edge directions",
        )
        rays = kept
    return [y for y, _ in rays]
