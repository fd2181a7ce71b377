"""Dual pieces of the LP route: the paper's certificate (Theorem 2.2) carried along h (docs/design.md, "Dual pieces").

Where facet i is far from binding, the optimal basis of max g_i A_d(h) x over P
changes often while phi_i(h) stays well below b_i.  A *dual piece* [a, e] (a
rational) skips those changes: vectors y_0, ..., y_K >= 0 indexed by the rows
of G with

    y(h) = sum_k (h - a)^k y_k,   G^T y(h) = D(h) N(h)^T g_i   (as polynomials),

so y(h) >= 0 for every h >= a, and

    q(h) = D(h)^2 b_i - y(h)^T b >= 0 on [a, e].

For x in P and D(h) != 0, D g_i N x = y^T G x <= y^T b <= D^2 b_i, so
g_i A_d(h) x <= b_i: facet i is valid on the whole piece, and the piece adds no
condition.  The identity holds coefficient by coefficient: G^T y_k = d_k, the
k-th Taylor coefficient at a of D N^T g_i.  y_0 is the optimal basis's dual at a
(z_B(a) >= 0, exact); y_k for k >= 1 is B^-T d_k when that is >= 0, else the
verified optimal dual of max d_k^T x over P from the exact LP chain
(:class:`~exactinv.lp.solver.ExactLPSolver`: a float HiGHS hint rebuilt and
verified in Q), so b^T y_k is as small as it can be.  The piece ends at a
rational e at or below the first root of q beyond a (certified root isolation),
or at the caller's cap.  Anything that fails returns None: the walk then goes on
with basis pieces.  Every piece is re-proved by the kernel
(:mod:`exactinv_check.routes.lp_duals`).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from fractions import Fraction
from math import comb
from typing import Protocol

import flint

from ..core.algebraic import Real, RealAlgebraic, exact_lt
from ..core.flintq import exact_text, fmpq_of, fraction_of
from ..core.real_signs import narrowed
from ..core.roots import real_roots
from ..core.scalars import INF
from ..lp.solver import OPTIMAL, LPResult

__all__ = ["DualCertificate", "dual_target", "dual_piece", "simplest_between"]

_ZERO = flint.fmpq(0)


@dataclass(frozen=True)
class DualCertificate:
    """The vectors y_0, ..., y_K of a dual piece starting at ``start`` (each a tuple of (row, value > 0),
    rows increasing) and the piece's ``end`` (a rational, or INF)."""

    start: Fraction
    end: Real
    ys: tuple[tuple[tuple[int, Fraction], ...], ...]

    def record(self) -> dict:
        """The certificate's entry for the piece: ``{"dual": [y_0, ..., y_K]}``, each y_k as [row, value] pairs.

        >>> DualCertificate(Fraction(1), INF, (((0, Fraction(1, 2)),), ())).record()
        {'dual': [[[0, '1/2']], []]}
        """
        return {"dual": [[[r, exact_text(v)] for r, v in y] for y in self.ys]}


def dual_target(C: flint.fmpq_mat, D: flint.fmpq_poly) -> flint.fmpq_mat:
    """D(h) N(h)^T g_i as an n x W matrix of coefficients (row l: component l from h^0 up), from
    C_i (column k: (g_i N_k)^T) and D.

    >>> dual_target(flint.fmpq_mat([[1, 2]]), flint.fmpq_poly([1, 1]))
    [1, 3, 2]
    """
    Dm = D.coeffs() or [_ZERO]
    L = C.ncols()
    W = L + len(Dm) - 1
    S = flint.fmpq_mat(L, W, [Dm[j - k] if 0 <= j - k < len(Dm) else 0 for k in range(L) for j in range(W)])
    return C * S


def simplest_between(lo: Fraction, hi: Fraction) -> Fraction:
    """The rational with the least denominator in the closed [lo, hi] (0 <= lo <= hi), by continued
    fractions: short ends keep the Taylor coefficients at a piece's start (and the certificate) small.

    >>> simplest_between(Fraction(31, 100), Fraction(1, 3)), simplest_between(Fraction(7, 5), Fraction(7, 5))
    (Fraction(1, 3), Fraction(7, 5))
    >>> simplest_between(Fraction(2, 7), Fraction(3, 10))
    Fraction(2, 7)
    """
    floor = lo.numerator // lo.denominator
    if floor == lo:
        return Fraction(floor)
    if floor + 1 <= hi:
        return Fraction(floor + 1)
    return floor + 1 / simplest_between(1 / (hi - floor), 1 / (lo - floor))


def _taylor(T: flint.fmpq_mat, a: Fraction) -> flint.fmpq_mat:
    """The Taylor coefficients at a of every row of T: column k = sum_j C(j, k) a^(j-k) T[:, j]."""
    W = T.ncols()
    x = fmpq_of(a)
    S = flint.fmpq_mat(W, W, [comb(j, k) * x ** (j - k) if j >= k else 0 for j in range(W) for k in range(W)])
    return T * S


def _rational_in(a: Fraction, root: Real) -> Fraction | None:
    """A rational in (a, root] for a real root > a: the root itself when rational, else the lower end of its
    isolating interval, refined until it passes a (None if that takes more than 200 bits).  Found by hypothesis:
    a piece starting 1.1e-16 below the root 3 - sqrt 5 of q, whose 2^-44 enclosure reached below a; the piece was
    then taken to end at the cap, past the root, and the kernel rejected q < 0 inside it.

    >>> alpha = RealAlgebraic.from_isolating_interval([4, -6, 1], 0, 1)     # 3 - sqrt 5 = 0.7639320225002103...
    >>> _rational_in(Fraction(215027748241771, 2**48), alpha) > Fraction(215027748241771, 2**48)
    True
    >>> _rational_in(Fraction(1, 2), Fraction(3, 4))
    Fraction(3, 4)
    """
    if not isinstance(root, RealAlgebraic):
        return Fraction(root)  # type: ignore[arg-type]
    alpha = narrowed(root)
    for bits in range(48, 201, 8):
        if alpha.lower > a:  # type: ignore[union-attr]
            return alpha.lower  # type: ignore[union-attr]
        alpha = alpha.refine(bits)  # type: ignore[union-attr]
    return None


def _sparse(y: list[flint.fmpq], rows: tuple[int, ...] | None = None) -> tuple[tuple[int, flint.fmpq], ...]:
    """(row, value) for the nonzero entries of y (indexed by ``rows`` when given, else by position)."""
    index = rows if rows is not None else range(len(y))
    return tuple(sorted((r, v) for r, v in zip(index, y) if v != 0))


class ExactSolve(Protocol):
    """The exact LP chain's solve (:meth:`exactinv.lp.solver.ExactLPSolver.solve`), or a guard around it that
    may decline (None)."""

    def solve(self, c: flint.fmpq_mat, b: flint.fmpq_mat, nonnegative: Sequence[bool]) -> LPResult | None:
        """max c^T x subject to G x <= b, exactly (verified optimum, primal and dual), or None (declined).

        The exact LP chain is one: max 3x on -1 <= x <= 1 is 3, at x = 1.

        >>> from exactinv.lp.solver import ExactLPSolver
        >>> G = flint.fmpq_mat(2, 1, [1, -1])
        >>> result = ExactLPSolver(G, (False, False)).solve(flint.fmpq_mat(1, 1, [3]), flint.fmpq_mat(2, 1, [1, 1]), (False,))
        >>> result.status.value, result.value
        ('optimal', Fraction(3, 1))
        """
        ...


Suggest = Callable[[int, flint.fmpq_mat], Iterable[tuple[tuple[int, ...], list[flint.fmpq]]]]


def dual_piece(G: flint.fmpq_mat, b: flint.fmpq_mat, b_i: Fraction, D: flint.fmpq_poly, target: flint.fmpq_mat,
               rows: tuple[int, ...], inv_t: flint.fmpq_mat, solver: ExactSolve, a: Fraction,
               cap: Fraction | None, suggest: Suggest | None = None,
               used: Callable[[int, tuple[int, ...]], None] | None = None) -> DualCertificate | None:
    """The dual piece of a facet from the rational a, with y_0 the dual of the basis ``rows`` (B^-T = ``inv_t``,
    optimal at a), or None when one is not found or q(a) <= 0 (the facet binds at a): module docstring.
    For k >= 1, ``suggest(k, d_k)`` may propose bases first, as (rows, B^-T d_k exactly) -- one that served
    before, a float LP's basis: each is taken only when B^-T d_k >= 0, and ``used(k, rows)`` is told
    which one served -- before the exact LP chain.  Exact throughout; floats are hints verified in Q.

    Forward Euler on x' = -x, P = [-1, 1], facet x <= 1 from a = 1/2: c(h) = 1 - h = c(a) - (h - a), so
    y_0 = 1/2 on the facet's row (its dual at a) and y_1 = 1 on the row -x <= 1 (G^T y_1 = -1), and
    q(h) = 1 - y(h)^T b = 1 - (1/2 + (h - 1/2)) = 1 - h >= 0 up to the end h = 1:

    >>> from exactinv.lp.solver import ExactLPSolver
    >>> G, b = flint.fmpq_mat(2, 1, [1, -1]), flint.fmpq_mat(2, 1, [1, 1])
    >>> dual_piece(G, b, Fraction(1), flint.fmpq_poly([1]), flint.fmpq_mat(1, 2, [1, -1]), (0,),
    ...            flint.fmpq_mat(1, 1, [1]), ExactLPSolver(G, (False, False)), Fraction(1, 2), None)
    DualCertificate(start=Fraction(1, 2), end=Fraction(1, 1), ys=(((0, Fraction(1, 2)),), ((1, Fraction(1, 1)),)))
    """
    n, m = G.ncols(), G.nrows()
    Tk = _taylor(target, a)
    W = Tk.ncols()
    ys: list[tuple[tuple[int, flint.fmpq], ...]] = []  # as Fractions only in a piece that is found
    betas: list[flint.fmpq] = []
    GT = G.transpose()
    for k in range(W):
        d = flint.fmpq_mat(n, 1, [Tk[l, k] for l in range(n)])
        if all(v == 0 for v in d.entries()):
            ys.append(())
            betas.append(_ZERO)
            continue
        yB = (inv_t * d).entries()
        y = None
        if all(v >= 0 for v in yB):
            y = _sparse(yB, rows)
        elif k == 0:
            return None  # the basis is not optimal at a
        elif suggest is not None:
            for other, yO in suggest(k, d):  # y_B = B^-T d_k for a basis B, exact
                if all(v >= 0 for v in yO):
                    y = _sparse(yO, other)
                    if used is not None:
                        used(k, other)
                    break
        if y is None:
            res = solver.solve(d, b, (False,) * n)  # the exact LP chain: a verified optimal dual
            if res is None or res.status != OPTIMAL or res.y_q is None:
                return None  # unbounded in the direction d_k: no y_k >= 0 (Farkas)
            full = res.y_q.entries()
            if len(full) != m or any(v < 0 for v in full) or GT * res.y_q != d:
                return None
            y = _sparse(full)
        ys.append(y)
        betas.append(sum((v * b[r, 0] for r, v in y), _ZERO))
    while len(ys) > 1 and not ys[-1]:
        ys.pop()
    shifted = flint.fmpq_poly([0])
    step = flint.fmpq_poly([-fmpq_of(a), 1])
    for beta in reversed(betas):
        shifted = shifted * step + beta
    q = D * D * fmpq_of(b_i) - shifted
    x = fmpq_of(a)
    if not q(x) > 0:
        return None
    end: Fraction | None = None  # None: q > 0 on all of [a, oo)
    for root, _ in real_roots(q):
        if exact_lt(a, root):
            top = _rational_in(a, root)
            if top is None:
                return None  # the root is within 2^-200 of a: no piece worth having
            end = simplest_between(top - (top - a) / 64, top)  # short, at most the root, within 1/64 of the piece
            break
    if cap is not None and (end is None or cap < end):
        end = cap
    if end is not None and not end > a:
        return None
    return DualCertificate(a, INF if end is None else end,
                           tuple(tuple((r, fraction_of(v)) for r, v in y) for y in ys))
