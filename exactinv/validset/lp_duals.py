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

import math
from collections.abc import Callable, Iterable, Sequence
from fractions import Fraction
from math import comb
from typing import Protocol

import flint
import numpy as np

from ..core.algebraic import Real, RealAlgebraic, exact_lt
from ..core.flintq import exact_text, fmpq_of, fraction_of
from ..core.float_hint import float_hint, float_hints
from ..core.polys import no_root_between
from ..core.real_signs import narrowed
from ..core.roots import real_roots
from ..core.scalars import INF, Infinity
from ..lp.solver import OPTIMAL, LPResult

__all__ = ["DualCertificate", "dual_target", "dual_piece", "piece_end", "simplest_between"]

_ZERO = flint.fmpq(0)
_ZERO_Q = Fraction(0)


Entries = tuple[tuple[tuple[int, Fraction | flint.fmpq], ...], ...]


class DualCertificate:
    """The vectors y_0, ..., y_K of a dual piece starting at ``start`` (each a tuple of (row, value > 0),
    rows increasing) and the piece's ``end`` (a rational, or INF).  Immutable.  The engine hands the values
    over as FLINT rationals; ``ys`` gives them as Fractions, converted once, when first asked (the record
    writes them from either).

    >>> c = DualCertificate(Fraction(1), INF, (((0, flint.fmpq(1, 2)),), ()))
    >>> c.ys, c == DualCertificate(Fraction(1), INF, (((0, Fraction(1, 2)),), ()))
    ((((0, Fraction(1, 2)),), ()), True)
    """

    __slots__ = ("start", "end", "_entries", "_ys")

    start: Fraction
    end: Real
    _entries: Entries
    _ys: tuple[tuple[tuple[int, Fraction], ...], ...] | None

    def __init__(self, start: Fraction, end: Real, ys: Entries):
        object.__setattr__(self, "start", start)
        object.__setattr__(self, "end", end)
        object.__setattr__(self, "_entries", tuple(tuple(y) for y in ys))
        object.__setattr__(self, "_ys", None)

    def __setattr__(self, name: str, value: object) -> None:
        raise AttributeError(f"DualCertificate is immutable: cannot set {name}")

    @property
    def entries(self) -> Entries:
        """y_0, ..., y_K as given (FLINT rationals from the engine)."""
        return self._entries

    @property
    def ys(self) -> tuple[tuple[tuple[int, Fraction], ...], ...]:
        """y_0, ..., y_K as (row, Fraction) pairs."""
        ys = self._ys
        if ys is None:
            ys = tuple(tuple((r, v if isinstance(v, Fraction) else fraction_of(v)) for r, v in y) for y in self._entries)
            object.__setattr__(self, "_ys", ys)
        return ys

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, DualCertificate):
            return NotImplemented
        return (self.start, self.end, self.ys) == (other.start, other.end, other.ys)

    def __hash__(self) -> int:
        return hash((self.start, self.end, self.ys))

    def __reduce__(self) -> tuple:
        """Pickled (and copied) by value, with Fractions: a result crosses process boundaries in a batch."""
        return (DualCertificate, (self.start, self.end, self.ys))

    def __repr__(self) -> str:
        return f"DualCertificate(start={self.start!r}, end={self.end!r}, ys={self.ys!r})"

    def record(self) -> dict:
        """The certificate's entry for the piece: ``{"dual": [y_0, ..., y_K]}``, each y_k as [row, value] pairs.

        >>> DualCertificate(Fraction(1), INF, (((0, Fraction(1, 2)),), ())).record()
        {'dual': [[[0, '1/2']], []]}
        """
        return {"dual": [[[r, exact_text(v)] for r, v in y] for y in self._entries]}

    def taylor_at(self, a: Fraction, first: int = 0) -> list[list[tuple[int, flint.fmpq]]]:
        """The same y(h) = sum_k (h - start)^k y_k written at a >= start: z_k = sum_{j >= k} C(j, k)
        (a - start)^(j - k) y_j, so y(h) = sum_k (h - a)^k z_k.  Every weight is >= 0, so z_k >= 0 and
        G^T z_k is the k-th Taylor coefficient at a of the same D N^T g_i: exact y_k for a piece from a.
        ``first``: z_first, z_(first+1), ... only.

        >>> DualCertificate(Fraction(0), INF, (((0, Fraction(1)),), ((1, Fraction(2)),))).taylor_at(Fraction(1, 2))
        [[(0, 1), (1, 1)], [(1, 2)]]
        """
        if a < self.start:
            raise ValueError("taylor_at: a below the piece's start")  # an internal misuse, never the user's
        K = len(self._entries)
        rows = sorted({r for y in self._entries for r, _ in y})
        column = {r: c for c, r in enumerate(rows)}
        Y = flint.fmpq_mat(K, len(rows))
        for j, y in enumerate(self._entries):
            for r, v in y:
                Y[j, column[r]] = v if isinstance(v, flint.fmpq) else fmpq_of(v)
        t = fmpq_of(a - self.start)
        S = flint.fmpq_mat(K - first, K, [comb(j, k) * t ** (j - k) if j >= k else 0
                                          for k in range(first, K) for j in range(K)])
        Z = (S * Y).tolist() if K > first else []
        return [[(r, v) for r, v in zip(rows, z) if v != _ZERO] for z in Z]


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
    return tuple(sorted((r, v) for r, v in zip(index, y) if v != _ZERO))


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


Y0 = tuple[tuple[int, ...], Sequence[flint.fmpq]]
"""y_0 as (rows, values): the exact dual B^-T d_0 of a basis B (its rows) at the piece's start."""


def dual_piece(G: flint.fmpq_mat, b: flint.fmpq_mat, b_i: Fraction, D: flint.fmpq_poly, target: flint.fmpq_mat,
               y0: Y0, solver: ExactSolve, a: Fraction, cap: Fraction | None, suggest: Suggest | None = None,
               used: Callable[[int, tuple[int, ...]], None] | None = None,
               carry: DualCertificate | None = None) -> DualCertificate | None:
    """The dual piece of a facet from the rational a, with y_0 given as (rows, B^-T d_0) -- the dual of the basis
    optimal at a after a basis piece, or of the float LP's basis at a after a dual piece: any exact y_0 >= 0
    with G^T y_0 = d_0 serves --, or None when one is not found or q(a) <= 0 (the facet binds at a): module
    docstring.  For k >= 1, ``suggest(k, d_k)`` may propose bases first, as (rows, B^-T d_k exactly) -- one that
    served before, a float LP's basis: each is taken only when B^-T d_k >= 0, and ``used(k, rows)`` is told
    which one served -- before the exact LP chain.  ``carry``: the facet's dual piece that ends at a; its
    y(h), written at a (:meth:`DualCertificate.taylor_at`, no LP), gives y_k, y_(k+1), ... whenever that
    already proves q >= 0 up to ``cap``.  Exact throughout; floats are hints verified in Q.

    Forward Euler on x' = -x, P = [-1, 1], facet x <= 1 from a = 1/2: c(h) = 1 - h = c(a) - (h - a), so
    y_0 = 1/2 on the facet's row (its dual at a) and y_1 = 1 on the row -x <= 1 (G^T y_1 = -1), and
    q(h) = 1 - y(h)^T b = 1 - (1/2 + (h - 1/2)) = 1 - h >= 0 up to the end h = 1:

    >>> from exactinv.lp.solver import ExactLPSolver
    >>> G, b = flint.fmpq_mat(2, 1, [1, -1]), flint.fmpq_mat(2, 1, [1, 1])
    >>> dual_piece(G, b, Fraction(1), flint.fmpq_poly([1]), flint.fmpq_mat(1, 2, [1, -1]),
    ...            ((0,), [flint.fmpq(1, 2)]), ExactLPSolver(G, (False, False)), Fraction(1, 2), None)
    DualCertificate(start=Fraction(1, 2), end=Fraction(1, 1), ys=(((0, Fraction(1, 2)),), ((1, Fraction(1, 1)),)))
    """
    n, m = G.ncols(), G.nrows()
    Tk = _taylor(target, a)
    W = Tk.ncols()
    rows0, values0 = y0
    if len(rows0) != len(values0) or not all(v >= _ZERO for v in values0):
        return None  # the basis is not optimal at a
    x = fmpq_of(a)
    Dx = D(flint.fmpq_poly([x, 1]))  # D(a + s)
    top = Dx * Dx * fmpq_of(b_i)  # q(a + s) = top(s) - sum_k beta_k s^k, in powers of s = h - a
    b_list = b.entries()
    ys: list[tuple[tuple[int, flint.fmpq], ...]] = [_sparse(list(values0), rows0)]
    betas: list[flint.fmpq] = [_beta(b_list, ys[0])]
    carried = _carried_betas(carry, a, b_list) if carry is not None and cap is not None else None
    if carried is not None and len(carried) > W:
        carried = None
    end: Real | None = None
    for k in range(1, W):
        if carried is not None and cap is not None:  # y_k, y_(k+1), ... carried over: enough to reach the cap?
            end = _reaches(top, betas + carried[k:], a, cap)
            if end is not None:
                assert carry is not None
                ys.extend(tuple(y) for y in carry.taylor_at(a, k))
                betas.extend(carried[k:])
                break
        d = flint.fmpq_mat(n, 1, [Tk[l, k] for l in range(n)])
        if all(v == _ZERO for v in d.entries()):
            ys.append(())
            betas.append(_ZERO)
            continue
        y = None
        if suggest is not None:
            for other, yO in suggest(k, d):  # y_B = B^-T d_k for a basis B, exact
                if all(v >= _ZERO for v in yO):
                    y = _sparse(yO, other)
                    if used is not None:
                        used(k, other)
                    break
        if y is None:
            res = solver.solve(d, b, (False,) * n)  # the exact LP chain: a verified optimal dual
            if res is None or res.status != OPTIMAL or res.y_q is None:
                return None  # unbounded in the direction d_k: no y_k >= 0 (Farkas)
            full = res.y_q.entries()
            if len(full) != m or any(v < 0 for v in full) or G.transpose() * res.y_q != d:
                return None
            y = _sparse(full)
        ys.append(y)
        betas.append(_beta(b_list, y))
    while len(ys) > 1 and not ys[-1]:
        ys.pop()
    q = top - flint.fmpq_poly(betas)
    if not q(_ZERO) > 0:
        return None
    if end is None:
        end = piece_end(q, a, cap)
    if end is None or (not isinstance(end, Infinity) and not end > a):
        return None
    return DualCertificate(a, end, tuple(ys))


def _flint_entries(y: tuple[tuple[int, Fraction | flint.fmpq], ...]) -> list[tuple[int, flint.fmpq]]:
    """(row, value) with every value an fmpq (the engine's already are)."""
    return [(r, v if isinstance(v, flint.fmpq) else fmpq_of(v)) for r, v in y]


def _carried_betas(carry: DualCertificate, a: Fraction, b: list[flint.fmpq]) -> list[flint.fmpq] | None:
    """b^T z_k for the previous piece's y(h) written at a (z_k of :meth:`DualCertificate.taylor_at`), from its
    own b^T y_j by the same binomial weights (no vector is formed): sum_j C(j, k) (a - start)^(j - k) b^T y_j."""
    if a < carry.start:
        return None
    old = [_beta(b, _flint_entries(y)) for y in carry.entries]
    t = fmpq_of(a - carry.start)
    return [sum((comb(j, k) * t ** (j - k) * old[j] for j in range(k, len(old))), _ZERO) for k in range(len(old))]


def _beta(b: list[flint.fmpq], y: Iterable[tuple[int, flint.fmpq]]) -> flint.fmpq:
    """b^T y for a sparse y."""
    return sum((v * b[r] for r, v in y), _ZERO)


def _reaches(top: flint.fmpq_poly, betas: list[flint.fmpq], a: Fraction, cap: Fraction) -> Fraction | None:
    """``cap`` when q(a + s) = top(s) - sum_k betas[k] s^k is > 0 at s = 0 and proved >= 0 on [0, cap - a]
    (:func:`_proved`); else None."""
    q = top - flint.fmpq_poly(betas)
    span = cap - a
    if not (span > 0 and q(_ZERO) > 0):
        return None
    return _proved(q, a, span)


def piece_end(q: flint.fmpq_poly, a: Fraction, cap: Fraction | None) -> Real | None:
    """The end e of a dual piece from a whose q(a + s) (in powers of s = h - a) is positive at s = 0: INF when
    q > 0 on all of [a, oo) and there is no cap, else a rational e <= cap with q > 0 on [a, e], short (the
    simplest rational within 1/64 of the piece below q's first root beyond a), or None when that root is
    within 2^-200 of a.  A float guess of the root first, proved by Descartes' rule on (a, e) and the signs
    at the ends; if floats fail or the proof does not go through, the certified isolation of q's roots.

    q(a + s) = 1 - s from a = 1/2: the root 3/2 ends the piece; with the cap 1, the cap does; 1 + s never ends:

    >>> q = flint.fmpq_poly([1, -1])
    >>> piece_end(q, Fraction(1, 2), None), piece_end(q, Fraction(1, 2), Fraction(1))
    (Fraction(3, 2), Fraction(1, 1))
    >>> piece_end(flint.fmpq_poly([1, 1]), Fraction(0), None)
    INF
    """
    guess = _float_end(q, a, cap)
    if guess is not None:
        return guess
    end: Fraction | None = None  # None: q > 0 on all of [a, oo)
    for root, _ in real_roots(q):
        if exact_lt(_ZERO_Q, root):
            top = _rational_in(_ZERO_Q, root)
            if top is None:
                return None  # the root is within 2^-200 of a: no piece worth having
            end = _short_end(a, top)
            break
    if cap is not None and (end is None or cap < end):
        end = cap
    return INF if end is None else end


def _short_end(a: Fraction, span: Fraction) -> Fraction:
    """The simplest rational in [a + 63/64 span, a + span] (span > 0): short ends keep the Taylor coefficients at
    the next piece's start (and the certificate) small."""
    return simplest_between(a + span - span / 64, a + span)


def _short_float(lo: float, hi: float) -> Fraction | None:
    """A short rational p/q in [lo, hi] (floats, 0 <= lo < hi), the least q <= 4096 that has one, found in floats
    (the caller proves whatever it needs of it exactly); None when floats fail or no q <= 4096 does.

    >>> _short_float(0.31, 1 / 3), _short_float(2.3, 2.31)
    (Fraction(1, 3), Fraction(23, 10))
    """
    if not (math.isfinite(lo) and math.isfinite(hi) and 0 <= lo < hi < 2.0**52):
        return None
    for q in range(1, 4097):
        p = math.ceil(lo * q)
        if p <= hi * q:
            return Fraction(p, q)
    return None


def _float_end(q: flint.fmpq_poly, a: Fraction, cap: Fraction | None) -> Real | None:
    """:func:`piece_end` from a float guess of q's first root beyond 0, proved exactly; None when floats say
    nothing useful or the proof fails (never raises, never wrong: every end it returns is proved)."""
    coeffs = q.coeffs()
    real = _decreasing_root(q) if _decreasing(q) else _float_roots(q)
    if real is None:
        return None
    if not real:  # no root beyond a in floats: q > 0 on [a, oo) -- by Descartes on (0, oo), all coefficients >= 0
        if cap is None:
            return INF if all(v >= 0 for v in coeffs) else None
        return _proved(q, a, cap - a)
    r = min(real)
    for top in (r * (1 + 1e-9), r * (1 - 1e-9)):  # the root itself when it is short and rational, else below it
        if not top > 0:
            return None
        start = float_hint(a)
        short = _short_float(start + top * 63 / 64, start + top)
        span = (short - a) if short is not None and short > a else _short_end(a, Fraction(top)) - a
        if cap is not None and cap - a < span:
            span = cap - a
        end = _proved(q, a, span)
        if end is not None:
            return end
    return None


def _decreasing_root(q: flint.fmpq_poly) -> list[float] | None:
    """The one positive root of a q that decreases on [0, oo) with q(0) > 0 (:func:`_decreasing`), by Newton's
    method in floats from the right (q is concave there, so the iterates fall monotonically onto the root):
    [] when q is constant, None when floats fail (a hint; never raises)."""
    try:
        c = float_hints(q.coeffs()).tolist()
        if len(c) < 2:
            return []
        if not all(math.isfinite(v) for v in c) or not c[0] > 0:
            return None
        x = 1.0
        while _horner(c, x) > 0:  # a point right of the root
            x *= 2
            if x > 1e300:
                return None
        for _ in range(100):
            f = _horner(c, x)
            df = _horner([k * v for k, v in enumerate(c)][1:], x)
            if not (math.isfinite(f) and math.isfinite(df)) or df >= 0:
                return None
            step = f / df
            x -= step
            if abs(step) <= 1e-15 * abs(x):
                break
        return [x] if x > 0 and math.isfinite(x) else None
    except Exception:  # noqa: BLE001 -- a hint never raises: it only fails to help
        return None


def _horner(c: list[float], x: float) -> float:
    out = 0.0
    for v in reversed(c):
        out = out * x + v
    return out


def _float_roots(q: flint.fmpq_poly) -> list[float] | None:
    """The positive real roots of q in floats (a hint: None when floats fail; never raises)."""
    try:
        with np.errstate(all="ignore"):
            c = float_hints(q.coeffs())
            if len(c) < 2:
                return [] if np.all(np.isfinite(c)) else None
            if not np.all(np.isfinite(c)) or c[-1] == 0:
                return None
            roots = np.polynomial.polynomial.polyroots(c / np.abs(c).max())
            if not np.all(np.isfinite(roots)):
                return None
            return [r.real.item() for r in roots if abs(r.imag) <= 1e-7 * (1.0 + abs(r.real)) and r.real > 0]
    except Exception:  # noqa: BLE001 -- a hint never raises: it only fails to help
        return None


def _proved(q: flint.fmpq_poly, a: Fraction, span: Fraction) -> Fraction | None:
    """a + span when q(a + s) >= 0 on [0, span] is proved (q(0) > 0 is known): q(span) >= 0 and Descartes' rule
    sees no root in (0, span); else None."""
    if not span > 0 or not q(fmpq_of(span)) >= 0:
        return None
    if _decreasing(q) or no_root_between(q, _ZERO_Q, span):
        return a + span
    return None


def _decreasing(q: flint.fmpq_poly) -> bool:
    """True when every coefficient of q beyond the constant one is <= 0: then q decreases on [0, oo), so
    q(span) >= 0 gives q >= 0 on all of [0, span] (the common case: b >= 0, D = 1, every b^T y_k >= 0)."""
    return all(c <= _ZERO for c in q.coeffs()[1:])
